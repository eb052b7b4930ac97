#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/cylinder_rim.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/plane.hpp>

namespace spook {

/// Cylinder–plane: the deepest points of a cylinder are on its rims
/// (detail::cylinderRimCandidates); each candidate at or below the plane is
/// a contact of depth −(its signed height). So a tilted cylinder resting on
/// its rim has one contact, one lying on its side two (one per cap), one
/// standing on a cap four spread around the rim, and the deepest rim point
/// is always among them. The normal points from the cylinder into the
/// plane, −n.
template <Scalar S>
struct Collider<CylinderT<S>, PlaneT<S>> {
  static void collide(const CylinderT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S> onPlane = X_WB * b.getPoint();
    for (const Vec3T<S>& p :
         detail::cylinderRimCandidates<S>(X_WA.translation(), X_WA.linear().col(1), X_WA.linear().col(0), a.getRadius(),
                                          S(0.5) * a.getHeight(), n)) {
      const S height = n.dot(p - onPlane);
      if (!sink.accepts(-height)) continue;
      // Midway between the rim point and the plane point under it.
      sink.addSpeculative(p - S(0.5) * height * n, -n, -height);
    }
  }
};

}  // namespace spook
