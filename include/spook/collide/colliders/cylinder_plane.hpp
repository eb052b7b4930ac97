#pragma once

#include <array>

#include <spook/collide/collider.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/collide/shapes/plane.hpp>

namespace spook {

/// Cylinder–plane: the deepest points of a cylinder are on its rims. On
/// each cap rim the candidates are four points 90° apart, starting from the
/// rim point farthest below the plane, v = −(n − (n·u) u)/|…| for axis u
/// (the cylinder's own x axis when the axis is along n and every rim point
/// is as deep); each candidate at or below the plane is a contact of depth
/// −(its signed height). So a tilted cylinder resting on its rim has one
/// contact, one lying on its side two (one per cap), one standing on a cap
/// four spread around the rim, and the deepest rim point is always among
/// them. The normal points from the cylinder into the plane, −n.
template <Scalar S>
struct Collider<CylinderT<S>, PlaneT<S>> {
  static void collide(const CylinderT<S>& a, const TransformT<S>& X_WA, const PlaneT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> n = X_WB.linear() * b.getNormal();
    const Vec3T<S> u = X_WA.linear().col(1);
    // Along the rim, away from the plane's outside; projected off u once
    // more, since for a cylinder standing nearly upright (n ≈ ±u) the first
    // difference is round-off that need not be ⟂ u (in float it made rim
    // points below the cap).
    Vec3T<S> across = (n.dot(u)) * u - n;
    across -= across.dot(u) * u;
    const S acrossLength = across.norm();
    const Vec3T<S> v =
        acrossLength > ScalarTraits<S>::epsilon() ? Vec3T<S>(across / acrossLength) : Vec3T<S>(X_WA.linear().col(0));
    const Vec3T<S> w = u.cross(v);
    const std::array<Vec3T<S>, 4> rim = {v, w, Vec3T<S>(-v), Vec3T<S>(-w)};
    const S r = a.getRadius(), halfHeight = S(0.5) * a.getHeight();
    const Vec3T<S> onPlane = X_WB * b.getPoint();
    for (const S side : {S(-1), S(1)}) {
      const Vec3T<S> capCenter = X_WA.translation() + side * halfHeight * u;
      const S capHeight = n.dot(capCenter - onPlane);
      for (const Vec3T<S>& direction : rim) {
        const S height = capHeight + r * n.dot(direction);
        if (!sink.accepts(-height)) continue;
        // Midway between the rim point and the plane point under it.
        sink.addSpeculative(capCenter + r * direction - S(0.5) * height * n, -n, -height);
      }
    }
  }
};

}  // namespace spook
