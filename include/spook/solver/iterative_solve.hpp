#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <spook/core/geometric_growth.hpp>
#include <spook/solver/friction_bounds.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/small_dense.hpp>

namespace spook::detail {

/// What an iterative solve did.
struct IterativeSolveResult {
  int iterations = 0;     ///< sweeps over the rows
  double change = 0.0;    ///< largest |ΔΛ|·(S+Σ)_ii of the last sweep (m/s)
  bool converged = false; ///< `change` fell below the tolerance
};

/// The units a Gauss–Seidel sweep updates, in the order of `subset`: a
/// row, or a block of one constraint's consecutive unbounded rows (up to
/// six) solved together, ΔΛ_B = (S+Σ)_BB⁻¹ r_B (block Gauss–Seidel, as
/// Jolt's and Box2D's joint parts solve a joint). The rows of a joint
/// couple through its bodies' inverse inertia; for a point-like body on a
/// long arm that coupling is ~1e6 times a row's own mass and row-by-row
/// sweeps barely converge, while a block update is exact for the joint.
/// Each block's inverse is formed once per solve, padded to 6 × 6, so that
/// a sweep's update is one fixed-size product.
class RowBlocks {
 public:
  static constexpr int kMaxRows = 6;
  struct Unit {
    int first = 0;     ///< position in the subset of its first row
    int count = 1;     ///< rows in the unit; a block when > 1
    int inverse = -1;  ///< blocks: their inverse
  };

  /// Units of `subset`; all single rows unless `makeBlocks`.
  RowBlocks(const IslandProblem& problem, const std::vector<int>& subset, bool makeBlocks) {
    const auto blockable = [&](int i) {
      const auto& e = problem.rows[static_cast<std::size_t>(i)];
      return makeBlocks && e.constraint >= 0 && e.normal < 0 && !e.bounded();
    };
    for (std::size_t k = 0; k < subset.size();) {
      std::size_t end = k + 1;
      if (blockable(subset[k]))
        while (end < subset.size() && end - k < std::size_t(kMaxRows) && blockable(subset[end]) &&
               problem.rows[static_cast<std::size_t>(subset[end])].constraint ==
                   problem.rows[static_cast<std::size_t>(subset[k])].constraint)
          ++end;
      Unit unit{static_cast<int>(k), static_cast<int>(end - k), -1};
      if (unit.count > 1) {
        // Padded with the identity to 6 × 6: the padding's rows stay
        // decoupled (their residuals are zero).
        Mat6d A = Mat6d::Identity();
        for (int a = 0; a < unit.count; ++a)
          for (int b = 0; b <= a; ++b) {
            const int i = subset[k + std::size_t(a)], j = subset[k + std::size_t(b)];
            A(a, b) = a == b ? problem.rows[static_cast<std::size_t>(i)].diagonal : problem.coupling(i, j);
          }
        if (invertByCholesky<6>(A, A, unit.count)) {
          unit.inverse = static_cast<int>(inverses_.size());
          inverses_.push_back(A);
        } else {
          // Not positive definite to round-off: this row alone, and its
          // followers start the next block (which may fail again, ending
          // row by row).
          end = k + 1;
          unit.count = 1;
        }
      }
      units_.push_back(unit);
      k = end;
    }
  }

  [[nodiscard]] const std::vector<Unit>& units() const { return units_; }
  /// (S+Σ)_BB⁻¹ of a block in its count × count corner (identity beyond).
  [[nodiscard]] const Mat6d& inverse(const Unit& unit) const {
    return inverses_[static_cast<std::size_t>(unit.inverse)];
  }

