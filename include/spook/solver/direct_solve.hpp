#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <spook/solver/body_space_solve.hpp>
#include <spook/solver/free_set_update.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/iterative_solve.hpp>
#include <spook/solver/solver.hpp>

namespace spook::detail {

/// What a direct solve did.
struct DirectSolveResult {
  int factorizations = 0;  ///< sparse LDLᵀ factorizations (one per pivot step)
  bool converged = true;   ///< a complementary solution was found
  bool fellBack = false;   ///< the pivoting gave up (the safe fallback answered, if asked for)
  double work = 0.0;       ///< multiply-adds of its factorizations, as analyzed
};

/// Eigen's sparse LDLᵀ, with the cost of a factorization known from the
/// symbolic analysis: about n + Σ c_j² multiply-adds over L's column counts
/// c_j below the diagonal (Davis, Direct Methods for Sparse Linear Systems,
/// 2006, §4.7).
class AnalyzedLDLT : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> {
 public:
  /// After analyzePattern().
  [[nodiscard]] double factorizationWork() const {
    const int* outer = m_matrix.outerIndexPtr();
    auto work = static_cast<double>(m_matrix.cols());
    for (Eigen::Index j = 0; j < m_matrix.cols(); ++j) {
      const auto c = static_cast<double>(outer[j + 1] - outer[j]);
      work += c * c;
    }
    return work;
  }

  /// About how many solves with the factor one factorization costs (a
  /// solve: 2 Σ c_j + n).
  [[nodiscard]] double solvesPerFactorization() const {
    const auto n = static_cast<double>(m_matrix.cols());
    return factorizationWork() / (2.0 * static_cast<double>(m_matrix.outerIndexPtr()[m_matrix.cols()]) + n);
  }
};

/// Solves the rows `subset` of an island exactly, the impulses of the other
/// rows held fixed: (S + Σ)_DD Λ_D = q_D − (S Λ)_D,fixed within the bounds.
///
/// S + Σ is assembled in block-sparse form (a row couples only to the rows
/// sharing one of its bodies) and factorized by a sparse LDLᵀ with an
/// approximate-minimum-degree ordering, so a chain or a tree of n bodies costs
/// O(n); the ordering is computed once per sparsity pattern, which the
/// pivot steps keep (a clamped row becomes an identity row) and so do steps
/// whose rows couple the same bodies. Σ > 0 keeps the matrix positive
/// definite. Where rows far outnumber the bodies' degrees of freedom and all
/// are compliant (contacts), the same system is solved through the bodies'
/// mass matrix instead (body_space_solve.hpp).
///
/// Bounded rows make a box-constrained LCP, solved by block principal
/// pivoting (Júdice & Pires 1994): every row is free, at its lower or at its
/// upper bound; each step solves the free rows with the others at their
/// bounds and swaps every infeasible row at once. Swapping them all can
/// cycle (the infeasible count repeated 30 30 34 35 37 32 on a 210-cube
/// pyramid in float until the cap): a step that does not reach a new
/// fewest-infeasible count swaps only a pseudo-random half of them (a hash
/// of the step and the row, so that runs repeat bit for bit), which breaks
/// such cycles. When the count has not improved for kBlockPivotingStrikes
/// steps, the solve turns into a descent that cannot cycle, from the best
/// (lowest merit, below) of the best iterate, the rows' starting impulses
/// and no impulse. It lowers f(Λ) = ½ΛᵀAΛ − qᵀΛ over the bounds, whose
/// minimum is the LCP's solution (A = S + Σ symmetric positive definite):
/// projected Gauss–Seidel sweeps, which never raise f, find a face (the
/// rows they leave at a bound), and the exact minimum of f on that face
/// (one factorization), projected onto the bounds, is taken where it
/// lowers f, its step halved until it does, as in projected Gauss–Seidel
/// subspace minimization (Silcowitz, Niebe & Erleben, GRAPP 2010; Moré &
/// Toraldo, SIAM J. Optim. 1(1), 1991, for the projected search). Once the
/// sweeps find the solution's face, the face step solves the LCP exactly.
/// (Murty's single pivots, used before, cannot cycle in exact arithmetic
/// but swap one row per step: the 1,600 normals of a 210-cube brick
/// pyramid in float, their friction held at its warm start, still had 9 to
/// 20 infeasible rows after 80 steps; Bertsekas' projected Newton, tried
/// there, took steps of 1/64 and less.) Should the step cap be reached,
/// the solve falls back to a safe answer: of the clamped best iterate (or
/// the descent's), the rows' starting impulses and no impulse at all, the
/// one of lowest f (f(Λ) − f(0) bounds the kinetic energy the impulses
/// add), refined by projected Gauss–Seidel. The solve is reported as not
/// converged. A solve is also given a budget of work (multiply-adds of its
/// factorizations, as the symbolic analysis counts them, and in row space
/// Solver::kDirectRowWork a row for each pivot step): it takes only the
/// pivot steps the budget affords, and where it cannot afford one
/// factorization (a pile of a thousand spheres, whose matrix fills in like
/// a 3D mesh's), it falls back to the safe answer at once. The cost of a
/// step is then bounded whatever the scene.
class DirectSolve {
 public:
  // It points into its own analyses (analyzed_).
  DirectSolve(const DirectSolve&) = delete;
  DirectSolve& operator=(const DirectSolve&) = delete;

