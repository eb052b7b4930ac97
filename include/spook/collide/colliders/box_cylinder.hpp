#pragma once

#include <cmath>
#include <vector>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/ccd_bridge.hpp>
#include <spook/collide/detail/cylinder_rim.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/supporting_feature.hpp>

namespace spook {

/// Box–cylinder. Across a face of the box the cylinder meets it as it meets
/// a plane (Collider<CylinderT, PlaneT>): its rim candidates
/// (detail::cylinderRimCandidates) over the face's rectangle, touching or,
/// within the sink's margin, gap points. That face is the one along
/// libccd's penetration normal (within the supporting-feature angle) where
/// the two overlap, the one the cylinder lies farthest beyond where they
/// are apart. Elsewhere (the cylinder across an edge of the box, or
/// touching the face beyond its rectangle) the contacts are libccd's
/// (detail::collideByCcd), and apart there are no gap points: off an edge
/// one would stop a wheel rolling over the seam of two flush boxes.
/// libccd's points alone let a wheel set 1 cm above a box fall a step of
/// free fall into it (8.8 cm at h = 0.1 s; through it under a 2.5 kN load)
/// and gave a wheel lying on a face one point where its tilt passed the
/// feature angle, on which the iterative solver rocked it 1 cm deep.
template <Scalar S>
struct Collider<BoxT<S>, CylinderT<S>> {
  static void collide(const BoxT<S>& a, const TransformT<S>& X_WA, const CylinderT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    using Vec3 = Vec3T<S>;
    std::vector<ContactPointT<S>> found;
    ContactSinkT<S> staging = sink.staging(found);
    detail::collideByCcd<S>(a, X_WA, b, X_WB, staging);
    const auto passOn = [&] {
      for (const auto& p : found) sink.add(p.point, p.normal, p.depth);
    };
    const Vec3 c = X_WA.translation(), e = a.getHalfExtents();
    const auto& R = X_WA.linear();
    int axis = -1;
    S along = S(-1);
    Vec3 n = Vec3::UnitZ();
    for (int k = 0; k < 3; ++k)
      for (const S side : {S(-1), S(1)}) {
        const Vec3 face = side * R.col(k);
        // Overlapping: the face nearest libccd's normal; apart: the face the
        // cylinder lies farthest beyond.
        const S score = found.empty() ? face.dot(X_WB * b.support(X_WB.linear().transpose() * -face) - c) - e[k]
                                      : face.dot(found.front().normal);
        if (axis < 0 || score > along) {
          axis = k;
          along = score;
          n = face;
        }
      }
    if (!found.empty() && along < S(kSupportingFeatureCos)) return passOn();
    if (found.empty() && !(along > S(0) && sink.accepts(-along))) return;

    const S touching = S(detail::kTouchingGap * std::min(detail::shapeSize(a), detail::shapeSize(b)));
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const auto onFace = [&](const Vec3& p) {
      const Vec3 d = p - c;
      return std::abs(R.col(a1).dot(d)) <= e[a1] && std::abs(R.col(a2).dot(d)) <= e[a2];
    };
    const auto candidates = detail::cylinderRimCandidates<S>(
        X_WB.translation(), X_WB.linear().col(1), X_WB.linear().col(0), b.getRadius(), S(0.5) * b.getHeight(), n);
    const std::size_t before = sink.size();
    if (!detail::addRimPointsOverFace<S>(
            candidates, n, Vec3(c + e[axis] * n), touching, S(1), onFace, [&](const Vec3& p) { return !onFace(p); },
            sink))
      return passOn();
    if (sink.size() == before) passOn();
  }
};

}  // namespace spook
