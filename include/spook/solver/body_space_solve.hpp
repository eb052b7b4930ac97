#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include <spook/solver/block_cholesky.hpp>
#include <spook/solver/factored_free_set.hpp>
#include <spook/solver/island_problem.hpp>

namespace spook::detail {

/// The free rows of a direct solve through the bodies instead of the rows:
/// by the Woodbury identity, (G M⁻¹Gᵀ + Σ) x = r is
///   (M + GᵀΣ⁻¹G) y = GᵀΣ⁻¹r,   x = Σ⁻¹(r − G y).
/// K = M + GᵀΣ⁻¹G has a 6×6 block per body and per pair of bodies sharing
/// rows, whatever the number of rows, whereas G M⁻¹Gᵀ couples every two rows
/// on a body: a box touching four others at four points each fills a 48×48
/// block. Contact scenes, where rows far outnumber the bodies' degrees of
/// freedom, factorize in a fraction of the time, by a Cholesky
/// factorization over the 6×6 blocks (block_cholesky.hpp).
///
/// x = Σ⁻¹(r − G y) cancels digits where Σ is small against the row's
/// mobility G M⁻¹Gᵀ (about log₁₀ of their ratio); DirectSolve wins them
/// back by iterative refinement (each pass solves for the residual with the
/// same factorization). The form is used only when every row is at least
/// kSofterThan as compliant as it is mobile, where a pass gains at least
/// five digits: contacts qualify (the normal rows of 1 kg unit cubes on the
/// default material are 6e-7..1e-6 as compliant as mobile, which kept them
/// out of the body space at the former 1e-6), rigid joints (Σ at its 1e-12
/// floor) do not.
class BodySpaceSolve {
 public:
  static constexpr double kSofterThan = 1e-10;

  /// Whether `numRows` rows outnumber the degrees of freedom of `numBodies`.
  [[nodiscard]] static bool outnumbers(std::size_t numRows, std::size_t numBodies) { return numRows > 6 * numBodies; }

  /// Whether the rows `subset` are better solved in body space: more rows
  /// than 6 per body, every body's mass known, every row soft enough.
  [[nodiscard]] static bool pays(const IslandProblem& problem, const std::vector<int>& subset) {
    if (!outnumbers(subset.size(), static_cast<std::size_t>(problem.numBodies))) return false;
    if (static_cast<int>(problem.mass.size()) != problem.numBodies) return false;
    for (int b = 0; b < problem.numBodies; ++b)
      if (!problem.mass[static_cast<std::size_t>(b)].allFinite()) return false;
    for (int i : subset) {
      const auto& e = problem.rows[static_cast<std::size_t>(i)];
      if (!(e.sigma >= kSofterThan * (e.diagonal - e.sigma))) return false;
    }
    return true;
  }

  /// Fixes K's sparsity pattern for the rows `subset`: a block per body and
  /// per pair of bodies sharing one of the rows, whether the row is free or
  /// clamped, so that the pattern and its symbolic analysis (the ordering
  /// and the elimination tree) hold over every pivot step of a solve, and
  /// over steps and solves whose rows couple the same bodies (a resting
  /// pile's contacts). Analyzes again only when the pattern changed.
  void analyze(const IslandProblem& problem, const std::vector<int>& subset) {
    keys_.clear();
    for (int i : subset) {
      const std::array<int, 3> body = problem.bodiesOf(problem.rows[static_cast<std::size_t>(i)]);
      for (std::size_t x = 1; x < body.size(); ++x)
        for (std::size_t y = 0; y < x; ++y)
          if (body[x] >= 0 && body[y] >= 0) {
            const std::uint64_t pair = key(std::max(body[x], body[y]), std::min(body[x], body[y]));
            // A contact's rows follow one another on the same pair: sorted fewer.
            if (keys_.empty() || keys_.back() != pair) keys_.push_back(pair);
          }
    }
    std::sort(keys_.begin(), keys_.end());
    keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
    if (problem.numBodies != patternBodies_ || keys_ != pattern_) {
      pattern_.swap(keys_);
      patternBodies_ = problem.numBodies;
      factored_ = false;
      std::vector<std::pair<int, int>> lower(pattern_.size());
      for (std::size_t p = 0; p < pattern_.size(); ++p) lower[p] = {rowOf(pattern_[p]), colOf(pattern_[p])};
      cholesky_.analyze(patternBodies_, lower);
    }
    // Only a factor worth updating needs to know its rows again.
    rowsHash_ = worthUpdating() ? hashRows(problem, subset) : 0;
  }