  /// Gauss–Seidel sweeps of the fallback.
  static constexpr int kFallbackSweeps = 64;

  /// A row is infeasible when it leaves its bounds, or its residual has the
  /// wrong sign, by more than this fraction of the island's largest impulse
  /// or right-hand side. The solve's round-off is relative to those, not to
  /// each row's own: with a tolerance of 1e-12 of each row's magnitude,
  /// rows of a 210-cube pyramid flipped on residuals of 1e-10 of the
  /// largest and the pivoting cycled to its cap.
  static constexpr double kRoundOff = 1e-10;

  /// Block pivoting steps allowed without a new fewest-infeasible count
  /// before the descent. The pivoting's random halves still find answers
  /// late that the descent, paced by its sweeps, reaches slowly: at 10, the
  /// 210 x 1 kg float brick pyramid under the direct policy fell back on
  /// 145 of 300 steps (none at 30).
  static constexpr int kBlockPivotingStrikes = 30;

  /// Projected Gauss–Seidel sweeps before each subspace step of the descent.
  static constexpr int kDescentSweeps = 4;

  /// Halvings of the descent's subspace step before it is given up for
  /// that step (the sweeps alone then lower f).
  static constexpr int kLineSearchHalvings = 8;

  DirectSolve() = default;
  /// A solve that turns to the descent after `blockPivotingStrikes` steps
  /// without a new fewest-infeasible count (0: after the first step).
  explicit DirectSolve(int blockPivotingStrikes) : strikesAllowed_(blockPivotingStrikes) {}

  /// `safeAnswer`: at the cap, leave the fallback's answer (else the rows'
  /// impulses are left as they were, for a caller that restores them).
  /// `maxWork`: the multiply-adds its factorizations may take in all.
  /// `sameMatrix`: the rows' Jacobians, masses and Σ are those of the last
  /// solve if it was of the same problem object (only impulses and bounds
  /// changed since: the friction iterations and coupling passes of one
  /// island's solve), whose matrix then stands; its rows are compared.
  DirectSolveResult solve(IslandProblem& problem, const std::vector<int>& subset, int maxPivotSteps,
                          bool safeAnswer = true, double maxWork = std::numeric_limits<double>::infinity(),
                          bool sameMatrix = false) {
    DirectSolveResult result;
    const int n = static_cast<int>(subset.size());
    if (n == 0) return result;
    const bool assembled = sameMatrix && assembledFor_ == &problem && assembledRows_ == subset;
    if (!assembled) bodySpace_ = BodySpaceSolve::pays(problem, subset);
    assembleRhs(problem, subset);
    if (!assembled) {
      if (bodySpace_)
        bodySpaceSolve_.analyze(problem, subset);
      else
        assembleMatrix(problem, subset);
      assembledFor_ = &problem;
      assembledRows_ = subset;
    }
    // A pivot step's rows count in row space; in body space the factor of
    // 6x6 blocks outweighs them (a settling pile of 1,000 spheres: ~1.4e7
    // multiply-adds against 1.3e6).
    const double work = bodySpace_ ? bodySpaceSolve_.factorizationWork()
                                   : analyzed_->ldlt->factorizationWork() + Solver::kDirectRowWork * n;
    // A solve capped at m pivot steps factorizes up to m + 1 times.
    if (maxWork < work * (static_cast<double>(maxPivotSteps) + 1.0))
      maxPivotSteps = static_cast<int>(std::floor(maxWork / work)) - 1;
    if (maxPivotSteps < 0) {
      if (safeAnswer) fallBack(problem, subset, startingImpulses(problem, subset));
      result.converged = false;
      result.fellBack = true;
      return result;
    }

    // The state of each row: free, or clamped at its lower or upper bound.
    // Warm start: a row whose guess (the last solution) is at a bound starts there.
    std::vector<State> state(static_cast<std::size_t>(n), FREE);
    bool anyBounded = false;
    for (int k = 0; k < n; ++k) {
      const auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
      if (!isBounded(e)) continue;
      anyBounded = true;
      if (e.guess <= e.lower) state[static_cast<std::size_t>(k)] = LOWER;
      else if (e.guess >= e.upper) state[static_cast<std::size_t>(k)] = UPPER;
    }

    const double tolW = kRoundOff * (q_.cwiseAbs().maxCoeff() + std::numeric_limits<double>::min());
    Eigen::VectorXd x(n), bestX;
    int best = std::numeric_limits<int>::max();
    int strikes = 0;
    std::vector<int> infeasible;
    for (int step = 0;; ++step) {
      solveFree(problem, subset, state, x);
      ++result.factorizations;
      if (!anyBounded) break;
      const Eigen::VectorXd w = residual(problem, subset, x);
      const double tolX = kRoundOff * (x.cwiseAbs().maxCoeff() + std::numeric_limits<double>::min());
      infeasible.clear();
      for (int k = 0; k < n; ++k) {
        const auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
        const State s = state[static_cast<std::size_t>(k)];
        if (e.upper <= e.lower) continue;  // a zero-width box: held at its bound from the start
        if ((s == FREE && (x[k] < e.lower - tolX || x[k] > e.upper + tolX)) || (s == LOWER && w[k] < -tolW) ||
            (s == UPPER && w[k] > tolW))
          infeasible.push_back(k);
      }
      if (infeasible.empty()) break;
      const int count = static_cast<int>(infeasible.size());
      if (count < best) {
        best = count;
        bestX = x;
        strikes = 0;
      } else {
        ++strikes;
      }
      if (step >= maxPivotSteps || strikes >= strikesAllowed_) {
        if (step < maxPivotSteps) {
          x = bestOfStarts(problem, subset, bestX);
          if (descend(problem, subset, x, maxPivotSteps - step, result.factorizations)) break;
          bestX = x;
        }
        if (safeAnswer) fallBack(problem, subset, bestX);
        result.converged = false;
        result.fellBack = true;
        result.work = work * result.factorizations;
        return result;
      }
      if (strikes > 0) keepRandomHalf(infeasible, step);
      for (int k : infeasible) {
        const auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
        State& s = state[static_cast<std::size_t>(k)];
        if (s != FREE) s = FREE;
        else s = x[k] < e.lower ? LOWER : UPPER;
      }
    }
    for (int k = 0; k < n; ++k) {
      auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
      e.impulse = std::clamp(x[k], e.lower, e.upper);
      e.guess = e.impulse;
    }
    result.work = work * result.factorizations;
    return result;
  }

