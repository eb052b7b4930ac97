#pragma once

#include <algorithm>
#include <cstddef>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/collide/supporting_feature.hpp>

namespace spook {

namespace detail {

/// Gap points of a shape (`other`, at X_WO) apart from a convex hull (at
/// X_WH) by up to the sink's margin across one of the hull's faces: the
/// face the shape lies farthest beyond (the least separation of the hull's
/// face axes, a lower bound on the distance), and on it the corners of the
/// shape's supporting feature against it whose feet lie on the face
/// polygon; each such corner is apart from the face's plane, and so from
/// the hull, by exactly its height. Apart across an edge or a corner of
/// the hull none: one there would stop a body that slides or rolls over the
/// seam of two flush hulls (a ghost contact). Normals point from the first
/// shape of the pair to the second (`hullFirst`).
template <Scalar S>
void hullFaceGapPoints(const ConvexT<S>& hull, const TransformT<S>& X_WH, const ConvexSupport& other,
                       const TransformT<S>& X_WO, ContactSinkT<S>& sink, bool hullFirst) {
  if (sink.margin() == S(0) || hull.getFaces().empty() || !other.feature) return;
  const TransformT<double> H = X_WH.template cast<double>(), O = X_WO.template cast<double>();
  const auto& vertices = hull.getVertices();
  const auto cornerOf = [&](int k) {
    return Vec3T<double>(H * vertices[static_cast<std::size_t>(k)].template cast<double>());
  };
  const typename ConvexT<S>::Face* best = nullptr;
  double farthest = 0.0;
  Vec3T<double> n = Vec3T<double>::UnitZ();
  for (const auto& f : hull.getFaces()) {
    const Vec3T<double> normal = H.linear() * f.normal.template cast<double>();
    const Vec3T<double> lowest = O * other.supportAlong(O.linear().transpose() * -normal);
    const double height = normal.dot(lowest - cornerOf(f.vertices.front()));
    if (!best || height > farthest) {
      best = &f;
      farthest = height;
      n = normal;
    }
  }
  const double touching = kTouchingGap * std::min(other.size, shapeSize(hull));
  if (!best || !(farthest > touching) || !sink.accepts(S(-farthest))) return;
  SupportingFeatureT<double> feature;
  other.feature(other.shape, O.linear().transpose() * -n, feature);
  const Vec3T<double> origin = cornerOf(best->vertices.front());
  const std::size_t corners = best->vertices.size();
  for (std::size_t i = 0; i < feature.count; ++i) {
    const Vec3T<double> p = O * feature.points[i];
    const double height = n.dot(p - origin);
    if (!(height > 0.0) || !sink.accepts(S(-height), S(touching))) continue;
    const Vec3T<double> foot = p - height * n;
    bool over = true;
    for (std::size_t k = 0; k < corners && over; ++k) {
      const Vec3T<double> from = cornerOf(best->vertices[k]), to = cornerOf(best->vertices[(k + 1) % corners]);
      over = (to - from).cross(foot - from).dot(n) >= 0.0;
    }
    if (over)
      sink.addSpeculative(Vec3T<double>(foot + 0.5 * height * n).cast<S>(),
                          Vec3T<double>(hullFirst ? n : Vec3T<double>(-n)).cast<S>(), S(-height), S(touching));
  }
}

/// libccd's contacts (collideByCcd) of a convex hull and a round shape;
/// apart, the gap points across the hull's faces (hullFaceGapPoints).
/// Without them a ball, capsule or wheel set 1 cm above a hull fell a step
/// of free fall into it (8.8 cm at h = 0.1 s), as onto a box it did not.
template <Scalar S, class A, class B>
void collideHullAndRound(const A& a, const TransformT<S>& X_WA, const B& b, const TransformT<S>& X_WB,
                         ContactSinkT<S>& sink) {
  const std::size_t before = sink.size();
  collideByCcd<S>(a, X_WA, b, X_WB, sink);
  if (sink.size() != before) return;
  if constexpr (A::kType == ShapeType::CONVEX)
    hullFaceGapPoints<S>(a, X_WA, convexSupportOf(b), X_WB, sink, true);
  else
    hullFaceGapPoints<S>(b, X_WB, convexSupportOf(a), X_WA, sink, false);
}

}  // namespace detail

/// Capsule–convex: libccd, with gap points across the hull's faces.
template <Scalar S>
struct Collider<CapsuleT<S>, ConvexT<S>> {
  static void collide(const CapsuleT<S>& a, const TransformT<S>& X_WA, const ConvexT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideHullAndRound<S>(a, X_WA, b, X_WB, sink);
  }
};

/// Convex–cylinder: libccd, with gap points across the hull's faces.
template <Scalar S>
struct Collider<ConvexT<S>, CylinderT<S>> {
  static void collide(const ConvexT<S>& a, const TransformT<S>& X_WA, const CylinderT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideHullAndRound<S>(a, X_WA, b, X_WB, sink);
  }
};

/// Convex–sphere: libccd, with gap points across the hull's faces.
template <Scalar S>
struct Collider<ConvexT<S>, SphereT<S>> {
  static void collide(const ConvexT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideHullAndRound<S>(a, X_WA, b, X_WB, sink);
  }
};

}  // namespace spook
