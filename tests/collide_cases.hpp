#pragma once

// Helpers of the colliders' degenerate-case tests: poses and a collide
// that checks every contact it gets is finite with a unit normal and, for
// two convex shapes, lies in their overlap (issue 24).

#include <doctest/doctest.h>

#include <cmath>
#include <type_traits>
#include <vector>

#include <spook/collide/collider.hpp>

#include "collide_reference.hpp"
#include "tolerance.hpp"

namespace spook::test {

template <class S>
using Points = std::vector<spook::ContactPointT<S>>;

template <class S>
spook::TransformT<S> at(S x, S y, S z) {
  spook::TransformT<S> X = spook::TransformT<S>::Identity();
  X.translation() = spook::Vec3T<S>(x, y, z);
  return X;
}

template <class S>
spook::TransformT<S> turned(const spook::TransformT<S>& X, S angle, const std::type_identity_t<spook::Vec3T<S>>& axis) {
  spook::TransformT<S> Y = X;
  Y.linear() = Eigen::AngleAxis<S>(angle, axis.normalized()).toRotationMatrix();
  return Y;
}

// spook::collide on the pair, every contact checked finite with a unit
// normal; between two convex shapes, within its depth (+1e-6 m, 1e-5 m in
// float) of both shapes' surfaces (pointExcess: in their overlap).
template <class A, class B, class S = typename A::Vec3::Scalar>
Points<S> contacts(const A& a, const spook::TransformT<S>& X_WA, const B& b, const spook::TransformT<S>& X_WB) {
  Points<S> points;
  spook::ContactSinkT<S> sink(points);
  spook::test::collideCompiled(a, X_WA, b, X_WB, sink);
  for (const auto& p : points) {
    CHECK(p.point.allFinite());
    CHECK(std::isfinite(p.depth));
    CHECK(p.depth >= S(0));
    CHECK(std::abs(p.normal.norm() - S(1)) <= pick<S>(1e-12, 1e-6));
    if constexpr (ConvexShape<A> && ConvexShape<B>) {
      CHECK(pointExcess(a, X_WA, b, X_WB, p.point.template cast<double>(),
                        p.normal.template cast<double>().normalized(), double(p.depth)) <= pick<S>(1e-6, 1e-5));
    }
  }
  return points;
}

template <class S>
bool near(const spook::Vec3T<S>& a, const spook::Vec3T<S>& b, S tolerance) {
  return (a - b).norm() <= tolerance;
}

}  // namespace spook::test