 private:
  /// A row's place in a pivot step: free, or held at its lower or upper bound.
  enum State : unsigned char { FREE, LOWER, UPPER };

  // f(Λ) = ½ΛᵀAΛ − qᵀΛ = ½Λᵀ(w − q), w = AΛ − q.
  double merit(const IslandProblem& problem, const std::vector<int>& subset, const Eigen::VectorXd& x) const {
    return merit(x, residual(problem, subset, x));
  }
  // f from x and its residual w, where the caller has w already.
  double merit(const Eigen::VectorXd& x, const Eigen::VectorXd& w) const { return 0.5 * x.dot(w - q_); }

  // Of x (clamped), the rows' impulses as the solve found them and no
  // impulse, the one of lowest f.
  Eigen::VectorXd bestOfStarts(const IslandProblem& problem, const std::vector<int>& subset, Eigen::VectorXd x) const {
    const auto n = static_cast<Eigen::Index>(subset.size());
    Eigen::VectorXd none(n), start(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
      x[k] = std::clamp(x[k], e.lower, e.upper);
      none[k] = std::clamp(0.0, e.lower, e.upper);
      start[k] = std::clamp(e.impulse, e.lower, e.upper);
    }
    double fx = merit(problem, subset, x);
    if (!std::isfinite(fx)) fx = std::numeric_limits<double>::infinity();
    for (const Eigen::VectorXd* candidate : {&start, &none})
      if (const double f = merit(problem, subset, *candidate); f < fx) {
        x = *candidate;
        fx = f;
      }
    return x;
  }

