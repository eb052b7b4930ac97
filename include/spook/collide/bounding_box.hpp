#pragma once

#include <spook/core/math.hpp>

namespace spook {

/// Axis-aligned box [min, max] (m), in whatever frame its owner states.
template <Scalar S>
struct BoundingBoxT {
  Vec3T<S> min = Vec3T<S>::Zero();
  Vec3T<S> max = Vec3T<S>::Zero();

  [[nodiscard]] Vec3T<S> center() const { return S(0.5) * (min + max); }
  [[nodiscard]] Vec3T<S> halfExtents() const { return S(0.5) * (max - min); }
  [[nodiscard]] bool contains(const Vec3T<S>& p, S tolerance = S(0)) const {
    return (p.array() >= min.array() - tolerance).all() && (p.array() <= max.array() + tolerance).all();
  }
};

}  // namespace spook
