#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/plane.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Plane–sphere: the plane is the solid half-space below it, so a sphere
/// whose center c lies at signed height s above the plane penetrates by
/// r − s (also when c is below the plane), along the plane normal.
template <Scalar S>
struct Collider<PlaneT<S>, SphereT<S>> {
  static void collide(const PlaneT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WA.linear() * a.getNormal();
    const Vec3T<S> c = X_WB.translation();
    const S height = n.dot(c - X_WA * a.getPoint());
    const S r = b.getRadius();
    const S depth = r - height;
    if (!sink.accepts(depth)) return;
    // Midway between the plane point under c, c − s n, and the sphere's deepest point c − r n.
    sink.addSpeculative(c - S(0.5) * (height + r) * n, n, depth);
  }
};

}  // namespace spook
