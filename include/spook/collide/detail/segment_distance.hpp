#pragma once

#include <algorithm>
#include <cmath>

#include <spook/core/math.hpp>

namespace spook::detail {

// Closest points between segments and points, the geometric core of every
// collider with a capsule or a line (Ericson, Real-Time Collision
// Detection, §5.1.2 and §5.1.9). All results are finite for any finite
// input, degenerate segments and parallel segments included.

/// Parameter t ∈ [0, 1] of the point of segment p + t (q − p) closest to x
/// (0 for a degenerate segment).
template <Scalar S>
[[nodiscard]] S closestParameterOnSegment(const Vec3T<S>& p, const Vec3T<S>& q, const Vec3T<S>& x) {
  const Vec3T<S> d = q - p;
  const S dd = d.squaredNorm();
  if (!(dd > S(0))) return S(0);
  return std::clamp(d.dot(x - p) / dd, S(0), S(1));
}

/// The point of segment [p, q] closest to x.
template <Scalar S>
[[nodiscard]] Vec3T<S> closestPointOnSegment(const Vec3T<S>& p, const Vec3T<S>& q, const Vec3T<S>& x) {
  return p + closestParameterOnSegment(p, q, x) * (q - p);
}

/// A unit vector perpendicular to d (any non-zero d), chosen deterministically:
/// d crossed with the coordinate axis least aligned with it.
template <Scalar S>
[[nodiscard]] Vec3T<S> unitPerpendicular(const Vec3T<S>& d) {
  int axis = 0;
  const Vec3T<S> a = d.cwiseAbs();
  if (a.y() < a[axis]) axis = 1;
  if (a.z() < a[axis]) axis = 2;
  const Vec3T<S> n = d.cross(Vec3T<S>::Unit(axis));
  const S length = n.norm();
  return length > S(0) ? Vec3T<S>(n / length) : Vec3T<S>(Vec3T<S>::UnitX());
}

/// The closest points of segments [p1, q1] and [p2, q2]: parameters s, t
/// ∈ [0, 1], the points themselves, and whether the segments are parallel
/// or degenerate (then the pair is one deterministic choice among many).
template <Scalar S>
struct SegmentClosestPoints {
  S s = S(0);
  S t = S(0);
  Vec3T<S> onFirst = Vec3T<S>::Zero();
  Vec3T<S> onSecond = Vec3T<S>::Zero();
  bool parallel = false;
};

/// Minimizes |p1 + s d1 − (p2 + t d2)|² over the unit square (Ericson
/// §5.1.9): the unconstrained minimum of the line pair is clamped to the
/// first segment, then the second parameter follows and is clamped, and the
/// first is recomputed once. Parallel (or degenerate) segments, where the
/// determinant a e − b² vanishes relative to a e, start from s = 0.
template <Scalar S>
[[nodiscard]] SegmentClosestPoints<S> closestPointsBetweenSegments(const Vec3T<S>& p1, const Vec3T<S>& q1,
                                                                   const Vec3T<S>& p2, const Vec3T<S>& q2) {
  const Vec3T<S> d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const S a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  SegmentClosestPoints<S> result;
  if (!(a > S(0)) && !(e > S(0))) {
    result.parallel = true;
  } else if (!(a > S(0))) {
    result.t = std::clamp(f / e, S(0), S(1));
    result.parallel = true;
  } else {
    const S c = d1.dot(r);
    if (!(e > S(0))) {
      result.s = std::clamp(-c / a, S(0), S(1));
      result.parallel = true;
    } else {
      const S b = d1.dot(d2);
      // a e − b² = |d1 × d2|², computed as such to keep its relative accuracy
      // for nearly parallel segments.
      const S denominator = d1.cross(d2).squaredNorm();
      result.parallel = !(denominator > S(4) * ScalarTraits<S>::epsilon() * a * e);
      S s = result.parallel ? S(0) : std::clamp((b * f - c * e) / denominator, S(0), S(1));
      S t = (b * s + f) / e;
      if (t < S(0)) {
        t = S(0);
        s = std::clamp(-c / a, S(0), S(1));
      } else if (t > S(1)) {
        t = S(1);
        s = std::clamp((b - c) / a, S(0), S(1));
      }
      result.s = s;
      result.t = t;
    }
  }
  result.onFirst = p1 + result.s * d1;
  result.onSecond = p2 + result.t * d2;
  return result;
}

}  // namespace spook::detail
