#pragma once

#include <cmath>

#include <spook/core/math.hpp>

namespace spook {

/// Axis-aligned box [min, max] (m), in whatever frame its owner states.
template <Scalar S>
struct BoundingBoxT {
  Vec3T<S> min = Vec3T<S>::Zero();
  Vec3T<S> max = Vec3T<S>::Zero();

  [[nodiscard]] Vec3T<S> center() const { return S(0.5) * (min + max); }
  [[nodiscard]] Vec3T<S> halfExtents() const { return S(0.5) * (max - min); }
  /// This box grown by `fraction` of its half-diagonal on every side (an
  /// unbounded box stays as it is).
  [[nodiscard]] BoundingBoxT grownBy(S fraction) const {
    const S margin = fraction * halfExtents().norm();
    if (!std::isfinite(margin)) return *this;
    return {min.array() - margin, max.array() + margin};
  }
  [[nodiscard]] bool contains(const Vec3T<S>& p, S tolerance = S(0)) const {
    return (p.array() >= min.array() - tolerance).all() && (p.array() <= max.array() + tolerance).all();
  }
};

}  // namespace spook
