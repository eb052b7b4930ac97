#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/plane.hpp>

namespace spook {

/// Line–plane: each segment endpoint at or below the plane (signed height
/// s <= 0) is a contact of depth −s, so a segment lying in or under the
/// plane has two. The normal points from the line into the plane, −n.
template <Scalar S>
struct Collider<LineT<S>, PlaneT<S>> {
  static void collide(const LineT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S> onPlane = X_WB * b.getPoint();
    for (const Vec3T<S>& end : {a.getFirstPoint(), a.getSecondPoint()}) {
      const Vec3T<S> e = X_WA * end;
      const S height = n.dot(e - onPlane);
      // Midway between the endpoint and the plane point under it.
      if (height <= S(0)) sink.add(e - S(0.5) * height * n, -n, -height);
    }
  }
};

}  // namespace spook