  /// Factorizes K for the rows of `subset` flagged free (freeIndex[k] ≥ 0);
  /// analyze() has seen the same rows. False where round-off left K not
  /// positive definite (the caller solves in row space instead). Where the
  /// rows are those of the last factorization, at most
  /// FactoredFreeSet::kMaxChangedRows of them changed state and the factor is costly enough
  /// (kUpdateWorthSolves), K is not factorized again but updated (see
  /// prepareUpdate; updated() tells, and `allowUpdate` false forbids it).
  [[nodiscard]] bool factorize(const IslandProblem& problem, const std::vector<int>& subset,
                               const std::vector<int>& freeIndex, bool allowUpdate = true) {
    if (allowUpdate && factored_ && worthUpdating() && rowsHash_ == factoredHash_ &&
        prepareUpdate(problem, subset, freeIndex))
      return true;
    updating_ = false;
    const int numBodies = problem.numBodies;
    diagonal_.resize(static_cast<std::size_t>(numBodies));
    for (int b = 0; b < numBodies; ++b) diagonal_[static_cast<std::size_t>(b)] = problem.mass[static_cast<std::size_t>(b)];
    blocks_.assign(pattern_.size(), Mat6d::Zero());
    for (std::size_t k = 0; k < subset.size(); ++k) {
      const int f = freeIndex[k];
      if (f < 0) continue;
      const auto& e = problem.rows[static_cast<std::size_t>(subset[k])];
      const double inverseSigma = 1.0 / e.sigma;
      // The row's bodies are distinct (IslandProblem::addBody).
      std::array<int, 3> body{};
      std::array<const Vec6d*, 3> J{};
      int n = 0;
      problem.forEachBody(e, [&](int b, const Vec6d& j, const Vec6d&) {
        body[static_cast<std::size_t>(n)] = b;
        J[static_cast<std::size_t>(n++)] = &j;
      });
      for (std::size_t x = 0; x < static_cast<std::size_t>(n); ++x) {
        diagonal_[static_cast<std::size_t>(body[x])] += inverseSigma * *J[x] * J[x]->transpose();
        // K's lower triangle: the block (larger body, smaller body).
        for (std::size_t y = 0; y < x; ++y) {
          const bool xLarger = body[x] > body[y];
          blockAt(xLarger ? body[x] : body[y], xLarger ? body[y] : body[x]) +=
              inverseSigma * (xLarger ? *J[x] : *J[y]) * (xLarger ? *J[y] : *J[x]).transpose();
        }
      }
    }

    // The hybrid's coupling passes and a pivoting that ends where it began
    // ask again for the K they had factorized: the factor stands.
    if (factored_ && diagonal_ == factoredDiagonal_ && blocks_ == factoredBlocks_) return true;
    factored_ = cholesky_.factorize(diagonal_, blocks_);
    if (factored_) {
      // diagonal_ and blocks_ are assembled afresh at each call: swapped, not copied.
      std::swap(diagonal_, factoredDiagonal_);
      std::swap(blocks_, factoredBlocks_);
      factoredHash_ = rowsHash_;
      set_.reset(freeIndex);
    }
    return factored_;
  }

  /// The multiply-adds of one factorization of the pattern analyze() fixed.
  [[nodiscard]] double factorizationWork() const { return cholesky_.factorizationWork(); }

