#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

#include <spook/core/math.hpp>

namespace spook::detail {

/// A convex polygon of at most 8 corners on the stack: a quadrilateral
/// clipped by the 4 side planes of a rectangle gains at most one corner per
/// plane.
template <Scalar S>
struct ClipPolygon {
  static constexpr std::size_t kCapacity = 8;
  std::array<Vec3T<S>, kCapacity> points;
  std::size_t count = 0;

  void push(const Vec3T<S>& p) {
    if (count < kCapacity) points[count++] = p;
  }
};

/// One Sutherland–Hodgman step: the part of `polygon` in the half-space
/// normal·x <= offset. A corner on the plane is kept (once); an edge that
/// strictly crosses the plane gains its crossing point.
template <Scalar S>
[[nodiscard]] ClipPolygon<S> clipPolygon(const ClipPolygon<S>& polygon, const Vec3T<S>& normal, S offset) {
  ClipPolygon<S> out;
  for (std::size_t i = 0; i < polygon.count; ++i) {
    const Vec3T<S>& p = polygon.points[i];
    const Vec3T<S>& q = polygon.points[(i + 1) % polygon.count];
    const S dp = normal.dot(p) - offset, dq = normal.dot(q) - offset;
    if (dp <= S(0)) out.push(p);
    if ((dp < S(0) && dq > S(0)) || (dp > S(0) && dq < S(0))) out.push(Vec3T<S>(p + (q - p) * (dp / (dp - dq))));
  }
  return out;
}

/// Closest points of the segments p + s·u, |s| <= sMax, and q + t·v,
/// |t| <= tMax, for unit u and v that are not parallel (the box edges and
/// capsule axis of the box colliders): the closest points of the two lines,
/// then each parameter clamped with the other one re-projected onto it.
template <Scalar S>
void clampedLineClosest(const Vec3T<S>& p, const Vec3T<S>& u, S sMax, const Vec3T<S>& q, const Vec3T<S>& v, S tMax, S& s,
                        S& t) {
  const Vec3T<S> w = q - p;
  const S b = u.dot(v), d = u.dot(w), e = v.dot(w);
  const S denominator = S(1) - b * b;  // |u × v|²
  s = denominator > S(0) ? (d - b * e) / denominator : S(0);
  s = std::clamp(s, -sMax, sMax);
  t = std::clamp(b * s - e, -tMax, tMax);
  s = std::clamp(b * t + d, -sMax, sMax);
}

}  // namespace spook::detail