 private:
  std::vector<Unit> units_;
  std::vector<Mat6d> inverses_;
};

/// A single row (not in a block) as the Gauss–Seidel sweeps read it: a copy
/// packed in sweep order, so that a sweep streams through memory, reads no
/// field it does not use and finds its normal's impulse and its cone
/// partner by position. The impulses (and followed bounds) go back to the
/// problem when the sweeps end.
struct SweepRow {
  enum class Kind : unsigned char { ROW, CONE_FIRST, CONE_SECOND };
  Vec6d J1 = Vec6d::Zero(), W1 = Vec6d::Zero(), J2 = Vec6d::Zero(), W2 = Vec6d::Zero();
  double q = 0.0, sigma = 0.0, diagonal = 0.0, lower = 0.0, upper = 0.0, impulse = 0.0;
  double mu = 0.0;           ///< rows following their normal: bounds ±μ max(0, Λn)
  double fixedNormal = 0.0;  ///< Λn of a normal that is not swept
  double a01 = 0.0;          ///< first row of a cone pair: (S+Σ) coupling with its partner
  /// 1/(S+Σ)ᵢᵢ; for the first row of a cone pair, 1/det of the pair's 2×2
  /// block. Multiplied, not divided, in the sweeps: a division's latency
  /// lies on the chain of updates through a body's velocity.
  double inverse = 0.0;
  int body1 = -1, body2 = -1, extra = -1;
  int row = -1;      ///< index in the problem
  int normal = -1;   ///< sweep position of its normal row; −1: not swept (or none)
  int partner = -1;  ///< first row of a cone pair: sweep position of the second
  bool follows = false;
  Kind kind = Kind::ROW;
};

SPOOK_ALWAYS_INLINE double sweptRowVelocity(const IslandProblem& problem, const SweepRow& s, const Vec6d* dv) {
  double v = 0.0;
  if (s.body1 >= 0) v += s.J1.dot(dv[s.body1]);
  if (s.body2 >= 0) v += s.J2.dot(dv[s.body2]);
  if (s.extra >= 0) {
    const IslandProblem::ExtraBody& x = problem.extraBodies[static_cast<std::size_t>(s.extra)];
    v += x.J.dot(dv[x.body]);
  }
  return v;
}

SPOOK_ALWAYS_INLINE void addSweptImpulse(const IslandProblem& problem, const SweepRow& s, Vec6d* dv, double d) {
  if (s.body1 >= 0) addScaled(dv[s.body1], s.W1, d);
  if (s.body2 >= 0) addScaled(dv[s.body2], s.W2, d);
  if (s.extra >= 0) {
    const IslandProblem::ExtraBody& x = problem.extraBodies[static_cast<std::size_t>(s.extra)];
    addScaled(dv[x.body], x.W, d);
  }
}

/// The single rows of `units` packed in unit order (SweepRow) into
/// `packed`; `swept` marks the problem's rows in the subset, `position`
/// is scratch.
inline void packSweepRows(const IslandProblem& problem, const std::vector<int>& subset,
                          const std::vector<RowBlocks::Unit>& units, const std::vector<char>& swept,
                          std::vector<SweepRow>& packed, std::vector<int>& position) {
  packed.clear();
  reserveGrowing(packed, units.size());
  assignGrowing(position, problem.rows.size(), -1);
  for (const RowBlocks::Unit& unit : units) {
    if (unit.count > 1) continue;
    const int i = subset[static_cast<std::size_t>(unit.first)];
    const IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(i)];
    SweepRow s;
    s.J1 = e.J1;
    s.W1 = e.W1;
    s.J2 = e.J2;
    s.W2 = e.W2;
    s.q = e.q;
    s.sigma = e.sigma;
    s.diagonal = e.diagonal;
    s.lower = e.lower;
    s.upper = e.upper;
    s.impulse = e.impulse;
    s.mu = e.mu;
    s.body1 = e.body1;
    s.body2 = e.body2;
    s.extra = e.extra;
    s.row = i;
    s.follows = e.followsNormal();
    if (e.frictionBound == FrictionBound::CONE && e.normal >= 0 && e.partner >= 0 &&
        swept[static_cast<std::size_t>(e.partner)]) {
      s.kind = e.partner < i ? SweepRow::Kind::CONE_SECOND : SweepRow::Kind::CONE_FIRST;
      if (s.kind == SweepRow::Kind::CONE_FIRST) s.a01 = problem.coupling(i, e.partner);
    }
    s.inverse = 1.0 / s.diagonal;
    position[static_cast<std::size_t>(i)] = static_cast<int>(packed.size());
    packed.push_back(s);
  }
  for (SweepRow& s : packed) {
    const IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(s.row)];
    if (s.follows) {
      s.normal = position[static_cast<std::size_t>(e.normal)];
      s.fixedNormal = problem.rows[static_cast<std::size_t>(e.normal)].impulse;
    }
    if (s.kind == SweepRow::Kind::CONE_FIRST) {
      s.partner = position[static_cast<std::size_t>(e.partner)];
      const SweepRow& p = packed[static_cast<std::size_t>(s.partner)];
      s.inverse = 1.0 / (s.diagonal * p.diagonal - s.a01 * s.a01);
    }
  }
}

