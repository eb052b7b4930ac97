#pragma once

#include <cmath>

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Box–sphere, in the box frame. A sphere center c outside the box pushes
/// away from the box point q closest to it (c clamped to the half extents):
/// depth r − |c − q|. A center inside the box, or on its surface, pushes out
/// through the nearest face, the one with the smallest h_i − |c_i| (the
/// lowest axis on a tie, the + face when c_i = 0): depth r + h_i − |c_i|.
/// Within the sink's speculative margin, a sphere off a face (not off an
/// edge or a corner) gives its gap point.
template <Scalar S>
struct Collider<BoxT<S>, SphereT<S>> {
  static void collide(const BoxT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S>& h = a.getHalfExtents();
    const S r = b.getRadius();
    const Vec3T<S> c = X_WA.inverse(Eigen::Isometry) * X_WB.translation();
    const Vec3T<S> q = c.cwiseMax(-h).cwiseMin(h);
    const Vec3T<S> d = c - q;
    const S distance = d.norm();
    Vec3T<S> n;      // box frame, from the box toward the sphere
    Vec3T<S> onBox;  // the box's deepest point along n
    S depth;
    if (distance > ScalarTraits<S>::epsilon() * (h.norm() + r)) {
      depth = r - distance;
      // Gap points only off a face: off an edge or a corner, the gap closes
      // slower than its linear rate says (a sphere rolling over the seam
      // of two boxes would be stopped by the next one's edge).
      const bool offFace = (c.array().abs() > h.array()).count() == 1;
      if (!(depth >= S(0) || (offFace && sink.accepts(depth)))) return;
      n = d / distance;
      onBox = q;
    } else {
      int axis = 0;
      S gap = h[0] - std::abs(c[0]);  // distance from c to the nearest face, >= 0 up to round-off
      for (int i = 1; i < 3; ++i) {
        const S g = h[i] - std::abs(c[i]);
        if (g < gap) {
          gap = g;
          axis = i;
        }
      }
      n = Vec3T<S>::Zero();
      n[axis] = c[axis] < S(0) ? S(-1) : S(1);
      depth = r + gap;
      onBox = c + gap * n;
    }
    // Midway between the box's deepest point and the sphere's, c − r n.
    sink.addSpeculative(X_WA * Vec3T<S>(S(0.5) * (onBox + c - r * n)), X_WA.linear() * n, depth);
  }
};

}  // namespace spook