  /// Whether the last factorize() updated the factor in hand instead of
  /// factorizing.
  [[nodiscard]] bool updated() const { return updating_; }

  /// Solves the free rows of the last factorize() for the right-hand side r
  /// (`rhs`, one entry per free row); writes x into `x` at the free rows'
  /// positions.
  void solve(const IslandProblem& problem, const std::vector<int>& subset, const std::vector<int>& freeIndex,
             const Eigen::VectorXd& rhs, Eigen::VectorXd& x) const {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(6 * problem.numBodies);  // GᵀΣ⁻¹r, solved in place for y
    for (std::size_t k = 0; k < subset.size(); ++k) {
      const int f = freeIndex[k];
      if (f < 0) continue;
      const auto& e = problem.rows[static_cast<std::size_t>(subset[k])];
      const double s = rhs[f] / e.sigma;
      problem.forEachBody(e, [&](int body, const Vec6d& J, const Vec6d&) { y.segment<6>(6 * body) += s * J; });
    }
    cholesky_.solve(y);
    if (updating_) {
      // y = K₀⁻¹b − Z C⁻¹ J_Dᵀ K₀⁻¹b (prepareUpdate).
      const std::vector<int>& changed = set_.changed();
      const auto m = static_cast<Eigen::Index>(changed.size());
      Eigen::VectorXd u(m);
      for (Eigen::Index i = 0; i < m; ++i)
        u[i] = dotJacobian(problem, subset[static_cast<std::size_t>(changed[static_cast<std::size_t>(i)])], y);
      const Eigen::VectorXd t = capacitance_.solve(u);
      for (Eigen::Index i = 0; i < m; ++i) y -= t[i] * set_.column(changed[static_cast<std::size_t>(i)]);
    }

    for (std::size_t k = 0; k < subset.size(); ++k) {
      const int f = freeIndex[k];
      if (f < 0) continue;
      const auto& e = problem.rows[static_cast<std::size_t>(subset[k])];
      double gy = 0.0;  // G y
      problem.forEachBody(e, [&](int body, const Vec6d& J, const Vec6d&) { gy += J.dot(y.segment<6>(6 * body)); });
      x[static_cast<Eigen::Index>(k)] = (rhs[f] - gy) / e.sigma;
    }
  }

  /// An update (a solve or two more, one per new column, a small dense
  /// solve) is taken where a factorization costs at least this many solves:
  /// a stack's chain of blocks factorizes in about five (20 stacks of 10
  /// cubes under the direct policy: 0.93 -> 1.2 ms a step with updates),
  /// a 210-cube pyramid's filled factor in far more.
  static constexpr double kUpdateWorthSolves = 8.0;

 private:
  // A pivot step frees or clamps a few rows: K = K₀ + Σ_D s_k j_k j_kᵀ over
  // the changed rows D, s_k = 1/σ_k for a row freed, −1/σ_k for one clamped,
  // j_k its Jacobian over the bodies. By the Woodbury identity
  //   K⁻¹ = K₀⁻¹ − Z (S⁻¹ + J_DᵀZ)⁻¹ Zᵀ,   Z = K₀⁻¹J_D,
  // a solve with K is one with the factor of K₀ and a dense solve of the
  // capacitance matrix C = S⁻¹ + J_DᵀZ, as small as the change. Z's columns
  // depend only on the row and K₀: each is solved once and kept while the
  // factor stands (pivot steps, the hybrid's coupling passes). The caller
  // checks the answer against the rows (refineInBodySpace) and factorizes
  // where it falls short, as where C is singular to round-off (a clamped
  // row that alone held a direction of K₀).
  bool prepareUpdate(const IslandProblem& problem, const std::vector<int>& subset, const std::vector<int>& freeIndex) {
    const auto jacobianSolved = [&](int k) {
      Eigen::VectorXd z = Eigen::VectorXd::Zero(6 * problem.numBodies);
      problem.forEachBody(problem.rows[static_cast<std::size_t>(subset[static_cast<std::size_t>(k)])],
                          [&](int body, const Vec6d& J, const Vec6d&) { z.segment<6>(6 * body) += J; });
      cholesky_.solve(z);
      return z;
    };
    if (!set_.collect(freeIndex, jacobianSolved)) return false;
    const std::vector<int>& changed = set_.changed();
    updating_ = !changed.empty();
    if (!updating_) return true;  // the factorized K itself
    const auto m = static_cast<Eigen::Index>(changed.size());
    Eigen::MatrixXd C(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const int k = changed[static_cast<std::size_t>(i)];
      const int row = subset[static_cast<std::size_t>(k)];
      for (Eigen::Index j = 0; j < m; ++j)
        C(i, j) = dotJacobian(problem, row, set_.column(changed[static_cast<std::size_t>(j)]));
      const double sigma = problem.rows[static_cast<std::size_t>(row)].sigma;
      C(i, i) += set_.wasFree(k) ? -sigma : sigma;
    }
    capacitance_.compute(C);
    return true;
  }