/// Projected Gauss–Seidel on the rows `subset` (PHYSICS.md §2.2), the other
/// rows' impulses held fixed, starting from the impulses in the problem
/// (the last step's when warm starting): Λᵢ ← clamp(Λᵢ + rᵢ/(S+Σ)ᵢᵢ, loᵢ, hiᵢ) with rᵢ = qᵢ − GᵢΔv − ΣᵢΛᵢ,
/// keeping Δv = M⁻¹GᵀΛ current so that one row costs O(1).
///
/// Friction rows take their bounds from the current impulse of their normal
/// row: ±μΛn (scaled box), and a cone's tangent pair is updated as a block,
/// its two impulses minimizing their quadratic within the disk of radius
/// μΛn (projectOntoDisk), the projected cone of PHYSICS.md §2.2.
///
/// A constraint's unbounded rows are updated as one block (RowBlocks).
inline IterativeSolveResult gaussSeidelSolve(IslandProblem& problem, const std::vector<int>& subset, int maxIterations,
                                             double tolerance) {
  IterativeSolveResult result;
  if (subset.empty()) return result;
  // Kept between solves: a scene's rows are packed again at every solve,
  // and fresh pages for them cost more than the packing.
  thread_local std::vector<Vec6d> velocityChange;
  thread_local std::vector<char> swept;
  thread_local std::vector<SweepRow> packed;
  thread_local std::vector<int> position;
  problem.velocityChange(velocityChange);
  Vec6d* dv = velocityChange.data();
  assignGrowing(swept, problem.rows.size(), char(0));
  for (int i : subset) swept[static_cast<std::size_t>(i)] = 1;
  const RowBlocks blocks(problem, subset, true);
  packSweepRows(problem, subset, blocks.units(), swept, packed, position);

  const auto followNormal = [&](SweepRow& s) {
    const double normal = s.normal >= 0 ? packed[static_cast<std::size_t>(s.normal)].impulse : s.fixedNormal;
    const double limit = s.mu * std::max(0.0, normal);
    s.lower = -limit;
    s.upper = limit;
  };
  for (int sweep = 0; sweep < maxIterations; ++sweep) {
    double change = 0.0;
    std::size_t next = 0;
    for (const RowBlocks::Unit& unit : blocks.units()) {
      if (unit.count > 1) {
        Vec6d r_B = Vec6d::Zero();
        for (int a = 0; a < unit.count; ++a) {
          const int i = subset[static_cast<std::size_t>(unit.first + a)];
          const auto& e = problem.rows[static_cast<std::size_t>(i)];
          r_B(a) = e.q - problem.rowVelocity(i, velocityChange) - e.sigma * e.impulse;
        }
        const Vec6d d_B = blocks.inverse(unit) * r_B;
        for (int a = 0; a < unit.count; ++a) {
          const int i = subset[static_cast<std::size_t>(unit.first + a)];
          auto& e = problem.rows[static_cast<std::size_t>(i)];
          e.impulse += d_B(a);
          problem.addImpulse(velocityChange, i, d_B(a));
          change = std::max(change, std::abs(d_B(a)) * e.diagonal);
        }
        continue;
      }
      SweepRow& s = packed[next++];
      if (s.follows) followNormal(s);
      if (s.kind == SweepRow::Kind::CONE_SECOND) continue;  // updated with the first of its pair
      const double r = s.q - sweptRowVelocity(problem, s, dv) - s.sigma * s.impulse;
      if (s.kind == SweepRow::Kind::CONE_FIRST) {
        SweepRow& p = packed[static_cast<std::size_t>(s.partner)];
        p.lower = s.lower;
        p.upper = s.upper;
        const double rp = p.q - sweptRowVelocity(problem, p, dv) - p.sigma * p.impulse;
        const double a01 = s.a01;
        const double d0 = (p.diagonal * r - a01 * rp) * s.inverse, d1 = (s.diagonal * rp - a01 * r) * s.inverse;
        // Scalars, not the projection's array: its two 8-byte stores would
        // not forward to a 16-byte load of the pair.
        double moved0 = s.impulse + d0, moved1 = p.impulse + d1;
        if (moved0 * moved0 + moved1 * moved1 > s.upper * s.upper) {
          const auto moved = projectOntoDisk({moved0, moved1}, s.upper, s.diagonal, a01, p.diagonal);
          moved0 = moved[0];
          moved1 = moved[1];
        }
        const double ds = moved0 - s.impulse, dp = moved1 - p.impulse;
        s.impulse = moved0;
        p.impulse = moved1;
        addSweptImpulse(problem, s, dv, ds);
        addSweptImpulse(problem, p, dv, dp);
        change = std::max(change, std::max(std::abs(ds) * s.diagonal, std::abs(dp) * p.diagonal));
        continue;
      }
      const double clamped = std::clamp(s.impulse + r * s.inverse, s.lower, s.upper);
      const double d = clamped - s.impulse;
      s.impulse = clamped;
      addSweptImpulse(problem, s, dv, d);
      change = std::max(change, std::abs(d) * s.diagonal);
    }
    result.iterations = sweep + 1;
    result.change = change;
    if (!std::isfinite(change)) break;
    if (change <= tolerance) {
      result.converged = true;
      break;
    }
  }
  for (const SweepRow& s : packed) {
    IslandProblem::Entry& e = problem.rows[static_cast<std::size_t>(s.row)];
    e.impulse = s.impulse;
    if (s.follows) {
      e.lower = s.lower;
      e.upper = s.upper;
    }
  }
  return result;
}