  // The monotone descent of the class note from a feasible x, at most
  // maxSteps factorizations: true when x passes the pivoting's test (each
  // row free within its bounds with w = 0, or at a bound w pushes against).
  bool descend(const IslandProblem& problem, const std::vector<int>& subset, Eigen::VectorXd& x, int maxSteps,
               int& factorizations) {
    const int n = static_cast<int>(subset.size());
    const double tolW = kRoundOff * (q_.cwiseAbs().maxCoeff() + std::numeric_limits<double>::min());
    const auto entry = [&](int k) -> const IslandProblem::Entry& {
      return problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
    };
    const auto solved = [&](const Eigen::VectorXd& y, const Eigen::VectorXd& w) {
      for (int k = 0; k < n; ++k) {
        const auto& e = entry(k);
        if (e.upper <= e.lower) continue;
        const bool atLower = y[k] <= e.lower, atUpper = y[k] >= e.upper;
        if ((atLower && w[k] < -tolW) || (atUpper && w[k] > tolW) || (!atLower && !atUpper && std::abs(w[k]) > tolW))
          return false;
      }
      return true;
    };
    std::vector<State> state(static_cast<std::size_t>(n));
    Eigen::VectorXd target(n), trial(n), w;
    for (int step = 0; step < maxSteps;) {
      sweep(problem, subset, x, kDescentSweeps);
      w = residual(problem, subset, x);
      if (solved(x, w)) return true;
      const double f = merit(x, w);
      for (int k = 0; k < n; ++k) {
        const auto& e = entry(k);
        state[static_cast<std::size_t>(k)] = x[k] <= e.lower ? LOWER : x[k] >= e.upper ? UPPER : FREE;
      }
      // The minimum of f on the face the sweeps found, projected onto the
      // bounds; the step is halved until f decreases.
      target = x;
      solveFree(problem, subset, state, target);
      ++factorizations;
      ++step;
      double alpha = 1.0;
      for (int halving = 0; halving < kLineSearchHalvings; ++halving, alpha *= 0.5) {
        for (int k = 0; k < n; ++k) trial[k] = std::clamp(x[k] + alpha * (target[k] - x[k]), entry(k).lower, entry(k).upper);
        w = residual(problem, subset, trial);
        if (merit(trial, w) < f) {
          x = trial;
          if (solved(x, w)) return true;
          break;
        }
      }
    }
    return false;
  }

  // Projected Gauss–Seidel sweeps on the rows' box LCP (their bounds held
  // fixed), in place: each row's update minimizes f along it, so f never rises.
  // Not gaussSeidelSolve (iterative_solve.hpp), which moves friction bounds
  // with the normals' impulses: the descent's monotonicity needs fixed ones.
  void sweep(const IslandProblem& problem, const std::vector<int>& subset, Eigen::VectorXd& x, int sweeps) const {
    std::vector<Vec6d> dv(static_cast<std::size_t>(problem.numBodies), Vec6d::Zero());
    for (std::size_t k = 0; k < subset.size(); ++k) problem.addImpulse(dv, subset[k], x[static_cast<Eigen::Index>(k)]);
    for (int s = 0; s < sweeps; ++s)
      for (std::size_t k = 0; k < subset.size(); ++k) {
        const int i = subset[k];
        const auto& e = problem.rows[static_cast<std::size_t>(i)];
        if (!(e.diagonal > 0.0)) continue;
        const auto j = static_cast<Eigen::Index>(k);
        const double w = problem.rowVelocity(i, dv) + e.sigma * x[j] - q_[j];
        const double next = std::clamp(x[j] - w / e.diagonal, e.lower, e.upper);
        problem.addImpulse(dv, i, next - x[j]);
        x[j] = next;
      }
  }

  static Eigen::VectorXd startingImpulses(const IslandProblem& problem, const std::vector<int>& subset) {
    Eigen::VectorXd x(static_cast<Eigen::Index>(subset.size()));
    for (std::size_t k = 0; k < subset.size(); ++k)
      x[static_cast<Eigen::Index>(k)] = problem.rows[static_cast<std::size_t>(subset[k])].impulse;
    return x;
  }

  // The safe answer of a solve whose pivoting gave up (see the class note).
  void fallBack(IslandProblem& problem, const std::vector<int>& subset, const Eigen::VectorXd& best) {
    const Eigen::VectorXd x = bestOfStarts(problem, subset, best);
    for (std::size_t k = 0; k < subset.size(); ++k)
      problem.rows[static_cast<std::size_t>(subset[k])].impulse = x[static_cast<Eigen::Index>(k)];
    iterativeSolve(problem, subset, kFallbackSweeps, 0.0, false);
    for (int i : subset) problem.rows[static_cast<std::size_t>(i)].guess = problem.rows[static_cast<std::size_t>(i)].impulse;
  }

  // Keeps about half of the rows, chosen by a hash of (step, row): at least one.
  static void keepRandomHalf(std::vector<int>& rows, int step) {
    std::size_t kept = 0;
    for (const int k : rows) {
      std::uint64_t h = (static_cast<std::uint64_t>(step) * 0x9E3779B97F4A7C15ull) ^
                        (static_cast<std::uint64_t>(k) * 0xC2B2AE3D27D4EB4Full);
      h ^= h >> 29;
      h *= 0xBF58476D1CE4E5B9ull;
      h ^= h >> 32;
      if (h & 1u) rows[kept++] = k;
    }
    rows.resize(std::max<std::size_t>(kept, 1));
  }

  static bool isBounded(const IslandProblem::Entry& e) {
    return e.lower > -std::numeric_limits<double>::infinity() || e.upper < std::numeric_limits<double>::infinity();
  }

