#pragma once

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/shapes/line.hpp>
#include <spook/collide/shapes/sphere.hpp>

namespace spook {

/// Line–sphere: the segment point q closest to the sphere center c gives
/// one contact of depth r − |c − q| along (c − q)/|c − q|; a center on the
/// segment pushes along a fixed perpendicular of the segment.
template <Scalar S>
struct Collider<LineT<S>, SphereT<S>> {
  static void collide(const LineT<S>& a, const TransformT<S>& X_WA, const SphereT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> p = X_WA * a.getFirstPoint(), q = X_WA * a.getSecondPoint();
    const Vec3T<S> c = X_WB.translation();
    const S t = detail::closestParameterOnSegment<S>(p, q, c);
    const Vec3T<S> onLine = p + t * (q - p);
    const S r = b.getRadius();
    Vec3T<S> d = c - onLine;
    // Along the segment's interior c − q is perpendicular to it: made exactly
    // so, round-off cannot tilt the normal toward the segment.
    if (t > S(0) && t < S(1)) d -= (q - p) * ((q - p).dot(d) / (q - p).squaredNorm());
    const S distance = d.norm();
    const S depth = r - distance;
    if (!(depth >= S(0))) return;
    const Vec3T<S> n = distance > ScalarTraits<S>::epsilon() * (r + a.getLength()) ? Vec3T<S>(d / distance)
                                                                                  : detail::unitPerpendicular<S>(q - p);
    // Midway between the segment point and the sphere's deepest point c − r n.
    sink.add(S(0.5) * (onLine + c - r * n), n, depth);
  }
};

}  // namespace spook
