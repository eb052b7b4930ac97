#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include <spook/core/math.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

template <class S>
spook::EulerAnglesT<S> randomAngles(std::mt19937& rng) {
  std::uniform_real_distribution<double> roll(-3.1, 3.1), pitch(-1.5, 1.5);
  return {S(roll(rng)), S(pitch(rng)), S(roll(rng))};
}

}  // namespace

TEST_CASE_TEMPLATE("Euler angles are fixed-axis x, then y, then z rotations", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  const S half = S(std::numbers::pi / 2);
  using V = spook::Vec3T<S>;
  CHECK((spook::toMatrix<S>({S(0), S(0), half}) * V::UnitX() - V::UnitY()).norm() < tol);
  CHECK((spook::toMatrix<S>({half, S(0), S(0)}) * V::UnitY() - V::UnitZ()).norm() < tol);
  CHECK((spook::toMatrix<S>({S(0), half, S(0)}) * V::UnitZ() - V::UnitX()).norm() < tol);
  // x first, then z: X stays X under the roll, then turns onto Y.
  CHECK((spook::toMatrix<S>({half, S(0), half}) * V::UnitX() - V::UnitY()).norm() < tol);
}

TEST_CASE_TEMPLATE("quaternion, matrix and Euler angles convert into one another", S, float, double) {
  const S tol = pick<S>(1e-12, 2e-5);
  std::mt19937 rng(7);
  for (int i = 0; i < 1000; ++i) {
    const spook::EulerAnglesT<S> e = randomAngles<S>(rng);
    const spook::QuatT<S> q = spook::toQuat(e);
    const spook::Mat3T<S> R = spook::toMatrix(e);
    CHECK((q.toRotationMatrix() - R).norm() < tol);
    CHECK((spook::QuatT<S>(R).toRotationMatrix() - R).norm() < tol);
    const spook::EulerAnglesT<S> back = spook::toEulerAngles(q);
    CHECK((spook::toMatrix(back) - R).norm() < tol);
    CHECK(std::abs(back.y - e.y) < S(20) * tol);
  }
}

TEST_CASE_TEMPLATE("Euler angles at gimbal lock still reproduce the rotation", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const spook::EulerAnglesT<S> e{S(0.3), S(std::numbers::pi / 2), S(-0.4)};
  const spook::Mat3T<S> R = spook::toMatrix(e);
  CHECK((spook::toMatrix(spook::toEulerAngles<S>(R)) - R).norm() < tol);
}

TEST_CASE_TEMPLATE("rotate(a, b) takes direction a onto direction b", S, float, double) {
  const S tol = pick<S>(1e-14, 1e-6);
  using V = spook::Vec3T<S>;
  CHECK((spook::rotate<S>(V::UnitX(), V::UnitZ()) * V::UnitX() - V::UnitZ()).norm() < tol);
  CHECK((spook::rotate<S>(V(S(2), S(0), S(0)), V(S(0), S(0), S(5))) * V::UnitX() - V::UnitZ()).norm() < tol);
  // Antiparallel: a half turn about some axis perpendicular to x.
  const spook::QuatT<S> flip = spook::rotate<S>(V::UnitX(), -V::UnitX());
  CHECK((flip * V::UnitX() + V::UnitX()).norm() < tol);
  CHECK(std::abs(flip.norm() - S(1)) < tol);
  CHECK_THROWS_AS((void)spook::rotate<S>(V::Zero(), V::UnitX()), spook::Error);
  // Vectors whose squared norm overflows or underflows keep their direction.
  const S huge = std::numeric_limits<S>::max() / S(4), tiny = std::numeric_limits<S>::denorm_min();
  CHECK((spook::rotate<S>(V(huge, huge, S(0)), V(S(0), S(0), huge)) * V(S(1), S(1), S(0)).normalized() - V::UnitZ())
            .norm() < tol);
  CHECK((spook::rotate<S>(V(tiny, S(0), S(0)), V(S(0), tiny, S(0))) * V::UnitX() - V::UnitY()).norm() < tol);
  // Random and nearly antiparallel pairs: a unit quaternion taking a onto b,
  // with no component about a × b's normal plane (the shortest arc: its
  // angle is acos(a·b)).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const V a = V(S(u(rng)), S(u(rng)), S(u(rng))).normalized();
    const S tilt = S(std::pow(10.0, -8.0 * (i % 5) / 4.0));
    const V b = i % 2 ? V((-a + tilt * a.unitOrthogonal()).normalized()) : V(V(S(u(rng)), S(u(rng)), S(u(rng))).normalized());
    const spook::QuatT<S> q = spook::rotate<S>(a, b);
    CHECK(std::abs(q.norm() - S(1)) < tol);
    CHECK((q * a - b).norm() < S(10) * tol);
    const S angle = S(2) * std::atan2(q.vec().norm(), std::abs(q.w()));
    CHECK(std::abs(angle - std::acos(std::clamp(a.dot(b), S(-1), S(1)))) < S(10) * std::sqrt(tol));
  }
}

TEST_CASE_TEMPLATE("exp and log of rotations are inverse, small angles included", S, float, double) {
  const S tol = pick<S>(1e-14, 1e-6);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (double scale : {1e-9, 1e-5, 1e-3, 0.5, 3.0}) {
    for (int i = 0; i < 100; ++i) {
      spook::Vec3T<S> phi(S(u(rng)), S(u(rng)), S(u(rng)));
      phi *= S(scale) / std::max(phi.norm(), S(1e-3));
      const spook::QuatT<S> q = spook::expRotation<S>(phi);
      CHECK(std::abs(q.norm() - S(1)) < tol);
      CHECK((spook::logRotation<S>(q) - phi).norm() < tol * std::max(S(1), phi.norm()));
      const spook::QuatT<S> reference(Eigen::AngleAxis<S>(phi.norm(), phi.normalized()));
      CHECK(std::abs(std::abs(q.dot(reference)) - S(1)) < tol);
    }
  }
}

TEST_CASE_TEMPLATE("an SPD matrix accepts inertia tensors and rejects the rest", S, float, double) {
  using M = spook::Mat3T<S>;
  M good;
  good << S(2), S(0.1), S(0), S(0.1), S(3), S(0.2), S(0), S(0.2), S(4);
  CHECK(spook::SPDMat3T<S>(good).matrix() == good);
  M negative = M::Identity();
  negative(2, 2) = S(-1);
  M singular = M::Identity();
  singular(0, 0) = S(0);
  M skewed = M::Identity();
  skewed(0, 1) = S(0.5);
  CHECK_THROWS_AS(spook::SPDMat3T<S>{negative}, spook::Error);
  CHECK_THROWS_AS(spook::SPDMat3T<S>{singular}, spook::Error);
  CHECK_THROWS_AS(spook::SPDMat3T<S>{skewed}, spook::Error);
}

TEST_CASE_TEMPLATE("a rigid transform and its inverse compose to the identity", S, float, double) {
  const S tol = pick<S>(1e-14, 1e-6);
  const auto X = spook::makeTransform<S>(spook::Vec3T<S>(S(1), S(-2), S(3)),
                                         spook::toQuat(spook::EulerAnglesT<S>{S(0.1), S(0.2), S(0.3)}));
  CHECK(((X * X.inverse()).matrix() - Eigen::Matrix<S, 4, 4>::Identity()).norm() < tol);
  CHECK(((X.inverse() * spook::Vec3T<S>(S(1), S(-2), S(3)))).norm() < tol);
}