  // q_ = q_D − G_D Δv(rows outside D).
  void assembleRhs(const IslandProblem& problem, const std::vector<int>& subset) {
    std::vector<char> inSubset(problem.rows.size(), 0);
    for (int i : subset) inSubset[static_cast<std::size_t>(i)] = 1;
    std::vector<int> others;
    for (int i = 0; i < static_cast<int>(problem.rows.size()); ++i)
      if (!inSubset[static_cast<std::size_t>(i)]) others.push_back(i);
    const std::vector<Vec6d> fixed = problem.velocityChange(others);
    q_.resize(static_cast<Eigen::Index>(subset.size()));
    for (std::size_t k = 0; k < subset.size(); ++k)
      q_[static_cast<Eigen::Index>(k)] = problem.rows[static_cast<std::size_t>(subset[k])].q - problem.rowVelocity(subset[k], fixed);
  }

  // w = (S + Σ)_DD x − q_D.
  Eigen::VectorXd residual(const IslandProblem& problem, const std::vector<int>& subset, const Eigen::VectorXd& x) const {
    if (!bodySpace_) return A_ * x - q_;
    std::vector<Vec6d> dv(static_cast<std::size_t>(problem.numBodies), Vec6d::Zero());
    for (std::size_t k = 0; k < subset.size(); ++k) problem.addImpulse(dv, subset[k], x[static_cast<Eigen::Index>(k)]);
    Eigen::VectorXd w(x.size());
    for (std::size_t k = 0; k < subset.size(); ++k) {
      const auto& e = problem.rows[static_cast<std::size_t>(subset[k])];
      const auto j = static_cast<Eigen::Index>(k);
      w[j] = problem.rowVelocity(subset[k], dv) + e.sigma * x[j] - q_[j];
    }
    return w;
  }

