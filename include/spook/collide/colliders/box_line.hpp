#pragma once

#include <algorithm>
#include <cmath>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/line.hpp>

namespace spook {

/// Box–line, in the box frame, for a segment x(t) = p + t d, t ∈ [0, 1].
///
/// Depth: the penetration depth proper, the shortest distance the line has
/// to move to leave the box, D = min over unit n of f(n) = h_box(n) −
/// min_t n·x(t) (the overlap of the two projections on n), the same measure
/// as every other convex pair and as the libccd fallback. The box ⊕ segment
/// difference is a polytope whose faces have the box face normals e_i and
/// the cross products d × e_i as normals, so the minimum is over these six
/// axes, both signs each (the separating axis theorem); a negative overlap
/// on any of them separates the shapes. Cross products shorter than
/// round-off (d along a box edge) are dropped: they are face normals then,
/// and the overlap they would bound differs from a face's by less than
/// their length.
///
/// Points: the line's deepest point along −n is the contact's line side,
/// midway to the box surface at depth D. On a face normal that is the
/// deepest endpoint, unless a point of the segment's part inside the box
/// (clipped against the three slabs |x_i| <= h_i) is as deep, as for a
/// segment lying in a face; on an edge axis every segment point is as deep
/// and the point closest to the box's supporting edge is taken. A segment
/// nearly parallel to the face (|sin| <= kParallelSine) also gets a contact
/// at each end of its inside part, with that point's own depth, so that a
/// rod lying across a face rests on two points.
template <Scalar S>
struct Collider<BoxT<S>, LineT<S>> {
  static constexpr S kParallelSine = S(1e-2);

  static void collide(const BoxT<S>& a, const TransformT<S>& X_WA, const LineT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const TransformT<S> X_AB = X_WA.inverse(Eigen::Isometry) * X_WB;
    const Vec3T<S> p = X_AB * b.getFirstPoint(), q = X_AB * b.getSecondPoint();
    const Vec3T<S> d = q - p;
    const Vec3T<S>& h = a.getHalfExtents();
    const S length = d.norm();
    const S tiny = S(16) * ScalarTraits<S>::epsilon() * (h.norm() + p.norm() + q.norm());

    // Separating axis test: the smallest overlap and its axis, from the box toward the line.
    S depth = S(0);
    Vec3T<S> n = Vec3T<S>::UnitZ();
    int edge = -1;  // the box edge direction of a cross-product axis, -1 for a face normal
    bool first = true;
    const auto tryAxis = [&](const Vec3T<S>& axis, int edgeAxis) {
      const S support = h.dot(axis.cwiseAbs());
      const S lowest = std::min(axis.dot(p), axis.dot(q)), highest = std::max(axis.dot(p), axis.dot(q));
      const S up = support - lowest, down = support + highest;  // overlaps along +axis and −axis
      if (first || up < depth) {
        depth = up;
        n = axis;
        edge = edgeAxis;
        first = false;
      }
      if (down < depth) {
        depth = down;
        n = -axis;
        edge = edgeAxis;
      }
    };
    for (int i = 0; i < 3; ++i) tryAxis(Vec3T<S>::Unit(i), -1);
    for (int i = 0; i < 3; ++i) {
      const Vec3T<S> axis = d.cross(Vec3T<S>::Unit(i));
      const S axisLength = axis.norm();
      if (axisLength > S(16) * ScalarTraits<S>::epsilon() * length) tryAxis(axis / axisLength, i);
    }
    if (!(depth >= S(0))) return;

    const auto add = [&](const Vec3T<S>& onLine, S pointDepth) {
      sink.add(X_WA * Vec3T<S>(onLine + S(0.5) * pointDepth * n), X_WA.linear() * n, pointDepth);
    };
    if (edge >= 0) {
      // The box edge along e_edge through the corner farthest along n.
      Vec3T<S> corner = a.support(n);
      Vec3T<S> otherEnd = corner;
      corner[edge] = -h[edge];
      otherEnd[edge] = h[edge];
      add(detail::closestPointsBetweenSegments<S>(p, q, corner, otherEnd).onFirst, depth);
      return;
    }

    // The part of the segment inside the box, t ∈ [t0, t1] (empty when t0 > t1).
    S t0 = S(0), t1 = S(1);
    for (int i = 0; i < 3; ++i) {
      if (d[i] != S(0)) {
        const S ta = (-h[i] - p[i]) / d[i], tb = (h[i] - p[i]) / d[i];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
      } else if (std::abs(p[i]) > h[i]) {
        t0 = S(1);
        t1 = S(0);
      }
    }
    const S support = h.dot(n.cwiseAbs());
    const auto depthAt = [&](S t) { return support - n.dot(p + t * d); };
    S deepest = depthAt(S(0)) >= depthAt(S(1)) ? S(0) : S(1);
    if (t0 <= t1) {
      const S inside = depthAt(t0) >= depthAt(t1) ? t0 : t1;
      if (depthAt(inside) >= depth - tiny) deepest = inside;
    }
    add(p + deepest * d, depth);
    if (!(t0 <= t1 && std::abs(n.dot(d)) <= kParallelSine * length)) return;
    const S apart = std::sqrt(ScalarTraits<S>::epsilon()) * (h.norm() + length);  // closer is the same contact
    const S ends[2] = {t0, t1};
    for (int k = 0; k < 2; ++k) {
      const S t = ends[k];
      if (std::abs(t - deepest) * length <= apart || (k == 1 && (t1 - t0) * length <= apart)) continue;
      const S pointDepth = depthAt(t);
      if (pointDepth >= S(0)) add(p + t * d, pointDepth);
    }
  }
};

}  // namespace spook
