#pragma once

// Helpers of the colliders' tests: poses and a collide that checks every
// contact it gets is finite with a unit normal and lies in the overlap,
// within its depth (+1e-6 m) of both shapes' surfaces.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/collider.hpp>
#include <spook/collide/colliders/mesh.hpp>

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

// The distance (m) from p (world) to the surface of shape placed at X_W
// (shape → world): exact for the round shapes, boxes, lines, planes and
// meshes; for a hull the largest face distance, exact inside and a lower
// bound outside. Negative for a point outside every kind it knows nothing of.
template <class Shape, class S = typename Shape::Vec3::Scalar>
double surfaceDistance(const Shape& shape, const spook::TransformT<S>& X_W, const spook::Vec3T<S>& p_W) {
  using V = spook::Vec3T<double>;
  const V p = (X_W.inverse() * p_W).template cast<double>();
  constexpr auto kType = Shape::kType;
  using Type = spook::ShapeType;
  if constexpr (kType == Type::SPHERE) {
    return std::abs(p.norm() - double(shape.getRadius()));
  } else if constexpr (kType == Type::BOX) {
    const V q = p.cwiseAbs() - shape.getHalfExtents().template cast<double>();
    return std::abs(q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0));
  } else if constexpr (kType == Type::CAPSULE) {
    const double h = 0.5 * double(shape.getHeight());
    const V axis(0, std::clamp(p.y(), -h, h), 0);
    return std::abs((p - axis).norm() - double(shape.getRadius()));
  } else if constexpr (kType == Type::CYLINDER) {
    const double radial = std::hypot(p.x(), p.z()) - double(shape.getRadius());
    const double axial = std::abs(p.y()) - 0.5 * double(shape.getHeight());
    return std::abs(std::hypot(std::max(radial, 0.0), std::max(axial, 0.0)) + std::min(std::max(radial, axial), 0.0));
  } else if constexpr (kType == Type::LINE) {
    return (spook::detail::closestOnSegment<double>(shape.getFirstPoint().template cast<double>(),
                                                     shape.getSecondPoint().template cast<double>(), p) - p).norm();
  } else if constexpr (kType == Type::PLANE) {
    return std::abs(shape.getNormal().template cast<double>().dot(p - shape.getPoint().template cast<double>()));
  } else if constexpr (kType == Type::CONVEX) {
    double distance = -std::numeric_limits<double>::infinity();
    for (const auto& f : shape.getFaces())
      distance = std::max(distance, f.normal.template cast<double>().dot(p) - double(f.offset));
    return std::abs(distance);
  } else if constexpr (kType == Type::TRIMESH || kType == Type::HEIGHTFIELD) {
    double distance = std::numeric_limits<double>::infinity();
    const spook::Vec3T<S> p_S = p.template cast<S>();
    const S reach(1);
    shape.forEachTriangle(spook::BoundingBoxT<S>{p_S - spook::Vec3T<S>::Constant(reach), p_S + spook::Vec3T<S>::Constant(reach)},
                          [&](std::size_t, const spook::Vec3T<S>& a, const spook::Vec3T<S>& b, const spook::Vec3T<S>& c) {
                            bool onFace = false;
                            const spook::detail::Triangle<double> t{{a.template cast<double>(), b.template cast<double>(),
                                                                     c.template cast<double>()}};
                            distance = std::min(distance, (spook::detail::closestOnTriangle<double>(t, p, onFace) - p).norm());
                          });
    return distance;
  } else {
    return -1.0;
  }
}

// spook::collide on the pair, every contact checked finite with a unit
// normal, and within its depth (+1e-6 m, float 1e-4 m relative to the
// coordinates) of both shapes' surfaces: on the contact, not far from it.
template <class A, class B, class S = typename A::Vec3::Scalar>
Points<S> contacts(const A& a, const spook::TransformT<S>& X_WA, const B& b, const spook::TransformT<S>& X_WB) {
  Points<S> points;
  spook::ContactSinkT<S> sink(points);
  spook::collide(a, X_WA, b, X_WB, sink);
  for (const auto& p : points) {
    CHECK(p.point.allFinite());
    CHECK(std::isfinite(p.depth));
    CHECK(p.depth >= S(0));
    CHECK(std::abs(p.normal.norm() - S(1)) <= pick<S>(1e-12, 1e-6));
    const double slack = pick<S>(1e-6, 1e-4 * (1.0 + double(p.point.norm())));
    for (const double distance : {surfaceDistance(a, X_WA, p.point), surfaceDistance(b, X_WB, p.point)}) {
      CAPTURE(p.point);
      CAPTURE(p.depth);
      CHECK(distance <= double(p.depth) + slack);
    }
  }
  return points;
}

template <class S>
bool near(const spook::Vec3T<S>& a, const spook::Vec3T<S>& b, S tolerance) {
  return (a - b).norm() <= tolerance;
}

}  // namespace spook::test