/// Projected Jacobi on the rows `subset`: every update of a sweep is
/// computed from the same Δv and applied scaled by 1/k, k the largest
/// number of swept rows on either of the row's bodies, which keeps it from
/// overshooting where rows share a body. Friction bounds follow the normal
/// as in Gauss–Seidel; a cone pair's box step is scaled back into its disk.
inline IterativeSolveResult jacobiSolve(IslandProblem& problem, const std::vector<int>& subset, int maxIterations,
                                        double tolerance) {
  IterativeSolveResult result;
  if (subset.empty()) return result;
  std::vector<Vec6d> dv = problem.velocityChange();

  std::vector<double> relaxation;
  std::vector<int> count(static_cast<std::size_t>(problem.numBodies), 0);
  for (int i : subset) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    for (int body : problem.bodiesOf(e))
      if (body >= 0) ++count[static_cast<std::size_t>(body)];
  }
  for (int i : subset) {
    int k = 1;
    for (int body : problem.bodiesOf(problem.rows[static_cast<std::size_t>(i)]))
      if (body >= 0) k = std::max(k, count[static_cast<std::size_t>(body)]);
    relaxation.push_back(1.0 / k);
  }
  std::vector<double> delta(subset.size(), 0.0);
  std::vector<char> inSubset(problem.rows.size(), 0);
  for (int i : subset) inSubset[static_cast<std::size_t>(i)] = 1;
  const auto conePair = [&](int i) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    return e.frictionBound == FrictionBound::CONE && e.normal >= 0 && e.partner >= 0 &&
           inSubset[static_cast<std::size_t>(e.partner)];
  };

  for (int sweep = 0; sweep < maxIterations; ++sweep) {
    double change = 0.0;
    for (std::size_t k = 0; k < subset.size(); ++k) {
      auto& e = problem.rows[static_cast<std::size_t>(subset[k])];
      if (e.followsNormal()) {
        const double limit = frictionLimit(problem, e);
        e.lower = -limit;
        e.upper = limit;
      }
      const double r = e.q - problem.rowVelocity(subset[k], dv) - e.sigma * e.impulse;
      delta[k] = relaxation[k] * (std::clamp(e.impulse + r / e.diagonal, e.lower, e.upper) - e.impulse);
    }
    for (std::size_t k = 0; k < subset.size(); ++k) {
      const int i = subset[k];
      auto& e = problem.rows[static_cast<std::size_t>(i)];
      e.impulse += delta[k];
      problem.addImpulse(dv, i, delta[k]);
      change = std::max(change, std::abs(delta[k]) * e.diagonal);
    }
    // The box step leaves a cone pair in its square: scale it into the disk.
    for (int i : subset) {
      auto& e = problem.rows[static_cast<std::size_t>(i)];
      if (!conePair(i) || e.partner < i) continue;
      auto& p = problem.rows[static_cast<std::size_t>(e.partner)];
      const double limit = frictionLimit(problem, e), force = planarLength(e.impulse, p.impulse);
      if (force <= limit) continue;
      const double f = limit / force;
      problem.addImpulse(dv, i, e.impulse * (f - 1.0));
      problem.addImpulse(dv, e.partner, p.impulse * (f - 1.0));
      e.impulse *= f;
      p.impulse *= f;
    }
    result.iterations = sweep + 1;
    result.change = change;
    if (!std::isfinite(change)) break;
    if (change <= tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

/// Projected Gauss–Seidel (gaussSeidelSolve) or, with `jacobi`, projected
/// Jacobi (jacobiSolve) on the rows `subset`.
inline IterativeSolveResult iterativeSolve(IslandProblem& problem, const std::vector<int>& subset, int maxIterations,
                                           double tolerance, bool jacobi) {
  return jacobi ? jacobiSolve(problem, subset, maxIterations, tolerance)
                : gaussSeidelSolve(problem, subset, maxIterations, tolerance);
}

}  // namespace spook::detail
