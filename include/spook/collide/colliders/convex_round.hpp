#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/cylinder_rim.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/convex.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/sphere.hpp>
#include <spook/collide/supporting_feature.hpp>

namespace spook {

namespace detail {

/// A face of a convex hull placed at X_WH (world, double): heights above
/// its plane and whether a point's foot lies on its polygon.
template <Scalar S>
struct PlacedHullFace {
  Vec3T<double> normal;                // outward, world
  std::vector<Vec3T<double>> corners;  // world, counter-clockwise about the normal

  PlacedHullFace(const ConvexT<S>& hull, const typename ConvexT<S>::Face& face, const TransformT<double>& X_WH)
      : normal(X_WH.linear() * face.normal.template cast<double>()) {
    corners.reserve(face.vertices.size());
    for (const auto index : face.vertices)
      corners.push_back(X_WH * hull.getVertices()[static_cast<std::size_t>(index)].template cast<double>());
  }

  [[nodiscard]] double height(const Vec3T<double>& p) const { return normal.dot(p - corners.front()); }
  [[nodiscard]] bool over(const Vec3T<double>& p) const {
    const std::size_t n = corners.size();
    for (std::size_t k = 0; k < n; ++k)
      if ((corners[(k + 1) % n] - corners[k]).cross(p - corners[k]).dot(normal) < 0.0) return false;
    return true;
  }
};

/// The face of a hull (at X_WH) that a convex shape (`other`, at X_WO) lies
/// farthest beyond (the least separation of the hull's face axes: a lower
/// bound on their distance, exact where the shape's nearest point is over
/// that face), and how far; or, with a unit `along` (world), the face whose
/// normal is closest to it, and its cosine. Null for a hull without faces.
template <Scalar S>
const typename ConvexT<S>::Face* hullFace(const ConvexT<S>& hull, const TransformT<double>& X_WH,
                                          const ConvexSupport& other, const TransformT<double>& X_WO,
                                          const Vec3T<double>* along, double& score) {
  const typename ConvexT<S>::Face* best = nullptr;
  for (const auto& f : hull.getFaces()) {
    const Vec3T<double> normal = X_WH.linear() * f.normal.template cast<double>();
    const auto corner = [&] {
      return X_WH * hull.getVertices()[static_cast<std::size_t>(f.vertices.front())].template cast<double>();
    };
    const double s = along ? normal.dot(*along)
                           : normal.dot(X_WO * other.supportAlong(X_WO.linear().transpose() * -normal) - corner());
    if (!best || s > score) {
      best = &f;
      score = s;
    }
  }
  return best;
}

/// Gap points of a shape (`other`, at X_WO) apart from a convex hull (at
/// X_WH) by up to the sink's margin across one of the hull's faces (the
/// one it lies farthest beyond, hullFace): the corners of the shape's
/// supporting feature against that face whose feet lie on its polygon,
/// each apart from the face's plane, and so from the hull, by exactly its
/// height. Apart across an edge or a corner of the hull none: one there
/// would stop a body that slides or rolls over the seam of two flush hulls
/// (a ghost contact). Normals point from the first shape of the pair to the
/// second (`hullFirst`).
template <Scalar S>
void hullFaceGapPoints(const ConvexT<S>& hull, const TransformT<S>& X_WH, const ConvexSupport& other,
                       const TransformT<S>& X_WO, ContactSinkT<S>& sink, bool hullFirst) {
  if (sink.margin() == S(0) || !other.feature) return;
  const TransformT<double> H = X_WH.template cast<double>(), O = X_WO.template cast<double>();
  double farthest = 0.0;
  const auto* best = hullFace<S>(hull, H, other, O, nullptr, farthest);
  const double touching = kTouchingGap * std::min(other.size, shapeSize(hull));
  if (!best || !(farthest > touching) || !sink.accepts(S(-farthest))) return;
  const PlacedHullFace<S> face(hull, *best, H);
  SupportingFeatureT<double> feature;
  other.feature(other.shape, O.linear().transpose() * -face.normal, feature);
  for (std::size_t i = 0; i < feature.count; ++i) {
    const Vec3T<double> p = O * feature.points[i];
    const double height = face.height(p);
    if (height > 0.0 && sink.accepts(S(-height), S(touching)) && face.over(p))
      sink.addSpeculative(Vec3T<double>(p - 0.5 * height * face.normal).cast<S>(),
                          Vec3T<double>(hullFirst ? face.normal : Vec3T<double>(-face.normal)).cast<S>(), S(-height),
                          S(touching));
  }
}

/// libccd's contacts (collideByCcd) of a convex hull and a sphere or a
/// capsule; apart, the gap points across the hull's faces
/// (hullFaceGapPoints). Without them a ball or a capsule set 1 cm above a
/// hull fell a step of free fall into it (88 mm at h = 0.1 s), as onto a
/// box it did not.
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

/// Convex–sphere: libccd, with gap points across the hull's faces.
template <Scalar S>
struct Collider<ConvexT<S>, SphereT<S>> {
  static void collide(const ConvexT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    detail::collideHullAndRound<S>(a, X_WA, b, X_WB, sink);
  }
};

/// Convex–cylinder, as box–cylinder: across a face of the hull the cylinder
/// meets it as it meets a plane, its rim candidates
/// (detail::cylinderRimCandidates) over the face's polygon, touching or,
/// within the sink's margin, gap points. That face is the one along
/// libccd's normal (within the supporting-feature angle) where the two
/// overlap, the one the cylinder lies farthest beyond where they are apart.
/// Elsewhere (across an edge of the hull, or touching the face beyond its
/// polygon) the contacts are libccd's, and apart there are no gap points.
/// With libccd's points alone a cylinder set 1 cm above a box-shaped hull
/// fell 88 mm into it at h = 0.1 s; with the eight corners of its cap's
/// feature as gap points Gauss–Seidel tipped it and rocked it on one point,
/// 22 mm deep (on a plane's four rim points 2.1 mm).
template <Scalar S>
struct Collider<ConvexT<S>, CylinderT<S>> {
  static void collide(const ConvexT<S>& a, const TransformT<S>& X_WA, const CylinderT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    std::vector<ContactPointT<S>> found;
    ContactSinkT<S> staging = sink.staging(found);
    detail::collideByCcd<S>(a, X_WA, b, X_WB, staging);
    const auto passOn = [&] {
      for (const auto& p : found) sink.add(p.point, p.normal, p.depth);
    };
    const TransformT<double> H = X_WA.template cast<double>(), C = X_WB.template cast<double>();
    const detail::ConvexSupport cylinder = detail::convexSupportOf(b);
    const Vec3T<double> libccdNormal = found.empty() ? Vec3T<double>(Vec3T<double>::UnitZ())
                                                     : Vec3T<double>(found.front().normal.template cast<double>());
    double score = 0.0;
    const auto* best = detail::hullFace<S>(a, H, cylinder, C, found.empty() ? nullptr : &libccdNormal, score);
    if (!best) return passOn();
    if (!found.empty() && score < kSupportingFeatureCos) return passOn();
    if (found.empty() && !(score > 0.0 && sink.accepts(S(-score)))) return;

    const detail::PlacedHullFace<S> face(a, *best, H);
    const double touching = detail::kTouchingGap * std::min(cylinder.size, detail::shapeSize(a));
    const auto candidates =
        detail::cylinderRimCandidates<double>(C.translation(), C.linear().col(1), C.linear().col(0),
                                              double(b.getRadius()), 0.5 * double(b.getHeight()), face.normal);
    const auto over = [&](const Vec3T<double>& p) { return face.over(p); };
    const std::size_t before = sink.size();
    if (!detail::addRimPointsOverFace<S>(
            candidates, face.normal, face.corners.front(), touching, 1.0, over,
            [&](const Vec3T<double>& p) { return !over(p); }, sink))
      return passOn();
    if (sink.size() == before) passOn();
  }
};

}  // namespace spook
