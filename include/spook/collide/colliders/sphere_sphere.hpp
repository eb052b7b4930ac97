#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Sphere–sphere: one contact along the line of centers, depth
/// r_a + r_b − |c_b − c_a|. Coincident centers (closer than round-off of
/// the radii) have no line of centers; they push along world +z.
template <Scalar S>
struct Collider<SphereT<S>, SphereT<S>> {
  static void collide(const SphereT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> cA = X_WA.translation(), cB = X_WB.translation();
    const S rA = a.getRadius(), rB = b.getRadius();
    const Vec3T<S> d = cB - cA;
    const S distance = d.norm();
    const S depth = rA + rB - distance;
    if (!sink.accepts(depth)) return;
    const Vec3T<S> n = distance > ScalarTraits<S>::epsilon() * (rA + rB) ? Vec3T<S>(d / distance) : Vec3T<S>::UnitZ();
    // Midway between a's deepest point cA + rA n and b's, cB − rB n.
    sink.addSpeculative(S(0.5) * (cA + cB + (rA - rB) * n), n, depth);
  }
};

}  // namespace spook
