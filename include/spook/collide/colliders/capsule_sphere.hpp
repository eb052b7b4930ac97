#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/shapes/capsule.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Capsule–sphere: the sphere center c against the capsule's core segment
/// (its hemisphere centers, ±height/2 along the capsule's y): one contact
/// from the segment point q closest to c, depth r_a + r_b − |c − q|. A
/// center on the segment pushes along the capsule's own x axis, which is
/// perpendicular to the segment.
template <Scalar S>
struct Collider<CapsuleT<S>, SphereT<S>> {
  static void collide(const CapsuleT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> halfAxis = X_WA.linear().col(1) * (S(0.5) * a.getHeight());
    const Vec3T<S> center = X_WA.translation(), c = X_WB.translation();
    const S t = detail::closestParameterOnSegment<S>(center - halfAxis, center + halfAxis, c);
    const Vec3T<S> q = center + (S(2) * t - S(1)) * halfAxis;
    const S rA = a.getRadius(), rB = b.getRadius();
    Vec3T<S> d = c - q;
    // Off an end the closest point is that end; along the side, c − q is
    // perpendicular to the axis, and making it exactly so keeps the normal
    // from tilting toward the axis by round-off when c is near it.
    if (t > S(0) && t < S(1)) d -= X_WA.linear().col(1) * X_WA.linear().col(1).dot(d);
    const S distance = d.norm();
    const S depth = rA + rB - distance;
    if (!sink.accepts(depth)) return;
    const Vec3T<S> n = distance > ScalarTraits<S>::epsilon() * (rA + rB + a.getHeight()) ? Vec3T<S>(d / distance)
                                                                                        : Vec3T<S>(X_WA.linear().col(0));
    sink.addSpeculative(S(0.5) * (q + c + (rA - rB) * n), n, depth);
  }
};

}  // namespace spook
