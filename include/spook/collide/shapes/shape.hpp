#pragma once

#include <cmath>
#include <string>

#include <spook/collide/bounding_box.hpp>
#include <spook/collide/shapes/shape_type.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// A geometric primitive in its own frame (origin at its center of volume).
/// It knows its volume, its inertia for a given mass and its bounding box;
/// convex shapes also give their support point. Lengths in meters.
template <Scalar S>
class ShapeT : public Referenced {
 public:
  using Vec3 = spook::Vec3T<S>;

  /// Which kind of shape this is; every concrete shape class also states it
  /// as `static constexpr ShapeType kType`.
  [[nodiscard]] virtual ShapeType getType() const = 0;
  /// Volume (m³); 0 for shapes that enclose none (Plane, Line, HeightField,
  /// an open Trimesh), which then add no mass to a body.
  [[nodiscard]] virtual S getVolume() const = 0;
  /// Inertia tensor about the shape origin, in the shape frame, for a
  /// uniform body of `mass` kg (kg·m²).
  [[nodiscard]] virtual SPDMat3T<S> calculateInertia(S mass) const = 0;
  /// Tight axis-aligned box in the shape frame (m).
  [[nodiscard]] virtual BoundingBoxT<S> getBoundingBox() const = 0;
  /// Center of volume in the shape frame (m); the origin for primitives.
  [[nodiscard]] virtual Vec3 getCenterOfVolume() const { return Vec3::Zero(); }

 protected:
  ~ShapeT() override = default;

  static void requireMass(const char* kind, S mass) {
    if (!(std::isfinite(mass) && mass > S(0)))
      throw detail::makeError(kind, "", "mass for the inertia must be finite and > 0 kg", mass);
  }
  static S requireLength(const char* kind, const char* what, S value) {
    if (!(std::isfinite(value) && value > S(0)))
      throw detail::makeError(kind, "", std::string(what) + " must be finite and > 0 m", value);
    return value;
  }
};

namespace detail {

/// Bounding box of a convex shape from its support function along ±x, ±y, ±z.
template <Scalar S, class Convex>
BoundingBoxT<S> boundingBoxFromSupport(const Convex& shape) {
  BoundingBoxT<S> box;
  for (int i = 0; i < 3; ++i) {
    const Vec3T<S> axis = Vec3T<S>::Unit(i);
    box.max[i] = shape.support(axis)[i];
    box.min[i] = shape.support(-axis)[i];
  }
  return box;
}

}  // namespace detail
}  // namespace spook
