#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <spook/solver/factored_free_set.hpp>
#include <spook/solver/small_dense.hpp>

namespace spook::detail {

/// Solves the free rows of a pivot step with the factor of an earlier step
/// of the same matrix, instead of factorizing again (direct_solve.hpp).
///
/// A block pivoting step frees or clamps a few rows: of the factorized free
/// set F₀, the rows R are now clamped and the rows P, clamped then, are now
/// free. The new free rows' system A_FF x_F = g is the bordered system
///
///   [ A₀₀    A₀P   E_R ] [ x₀ ]   [ g₀ ]
///   [ A_P0   A_PP  0   ] [ x_P ] = [ g_P ]      (x_R = 0 through the
///   [ E_Rᵀ   0     0   ] [ μ  ]   [ 0  ]       multipliers μ)
///
/// with A₀₀ = A_F₀F₀, the factorized matrix. Its Schur complement over A₀₀,
/// S = [A_PP 0; 0 0] − [A_P0; E_Rᵀ] A₀₀⁻¹ [A₀P E_R], is as small as the
/// change, and its columns A₀₀⁻¹A₀p and A₀₀⁻¹e_r depend only on the row and
/// the factor: each is solved once and kept while the factor stands, over
/// the pivot steps of a solve and the hybrid's coupling passes (the block
/// update of Gill, Murray, Saunders & Wright, "Sparse matrix methods in
/// optimization", SIAM J. Sci. Stat. Comput. 5(3), 1984). A step then costs
/// one solve with the factor, one per row not seen changed before, and a
/// dense solve of S, where factorizing a pile of spheres' normals costs
/// about ten solves. The answer is checked against the new matrix and
/// refined with the same update; the caller factorizes where the change
/// grows past FactoredFreeSet's caps or the residual does not fall.
class FreeSetUpdate {
 public:
  /// Refinements of an update's answer against its residual.
  static constexpr int kRefinements = 2;

  /// A new factor of the matrix with the rows freeIndex[k] ≥ 0 free.
  void reset(const std::vector<int>& freeIndex) { set_.reset(freeIndex); }
  /// No factor.
  void clear() { set_.clear(); }
  /// Whether the rows freeIndex[k] ≥ 0 are the factorized free set.
  [[nodiscard]] bool isFactorized(const std::vector<int>& freeIndex) const { return set_.isFactorized(freeIndex); }

  /// Solves B x = b for the matrix B of the free rows `freeIndex` (≥ 0:
  /// free) in the identity-row form of DirectSolve: `A` is the full
  /// symmetric matrix of every row, `current` B's lower triangle, and
  /// `factorSolve(v)` returns the factorized matrix's inverse times v.
  /// False where the change is too large or the answer's residual stays
  /// above `enough` (x then undefined).
  template <class FactorSolve>
  bool solve(const Eigen::SparseMatrix<double>& A, const Eigen::SparseMatrix<double>& current,
             const std::vector<int>& freeIndex, const Eigen::VectorXd& b, double enough, FactorSolve&& factorSolve,
             Eigen::VectorXd& x) {
    if (!set_.collect(freeIndex, [&](int k) { return Eigen::VectorXd(factorSolve(borderColumn(A, k))); })) return false;
    const std::vector<int>& changed = set_.changed();
    if (changed.empty()) return false;  // the factorized matrix itself: DirectSolve solves it with its factor
    const auto m = static_cast<Eigen::Index>(changed.size());
    Eigen::MatrixXd S(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const int ki = changed[static_cast<std::size_t>(i)];
      for (Eigen::Index j = 0; j < m; ++j) {
        const int kj = changed[static_cast<std::size_t>(j)];
        const Eigen::VectorXd& z = column(kj);
        if (wasFree(ki))
          S(i, j) = -z[ki];
        else
          S(i, j) = (wasFree(kj) ? 0.0 : A.coeff(ki, kj)) - dotFactoredFree(A, ki, z);
      }
    }
    DenseLU lu;
    lu.compute(S);

    x.setZero(b.size());
    Eigen::VectorXd r = b;
    for (int pass = 0; pass <= kRefinements; ++pass) {
      x += apply(A, lu, r, factorSolve);
      r = b - current.selfadjointView<Eigen::Lower>() * x;
      const double size = r.cwiseAbs().maxCoeff();
      if (size <= enough) return true;
      if (!std::isfinite(size)) return false;
    }
    return false;
  }

 private:
  bool wasFree(int k) const { return set_.wasFree(k); }
  const Eigen::VectorXd& column(int k) const { return set_.column(k); }

  // The border of row k: e_k for a row then free (now clamped), its
  // coupling to the factorized free rows A₀k for a row then clamped.
  Eigen::VectorXd borderColumn(const Eigen::SparseMatrix<double>& A, int k) const {
    Eigen::VectorXd c = Eigen::VectorXd::Zero(A.rows());
    if (wasFree(k)) {
      c[k] = 1.0;
      return c;
    }
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      if (wasFree(static_cast<int>(it.row()))) c[it.row()] = it.value();
    return c;
  }

  // A_k0 · v over the factorized free rows.
  double dotFactoredFree(const Eigen::SparseMatrix<double>& A, int k, const Eigen::VectorXd& v) const {
    double sum = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      if (wasFree(static_cast<int>(it.row()))) sum += it.value() * v[it.row()];
    return sum;
  }

  // The bordered system's answer for the right-hand side b (zero at the
  // rows clamped now).
  template <class FactorSolve>
  Eigen::VectorXd apply(const Eigen::SparseMatrix<double>& A, const DenseLU& lu, const Eigen::VectorXd& b,
                        FactorSolve& factorSolve) const {
    Eigen::VectorXd g = b;
    for (int k : set_.changed())
      if (!wasFree(k)) g[k] = 0.0;  // the freed rows' equations are S's
    Eigen::VectorXd y = factorSolve(g);
    const auto m = static_cast<Eigen::Index>(set_.changed().size());
    Eigen::VectorXd s(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      const int k = set_.changed()[static_cast<std::size_t>(i)];
      s[i] = wasFree(k) ? -y[k] : b[k] - dotFactoredFree(A, k, y);
    }
    const Eigen::VectorXd t = lu.solve(s);
    for (Eigen::Index j = 0; j < m; ++j) y -= t[j] * column(set_.changed()[static_cast<std::size_t>(j)]);
    for (Eigen::Index j = 0; j < m; ++j) {
      const int k = set_.changed()[static_cast<std::size_t>(j)];
      y[k] = wasFree(k) ? 0.0 : t[j];
    }
    return y;
  }

  FactoredFreeSet set_;  ///< its columns: A₀₀⁻¹ times a row's border column
};

}  // namespace spook::detail
