#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace spook::detail {

// The solver's small dense factorizations in plain loops: a Cholesky factor
// of a fixed-size block (3×3 inertias, 6×6 body blocks) and an LU with
// partial pivoting of the low-rank updates' capacitance matrices (at most
// FactoredFreeSet::kMaxChangedRows = 32 rows). At these sizes plain loops
// are as fast as Eigen's LLT and PartialPivLU, and they do not instantiate
// Eigen's blocked kernels (matrix-matrix products, triangular solves),
// which cost every program that compiles the solver some 2 s of GCC's time.

/// The lower Cholesky factor L (A = LLᵀ) of the symmetric positive definite
/// leading n × n corner of A, lower triangle read; false, with L
/// unspecified, when a pivot is not positive or not finite.
template <int N>
bool choleskyLower(const Eigen::Matrix<double, N, N>& A, Eigen::Matrix<double, N, N>& L, int n = N) {
  L.setZero();
  for (int j = 0; j < n; ++j) {
    double d = A(j, j);
    for (int k = 0; k < j; ++k) d -= L(j, k) * L(j, k);
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    L(j, j) = std::sqrt(d);
    for (int i = j + 1; i < n; ++i) {
      double x = A(i, j);
      for (int k = 0; k < j; ++k) x -= L(i, k) * L(j, k);
      L(i, j) = x / L(j, j);
    }
  }
  return true;
}

/// W = L⁻¹ of the lower triangular leading n × n corner of L (nonzero
/// diagonal); W is lower triangular, zero elsewhere.
template <int N>
void invertLowerTriangular(const Eigen::Matrix<double, N, N>& L, Eigen::Matrix<double, N, N>& W, int n = N) {
  W.setZero();
  for (int j = 0; j < n; ++j) {
    W(j, j) = 1.0 / L(j, j);
    for (int i = j + 1; i < n; ++i) {
      double x = 0.0;
      for (int k = j; k < i; ++k) x -= L(i, k) * W(k, j);
      W(i, j) = x / L(i, i);
    }
  }
}

/// The inverse of the symmetric positive definite leading n × n corner of
/// A (lower triangle read), by A⁻¹ = L⁻ᵀL⁻¹, into the same corner of
/// `inverse` (which may be A itself; the rest of it is left as it was);
/// false, with that corner unspecified, when A is not positive definite or
/// its inverse overflows.
template <int N>
bool invertByCholesky(const Eigen::Matrix<double, N, N>& A, Eigen::Matrix<double, N, N>& inverse, int n = N) {
  Eigen::Matrix<double, N, N> L, W;  // W = L⁻¹
  if (!choleskyLower<N>(A, L, n)) return false;
  invertLowerTriangular<N>(L, W, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j <= i; ++j) {
      double x = 0.0;
      for (int k = i; k < n; ++k) x += W(k, i) * W(k, j);
      inverse(i, j) = inverse(j, i) = x;
    }
  return inverse.topLeftCorner(n, n).allFinite();
}

/// LU factorization with partial (row) pivoting, PA = LU, of a small
/// square matrix; solve() answers A x = b. A singular matrix gives
/// non-finite answers, as Eigen's PartialPivLU does.
class DenseLU {
 public:
  void compute(const Eigen::MatrixXd& A) {
    lu_ = A;
    const Eigen::Index n = lu_.rows();
    rowOf_.resize(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i) rowOf_[static_cast<std::size_t>(i)] = i;
    for (Eigen::Index j = 0; j < n; ++j) {
      Eigen::Index pivot = j;
      for (Eigen::Index i = j + 1; i < n; ++i)
        if (std::abs(lu_(i, j)) > std::abs(lu_(pivot, j))) pivot = i;
      if (pivot != j) {
        lu_.row(j).swap(lu_.row(pivot));
        std::swap(rowOf_[static_cast<std::size_t>(j)], rowOf_[static_cast<std::size_t>(pivot)]);
      }
      const double diagonal = lu_(j, j);
      for (Eigen::Index i = j + 1; i < n; ++i) {
        const double factor = lu_(i, j) / diagonal;
        lu_(i, j) = factor;
        for (Eigen::Index k = j + 1; k < n; ++k) lu_(i, k) -= factor * lu_(j, k);
      }
    }
  }

  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    const Eigen::Index n = lu_.rows();
    Eigen::VectorXd x(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      double sum = b[rowOf_[static_cast<std::size_t>(i)]];
      for (Eigen::Index k = 0; k < i; ++k) sum -= lu_(i, k) * x[k];
      x[i] = sum;
    }
    for (Eigen::Index i = n - 1; i >= 0; --i) {
      double sum = x[i];
      for (Eigen::Index k = i + 1; k < n; ++k) sum -= lu_(i, k) * x[k];
      x[i] = sum / lu_(i, i);
    }
    return x;
  }

 private:
  Eigen::MatrixXd lu_;
  std::vector<Eigen::Index> rowOf_;  ///< row i of PA is row rowOf_[i] of A
};

}  // namespace spook::detail