  // A_ = (S + Σ)_DD, full symmetric, and lower_, its lower triangle, both
  // written column by column in compressed form: through triplets, their
  // sort and the copy of the triangle took a sixth of a 10-cube stack's
  // hybrid step.
  void assembleMatrix(const IslandProblem& problem, const std::vector<int>& subset) {
    const int n = static_cast<int>(subset.size());
    const auto numBodies = static_cast<std::size_t>(problem.numBodies);
    // The rows on each body: rowsOfBody_[rowsOfBodyStart_[b], rowsOfBodyStart_[b + 1]).
    rowsOfBodyStart_.assign(numBodies + 1, 0);
    for (int k = 0; k < n; ++k)
      problem.forEachBody(problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])],
                          [&](int body, const Vec6d&, const Vec6d&) { ++rowsOfBodyStart_[std::size_t(body) + 1]; });
    for (std::size_t b = 0; b < numBodies; ++b) rowsOfBodyStart_[b + 1] += rowsOfBodyStart_[b];
    rowsOfBody_.resize(rowsOfBodyStart_.back());
    fill_.assign(rowsOfBodyStart_.begin(), rowsOfBodyStart_.end() - 1);
    for (int k = 0; k < n; ++k)
      problem.forEachBody(problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])],
                          [&](int body, const Vec6d&, const Vec6d&) { rowsOfBody_[fill_[std::size_t(body)]++] = k; });

    // Each row's couplings to the rows after it, in order: below_[belowStart_[k], belowStart_[k + 1]).
    // Two rows sharing both bodies meet twice and coupling() already sums
    // both, so each pair is taken once.
    below_.clear();
    belowStart_.assign(static_cast<std::size_t>(n) + 1, 0);
    above_.assign(static_cast<std::size_t>(n), 0);
    lastSeen_.assign(static_cast<std::size_t>(n), -1);
    for (int k = 0; k < n; ++k) {
      const int i = subset[static_cast<std::size_t>(k)];
      problem.forEachBody(problem.rows[static_cast<std::size_t>(i)], [&](int body, const Vec6d&, const Vec6d&) {
        for (std::size_t p = rowsOfBodyStart_[std::size_t(body)]; p < rowsOfBodyStart_[std::size_t(body) + 1]; ++p) {
          const int m = rowsOfBody_[p];
          if (m <= k || lastSeen_[static_cast<std::size_t>(m)] == k) continue;
          lastSeen_[static_cast<std::size_t>(m)] = k;
          const double s = problem.coupling(i, subset[static_cast<std::size_t>(m)]);
          if (s == 0.0) continue;
          below_.push_back({m, s});
          ++above_[static_cast<std::size_t>(m)];
        }
      });
      belowStart_[static_cast<std::size_t>(k) + 1] = below_.size();
      std::sort(below_.begin() + std::ptrdiff_t(belowStart_[static_cast<std::size_t>(k)]), below_.end(),
                [](const Coupling& x, const Coupling& y) { return x.row < y.row; });
    }

    const auto offDiagonal = static_cast<Eigen::Index>(below_.size());
    A_.resize(n, n);
    A_.resizeNonZeros(n + 2 * offDiagonal);
    lower_.resize(n, n);
    lower_.resizeNonZeros(n + offDiagonal);
    int* outerA = A_.outerIndexPtr();
    int* outerL = lower_.outerIndexPtr();
    outerA[0] = outerL[0] = 0;
    for (int k = 0; k < n; ++k) {
      const auto count = static_cast<int>(belowStart_[std::size_t(k) + 1] - belowStart_[std::size_t(k)]);
      outerA[k + 1] = outerA[k] + above_[static_cast<std::size_t>(k)] + 1 + count;
      outerL[k + 1] = outerL[k] + 1 + count;
    }
    // Column k of A_: the rows before k (written as their own columns were,
    // in ascending order), the diagonal, the rows after k.
    int* innerA = A_.innerIndexPtr();
    double* valueA = A_.valuePtr();
    int* innerL = lower_.innerIndexPtr();
    double* valueL = lower_.valuePtr();
    cursor_.assign(outerA, outerA + n);
    for (int k = 0; k < n; ++k) {
      const double diagonal = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])].diagonal;
      int& at = cursor_[static_cast<std::size_t>(k)];
      int atL = outerL[k];
      innerA[at] = innerL[atL] = k;
      valueA[at++] = valueL[atL++] = diagonal;
      for (std::size_t p = belowStart_[std::size_t(k)]; p < belowStart_[std::size_t(k) + 1]; ++p) {
        const Coupling& c = below_[p];
        innerA[at] = innerL[atL] = c.row;
        valueA[at++] = valueL[atL++] = c.value;
        int& upper = cursor_[static_cast<std::size_t>(c.row)];
        innerA[upper] = k;
        valueA[upper++] = c.value;
      }
    }
    // Its lower triangle, factorized at each pivot step (solveFree); the
    // ordering and elimination tree are computed once per pattern: kept from
    // step to step (a chain's joints keep theirs), and for the last
    // kAnalyzedPatterns patterns, which islands solved one after another by
    // the same solver take in turn (20 stacks of 10 cubes ordered 16
    // patterns a step anew, 6% of the step).
    lowerValues_.assign(lower_.valuePtr(), lower_.valuePtr() + lower_.nonZeros());
    const auto columns = static_cast<std::size_t>(n) + 1, entries = static_cast<std::size_t>(lower_.nonZeros());
    const auto holds = [&](const AnalyzedPattern& a) {
      return a.outer.size() == columns && a.inner.size() == entries &&
             std::equal(a.outer.begin(), a.outer.end(), lower_.outerIndexPtr()) &&
             std::equal(a.inner.begin(), a.inner.end(), lower_.innerIndexPtr());
    };
    ++patternClock_;
    if (analyzed_ && holds(*analyzed_)) {
      analyzed_->lastUse = patternClock_;
      return;
    }
    // Another pattern: the factor in hand is not of this matrix.
    factoredBase_.clear();
    update_.clear();
    analyzed_ = &large_;
    if (entries <= kPatternEntriesKept) {
      for (AnalyzedPattern& a : patterns_)
        if (holds(a)) {
          analyzed_ = &a;
          a.lastUse = patternClock_;
          return;
        }
      if (patterns_.size() < kAnalyzedPatterns) {
        if (patterns_.empty()) patterns_.reserve(kAnalyzedPatterns);
        analyzed_ = &patterns_.emplace_back();
      } else {
        analyzed_ = &*std::min_element(
            patterns_.begin(), patterns_.end(),
            [](const AnalyzedPattern& a, const AnalyzedPattern& b) { return a.lastUse < b.lastUse; });
      }
    }
    analyzed_->ldlt->analyzePattern(lower_);
    analyzed_->outer.assign(lower_.outerIndexPtr(), lower_.outerIndexPtr() + columns);
    analyzed_->inner.assign(lower_.innerIndexPtr(), lower_.innerIndexPtr() + entries);
    analyzed_->lastUse = patternClock_;
  }

  // Solves the free rows with the others at their bounds, or where
  // `heldAtBounds` is false, at their impulses in x.
  void solveFree(const IslandProblem& problem, const std::vector<int>& subset, const std::vector<State>& state,
                 Eigen::VectorXd& x, bool heldAtBounds = true) {
    const int n = static_cast<int>(subset.size());
    std::vector<int> freeIndex(static_cast<std::size_t>(n), -1);
    int numFree = 0;
    for (int k = 0; k < n; ++k) {
      const auto& e = problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])];
      if (state[static_cast<std::size_t>(k)] == FREE)
        freeIndex[static_cast<std::size_t>(k)] = numFree++;
      else if (heldAtBounds)
        x[k] = state[static_cast<std::size_t>(k)] == LOWER ? e.lower : e.upper;
    }
    if (numFree == 0) return;
    Eigen::VectorXd rhs(numFree);
    for (int k = 0; k < n; ++k)
      if (freeIndex[static_cast<std::size_t>(k)] >= 0) rhs[freeIndex[static_cast<std::size_t>(k)]] = q_[k];
    if (bodySpace_) {
      std::vector<Vec6d> clamped(static_cast<std::size_t>(problem.numBodies), Vec6d::Zero());
      for (int k = 0; k < n; ++k)
        if (freeIndex[static_cast<std::size_t>(k)] < 0) problem.addImpulse(clamped, subset[static_cast<std::size_t>(k)], x[k]);
      for (int k = 0; k < n; ++k)
        if (const int f = freeIndex[static_cast<std::size_t>(k)]; f >= 0)
          rhs[f] -= problem.rowVelocity(subset[static_cast<std::size_t>(k)], clamped);
      if (bodySpaceSolve_.factorize(problem, subset, freeIndex)) {
        bodySpaceSolve_.solve(problem, subset, freeIndex, rhs, x);
        // An updated factor must reach the refinement's residual; it
        // factorizes where it does not.
        if (refineInBodySpace(problem, subset, freeIndex, rhs, x) || !bodySpaceSolve_.updated()) return;
        if (bodySpaceSolve_.factorize(problem, subset, freeIndex, /*allowUpdate=*/false)) {
          bodySpaceSolve_.solve(problem, subset, freeIndex, rhs, x);
          refineInBodySpace(problem, subset, freeIndex, rhs, x);
          return;
        }
      }
      // Round-off left K indefinite: this solve continues in row space.
      bodySpace_ = false;
      assembleMatrix(problem, subset);
      for (int k = 0; k < n; ++k)
        if (const int f = freeIndex[static_cast<std::size_t>(k)]; f >= 0) rhs[f] = q_[k];
    }
    // The clamped rows and columns of (S + Σ)_DD become the identity's (and
    // their right-hand side zero), which keeps the matrix's pattern, and
    // with it the symbolic analysis of assembleMatrix, for every pivot step.
    Eigen::VectorXd full = Eigen::VectorXd::Zero(n);
    for (int k = 0; k < n; ++k)
      if (const int f = freeIndex[static_cast<std::size_t>(k)]; f >= 0) full[k] = rhs[f];
    const int* outer = lower_.outerIndexPtr();
    const int* inner = lower_.innerIndexPtr();
    double* value = lower_.valuePtr();
    for (int col = 0; col < n; ++col) {
      const bool freeCol = freeIndex[static_cast<std::size_t>(col)] >= 0;
      for (int p = outer[col]; p < outer[col + 1]; ++p) {
        const int row = inner[p];
        const double a = lowerValues_[static_cast<std::size_t>(p)];
        const bool freeRow = freeIndex[static_cast<std::size_t>(row)] >= 0;
        if (row == col) {
          value[p] = freeCol ? a : 1.0;
        } else if (freeRow && freeCol) {
          value[p] = a;
        } else {
          value[p] = 0.0;
          if (freeRow) full[row] -= a * x[col];
          else if (freeCol) full[col] -= a * x[row];
        }
      }
    }
    // The hybrid's coupling passes start where the last pass ended: the
    // same matrix (same rows, same free set), whose factor the pattern's ldlt still
    // holds. A pivot step that changed a few rows of it is solved with that
    // factor (free_set_update.hpp).
    const bool sameRows = !factoredBase_.empty() && factoredBase_ == lowerValues_;
    Eigen::VectorXd solution;
    if (sameRows && update_.isFactorized(freeIndex)) {
      solution = analyzed_->ldlt->solve(full);
    } else if (!sameRows || solvesPerFactorization_ < kUpdateWorthSolves ||
               !update_.solve(
                   A_, lower_, freeIndex, full, kRefinedResidual * full.cwiseAbs().maxCoeff(),
                   [this](const Eigen::VectorXd& v) { return Eigen::VectorXd(analyzed_->ldlt->solve(v)); }, solution)) {
      analyzed_->ldlt->factorize(lower_);
      factoredBase_ = lowerValues_;
      update_.reset(freeIndex);
      solvesPerFactorization_ = analyzed_->ldlt->solvesPerFactorization();
      solution = analyzed_->ldlt->solve(full);
    }
    for (int k = 0; k < n; ++k)
      if (freeIndex[static_cast<std::size_t>(k)] >= 0) x[k] = solution[k];
  }

  // Iterative refinement of the free rows' body-space solution x of
  // (S + Σ)_FF x_F = r (Wilkinson 1963; Higham, Accuracy and Stability of
  // Numerical Algorithms, ch. 12): the residual in row space, solved again
  // with the same factorization, corrects x by as many digits as the body
  // space lost, while the residual shrinks (at most kRefinements passes),
  // down to kRefinedResidual of the largest right-hand side: a hundredth of
  // the pivoting's tolerance (kRoundOff), below which no feasibility
  // decision changes (refining to 1e-15 cost a 10-cube stack 7-12% of its
  // step and changed no pyramid's drift or fallbacks). True where the
  // residual reached that.
  bool refineInBodySpace(const IslandProblem& problem, const std::vector<int>& subset,
                         const std::vector<int>& freeIndex, const Eigen::VectorXd& rhs, Eigen::VectorXd& x) {
    const int n = static_cast<int>(subset.size());
    Eigen::VectorXd rho(rhs.size()), dx(n);
    const auto residualNorm = [&] {
      std::vector<Vec6d> dv(static_cast<std::size_t>(problem.numBodies), Vec6d::Zero());
      for (int k = 0; k < n; ++k)
        if (freeIndex[static_cast<std::size_t>(k)] >= 0) problem.addImpulse(dv, subset[static_cast<std::size_t>(k)], x[k]);
      for (int k = 0; k < n; ++k)
        if (const int f = freeIndex[static_cast<std::size_t>(k)]; f >= 0) {
          const int i = subset[static_cast<std::size_t>(k)];
          rho[f] = rhs[f] - problem.rowVelocity(i, dv) - problem.rows[static_cast<std::size_t>(i)].sigma * x[k];
        }
      return rho.cwiseAbs().maxCoeff();
    };
    const double enough = kRefinedResidual * rhs.cwiseAbs().maxCoeff();
    double size = residualNorm();
    for (int pass = 0; pass < kRefinements && size > enough; ++pass) {
      const Eigen::VectorXd before = x;
      bodySpaceSolve_.solve(problem, subset, freeIndex, rho, dx);
      for (int k = 0; k < n; ++k)
        if (freeIndex[static_cast<std::size_t>(k)] >= 0) x[k] += dx[k];
      const double after = residualNorm();
      if (!(after < 0.5 * size)) {
        x = before;
        break;
      }
      size = after;
    }
    return size <= enough;
  }

  static constexpr int kRefinements = 4;
  /// The row-space factor serves other free sets (update_) where its
  /// factorization costs at least this many solves (as in body space,
  /// BodySpaceSolve::kUpdateWorthSolves).
  static constexpr double kUpdateWorthSolves = BodySpaceSolve::kUpdateWorthSolves;
  static constexpr double kRefinedResidual = 1e-2 * kRoundOff;

  int strikesAllowed_ = kBlockPivotingStrikes;
  const IslandProblem* assembledFor_ = nullptr;  ///< the problem and rows of the matrix in hand
  std::vector<int> assembledRows_;
  bool bodySpace_ = false;
  BodySpaceSolve bodySpaceSolve_;
  Eigen::SparseMatrix<double> A_, lower_;
  std::vector<double> lowerValues_;             ///< lower_'s values as assembled
  std::vector<double> factoredBase_;            ///< lowerValues_ when analyzed_'s factor was computed (none: empty)
  FreeSetUpdate update_;                        ///< that factor's free set, and solves of others with it
  double solvesPerFactorization_ = 0.0;         ///< of that factor
  Eigen::VectorXd q_;
  struct Coupling {
    int row;
    double value;
  };
  // assembleMatrix's scratch.
  std::vector<std::size_t> rowsOfBodyStart_, fill_, belowStart_;
  std::vector<int> rowsOfBody_, above_, lastSeen_, cursor_;
  std::vector<Coupling> below_;
  /// A sparsity pattern of lower_ and the factorization analyzed for it.
  struct AnalyzedPattern {
    std::vector<int> outer, inner;
    std::unique_ptr<AnalyzedLDLT> ldlt = std::make_unique<AnalyzedLDLT>();
    std::uint64_t lastUse = 0;
  };
  /// Patterns kept for the islands that take turns: the last
  /// kAnalyzedPatterns of at most kPatternEntriesKept entries each (a
  /// factor of a few hundred kB at most); a larger island's analysis
  /// is amortized by its factorization, and its pattern changes with its
  /// contacts: it has one slot of its own, analyzed again for each new one.
  static constexpr std::size_t kAnalyzedPatterns = 32;
  static constexpr std::size_t kPatternEntriesKept = 4096;
  std::vector<AnalyzedPattern> patterns_;  ///< reserved before the first: never moved
  AnalyzedPattern large_;
  AnalyzedPattern* analyzed_ = nullptr;  ///< lower_'s: its factor is the one factorized and solved with
  std::uint64_t patternClock_ = 0;
};

}  // namespace spook::detail
