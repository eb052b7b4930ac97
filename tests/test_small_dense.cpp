#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Core>

#include <spook/solver/small_dense.hpp>

using namespace spook::detail;

namespace {

// A random symmetric positive definite N × N matrix of condition number
// about `condition`: Q diag(λ) Qᵀ with λ spread log-evenly over [1, condition].
template <int N>
Eigen::Matrix<double, N, N> randomSpd(std::mt19937& rng, double condition) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // Q: Gram-Schmidt (applied twice) on random columns.
  Eigen::Matrix<double, N, N> Q;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> q;
    for (int i = 0; i < N; ++i) q[i] = u(rng);
    for (int pass = 0; pass < 2; ++pass)
      for (int k = 0; k < j; ++k) q -= Q.col(k).dot(q) * Q.col(k);
    Q.col(j) = q.normalized();
  }
  Eigen::Matrix<double, N, 1> lambda;
  for (int k = 0; k < N; ++k) lambda[k] = std::pow(condition, double(k) / double(N - 1));
  return Q * lambda.asDiagonal() * Q.transpose();
}

}  // namespace

TEST_CASE_TEMPLATE("small Cholesky: L Lᵀ reproduces a positive definite block, its inverse multiplies to I", Size,
                   std::integral_constant<int, 3>, std::integral_constant<int, 6>) {
  constexpr int N = Size::value;
  using Mat = Eigen::Matrix<double, N, N>;
  std::mt19937 rng(7);
  for (const double condition : {1.0, 1e3, 1e8}) {
    for (int trial = 0; trial < 20; ++trial) {
      const Mat A = randomSpd<N>(rng, condition);
      Mat L, inverse;
      REQUIRE(choleskyLower<N>(A, L));
      CHECK(Mat(L.template triangularView<Eigen::StrictlyUpper>()).isZero(0.0));
      // Backward stable: ‖LLᵀ − A‖ ≤ c·ε‖A‖ whatever the condition.
      CHECK((L * L.transpose() - A).norm() <= 1e-14 * A.norm());
      REQUIRE(invertByCholesky<N>(A, inverse));
      // Forward error grows with the condition number: ‖A A⁻¹ − I‖ ≤ c·ε·κ.
      CHECK((A * inverse - Mat::Identity()).norm() <= 1e-13 * condition);
      CHECK((inverse - inverse.transpose()).norm() <= 1e-14 * inverse.norm());
    }
  }
}

TEST_CASE("small Cholesky: an indefinite, singular or non-finite block is refused") {
  Eigen::Matrix3d L;
  Eigen::Matrix3d indefinite = Eigen::Vector3d(1.0, -1e-9, 2.0).asDiagonal();
  CHECK_FALSE(choleskyLower<3>(indefinite, L));
  Eigen::Matrix3d singular = Eigen::Matrix3d::Ones();  // rank one
  CHECK_FALSE(choleskyLower<3>(singular, L));
  Eigen::Matrix3d nan = Eigen::Matrix3d::Identity();
  nan(2, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(choleskyLower<3>(nan, L));
  // The leading corner alone is factorized: a bad entry outside it is ignored.
  Eigen::Matrix<double, 6, 6> corner = Eigen::Matrix<double, 6, 6>::Identity();
  corner(5, 5) = -1.0;
  Eigen::Matrix<double, 6, 6> L6;
  CHECK(choleskyLower<6>(corner, L6, 5));
  CHECK_FALSE(choleskyLower<6>(corner, L6, 6));
}

TEST_CASE("invertByCholesky inverts the leading corner of a 6 x 6 block in place") {
  std::mt19937 rng(11);
  for (int n = 1; n <= 6; ++n) {
    Eigen::Matrix<double, 6, 6> A = randomSpd<6>(rng, 1e4);
    const Eigen::Matrix<double, 6, 6> before = A;
    const Eigen::MatrixXd corner = A.topLeftCorner(n, n);
    REQUIRE(invertByCholesky<6>(A, A, n));
    CHECK((corner * A.topLeftCorner(n, n) - Eigen::MatrixXd::Identity(n, n)).norm() <= 1e-9);
    // Outside the corner A is left as it was.
    CHECK(A.rightCols(6 - n) == before.rightCols(6 - n));
    CHECK(A.bottomRows(6 - n) == before.bottomRows(6 - n));
  }
}

TEST_CASE("DenseLU recovers a known solution, pivoting past a zero leading entry") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const int n : {2, 5, 17, 32}) {
    Eigen::MatrixXd A = Eigen::MatrixXd::NullaryExpr(n, n, [&] { return u(rng); });
    A(0, 0) = 0.0;  // no LU without a row exchange
    const Eigen::VectorXd solution = Eigen::VectorXd::NullaryExpr(n, [&] { return u(rng); });
    const Eigen::VectorXd b = A * solution;
    DenseLU lu;
    lu.compute(A);
    const Eigen::VectorXd x = lu.solve(b);
    CHECK((A * x - b).norm() <= 1e-12 * (A.norm() * x.norm() + b.norm()));
    // These random matrices have condition numbers below ~1e4.
    CHECK((x - solution).norm() <= 1e-9 * solution.norm());
  }
  // A singular matrix answers non-finite values, not a finite wrong one.
  Eigen::MatrixXd singular(2, 2);
  singular << 1.0, 2.0, 2.0, 4.0;
  DenseLU lu;
  lu.compute(singular);
  CHECK_FALSE(lu.solve(Eigen::Vector2d(1.0, 0.0)).allFinite());
}