  bool worthUpdating() const { return cholesky_.solvesPerFactorization() >= kUpdateWorthSolves; }

  // j_rowᵀ v over the row's bodies.
  static double dotJacobian(const IslandProblem& problem, int row, const Eigen::VectorXd& v) {
    double sum = 0.0;
    problem.forEachBody(problem.rows[static_cast<std::size_t>(row)],
                        [&](int body, const Vec6d& J, const Vec6d&) { sum += J.dot(v.segment<6>(6 * body)); });
    return sum;
  }

  // A hash of what K₀ is made of (the rows' bodies, Jacobians and Σ, the
  // bodies' masses): rows that hash alike are taken for the same rows,
  // which the caller's check of the answer against the rows backs.
  static std::uint64_t hashRows(const IslandProblem& problem, const std::vector<int>& subset) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    const auto mix = [&h](double value) {
      std::uint64_t bits = 0;
      std::memcpy(&bits, &value, sizeof bits);
      h = (h ^ bits) * 0x100000001b3ull;
      h ^= h >> 29;
    };
    for (int i : subset) {
      const auto& e = problem.rows[static_cast<std::size_t>(i)];
      mix(e.sigma);
      problem.forEachBody(e, [&](int body, const Vec6d& J, const Vec6d&) {
        mix(static_cast<double>(body));
        for (int c = 0; c < 6; ++c) mix(J[c]);
      });
    }
    for (const Mat6d& m : problem.mass)
      for (int c = 0; c < 36; ++c) mix(m.data()[c]);
    return h;
  }

  static std::uint64_t key(int row, int col) {
    return (static_cast<std::uint64_t>(row) << 32) | static_cast<std::uint32_t>(col);
  }
  static int rowOf(std::uint64_t k) { return static_cast<int>(k >> 32); }
  static int colOf(std::uint64_t k) { return static_cast<int>(k & 0xffffffffu); }

  Mat6d& blockAt(int row, int col) {
    const auto it = std::lower_bound(pattern_.begin(), pattern_.end(), key(row, col));
    return blocks_[static_cast<std::size_t>(it - pattern_.begin())];
  }

  std::vector<Mat6d> diagonal_, blocks_;  ///< K's blocks: per body, per entry of pattern_
  std::vector<std::uint64_t> pattern_, keys_;  ///< K's off-diagonal blocks (row body, column body), sorted
  int patternBodies_ = -1;
  BlockCholesky cholesky_;
  /// K's blocks as cholesky_ holds them factorized (factored_).
  std::vector<Mat6d> factoredDiagonal_, factoredBlocks_;
  bool factored_ = false;
  std::uint64_t rowsHash_ = 0, factoredHash_ = 0;  ///< hashRows of analyze()'s rows, of the factorized ones
  FactoredFreeSet set_;                            ///< its columns: Z's, K₀⁻¹ j_k
  DenseLU capacitance_;
  bool updating_ = false;
};

}  // namespace spook::detail
