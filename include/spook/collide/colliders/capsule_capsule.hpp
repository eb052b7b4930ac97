#pragma once

#include <algorithm>
#include <cmath>

#include <spook/collide/collider.hpp>
#include <spook/collide/detail/segment_distance.hpp>
#include <spook/collide/shapes/capsule.hpp>

namespace spook {

/// Capsule–capsule: the closest points a, b of the two core segments give
/// the deepest contact, depth r_a + r_b − |b − a| along (b − a)/|b − a|.
/// Segments that meet have no such direction; they push along the common
/// perpendicular d_a × d_b (turned toward b's center), or, when they are
/// also parallel, along a fixed perpendicular of a's axis.
///
/// Nearly parallel capsules (|sin θ| <= kParallelSine between the axes)
/// lying side by side touch along a line, and one point would let them roll
/// about it: the ends of the stretch where their axes overlap (the part of
/// a's segment onto which b's segment projects) add a contact each, with
/// the exact depth between that point of a's axis and the nearest point of
/// b's. The deepest contact is always reported, so the largest depth is the
/// exact penetration.
template <Scalar S>
struct Collider<CapsuleT<S>, CapsuleT<S>> {
  static constexpr S kParallelSine = S(1e-2);

  static void collide(const CapsuleT<S>& a, const TransformT<S>& X_WA, const CapsuleT<S>& b, const TransformT<S>& X_WB,
                      ContactSinkT<S>& sink) {
    const Vec3T<S> halfA = X_WA.linear().col(1) * (S(0.5) * a.getHeight());
    const Vec3T<S> halfB = X_WB.linear().col(1) * (S(0.5) * b.getHeight());
    const Vec3T<S> pA = X_WA.translation() - halfA, qA = X_WA.translation() + halfA;
    const Vec3T<S> pB = X_WB.translation() - halfB, qB = X_WB.translation() + halfB;
    const S rA = a.getRadius(), rB = b.getRadius();
    const S scale = rA + rB + a.getHeight() + b.getHeight();
    const auto closest = detail::closestPointsBetweenSegments<S>(pA, qA, pB, qB);

    // The direction for points closer than round-off, where b − a has none.
    Vec3T<S> fallback;
    const Vec3T<S> across = halfA.cross(halfB);
    if (!closest.parallel && across.norm() > S(0)) {
      fallback = across.normalized();
      if (fallback.dot(X_WB.translation() - X_WA.translation()) < S(0)) fallback = -fallback;
    } else {
      fallback = X_WA.linear().col(0);
    }
    const S tiny = ScalarTraits<S>::epsilon() * scale;
    const auto addAlong = [&](const Vec3T<S>& onA, const Vec3T<S>& onB, const Vec3T<S>& n, S distance) {
      const S depth = rA + rB - distance;
      if (!sink.accepts(depth)) return false;
      sink.addSpeculative(S(0.5) * (onA + onB + (rA - rB) * n), n, depth);
      return true;
    };
    const auto add = [&](const Vec3T<S>& onA, const Vec3T<S>& onB) {
      const Vec3T<S> d = onB - onA;
      const S distance = d.norm();
      return addAlong(onA, onB, distance > tiny ? Vec3T<S>(d / distance) : fallback, distance);
    };
    const bool inside = closest.s > S(0) && closest.s < S(1) && closest.t > S(0) && closest.t < S(1);
    if (inside && !closest.parallel) {
      // Closest points inside both segments are those of the two lines: the
      // normal is their common perpendicular and the distance its projection
      // of pB − pA, both free of the round-off in s and t, which would tilt
      // the normal by ε/distance for nearly crossing axes.
      const Vec3T<S> d = closest.onSecond - closest.onFirst;
      const Vec3T<S> n = d.dot(fallback) < S(0) ? Vec3T<S>(-fallback) : fallback;
      if (!addAlong(closest.onFirst, closest.onSecond, n, std::abs(n.dot(pB - pA)))) return;
    } else if (!add(closest.onFirst, closest.onSecond)) {
      return;
    }

    const Vec3T<S> dA = qA - pA, dB = qB - pB;
    const S lengthA2 = dA.squaredNorm();
    if (!(across.squaredNorm() * S(16) <= kParallelSine * kParallelSine * lengthA2 * dB.squaredNorm())) return;
    // The stretch of a's segment (parameters on a) that b's projects onto.
    const S s0 = dA.dot(pB - pA) / lengthA2, s1 = dA.dot(qB - pA) / lengthA2;
    const S lo = std::max(S(0), std::min(s0, s1)), hi = std::min(S(1), std::max(s0, s1));
    if (!(lo < hi)) return;
    const S apart = std::sqrt(ScalarTraits<S>::epsilon()) * scale;  // ends closer than this are the same contact
    const S lengthA = std::sqrt(lengthA2);
    for (const S s : {lo, hi}) {
      if (std::abs(s - closest.s) * lengthA <= apart) continue;
      const Vec3T<S> onA = pA + s * dA;
      add(onA, detail::closestPointOnSegment<S>(pB, qB, onA));
    }
  }
};

}  // namespace spook
