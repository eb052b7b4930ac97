#pragma once

#include <spook/core/math.hpp>

namespace spook {

/// Axis-aligned box [min, max] (m), in whatever frame its owner states.
template <Scalar S>
struct BoundingBoxT {
  Vec3<S> min = Vec3<S>::Zero();
  Vec3<S> max = Vec3<S>::Zero();

  [[nodiscard]] Vec3<S> center() const { return S(0.5) * (min + max); }
  [[nodiscard]] Vec3<S> halfExtents() const { return S(0.5) * (max - min); }
  [[nodiscard]] bool contains(const Vec3<S>& p, S tolerance = S(0)) const {
    return (p.array() >= min.array() - tolerance).all() && (p.array() <= max.array() + tolerance).all();
  }
};

}  // namespace spook
