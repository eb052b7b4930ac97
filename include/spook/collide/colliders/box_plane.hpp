#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/plane.hpp>

namespace spook {

/// Box–plane: every corner at or below the plane (signed height s <= 0) is
/// a contact of depth −s: four for a box lying flat on a face, two on an
/// edge, one on a corner. Corners above the plane by less than the touching
/// gap (detail::kTouchingGap of the box's size) touch it (depth 0), so that
/// a resting box tilted by round-off keeps its four. The normal points from
/// the box into the plane, −n.
template <Scalar S>
struct Collider<BoxT<S>, PlaneT<S>> {
  static void collide(const BoxT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S>& h = a.getHalfExtents();
    // Heights relative to the box center: corner height = center height + Σ ±h_i (n · axis_i).
    const S centerHeight = n.dot(X_WA.translation() - X_WB * b.getPoint());
    const Vec3T<S> reach = (X_WA.linear().transpose() * n).cwiseProduct(h);
    const S gap = S(detail::kTouchingGap) * h.norm();
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3T<S> sign((corner & 1) ? S(1) : S(-1), (corner & 2) ? S(1) : S(-1), (corner & 4) ? S(1) : S(-1));
      const S height = centerHeight + sign.dot(reach);
      if (!sink.accepts(-height, gap)) continue;
      const Vec3T<S> p = X_WA * Vec3T<S>(sign.cwiseProduct(h));
      // Midway between the corner and the plane point under it.
      sink.addSpeculative(p - S(0.5) * height * n, -n, -height, gap);
    }
  }
};

}  // namespace spook
