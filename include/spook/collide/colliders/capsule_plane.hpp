#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/plane.hpp>

namespace spook {

/// Capsule–plane: each end sphere (hemisphere center e at signed height s
/// above the plane) that reaches the solid below the plane is a contact of
/// depth r − s: one for a tilted capsule, two for one lying on the plane.
/// The normal points from the capsule into the plane, −n.
template <Scalar S>
struct Collider<CapsuleT<S>, PlaneT<S>> {
  static void collide(const CapsuleT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S> onPlane = X_WB * b.getPoint();
    const Vec3T<S> halfAxis = X_WA.linear().col(1) * (S(0.5) * a.getHeight());
    const S r = a.getRadius();
    for (const S side : {S(-1), S(1)}) {
      const Vec3T<S> e = X_WA.translation() + side * halfAxis;
      const S height = n.dot(e - onPlane);
      const S depth = r - height;
      // Midway between the capsule's deepest point e − r n and the plane point under e, e − s n.
      if (sink.accepts(depth)) sink.addSpeculative(e - S(0.5) * (r + height) * n, -n, depth);
    }
  }
};

}  // namespace spook
