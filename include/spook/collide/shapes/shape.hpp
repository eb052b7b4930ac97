#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <spook/collide/bounding_box.hpp>
#include <spook/collide/contact_sink.hpp>
#include <spook/collide/shapes/shape_type.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

template <Scalar S>
class ShapeT;

namespace detail {

/// The contacts of a with b, for a b whose type ranks at or below a's
/// (dispatchRank); false, writing nothing, for a pair without a collider.
/// Defined with the colliders (collide/shape_dispatch.hpp).
template <class A>
bool collideWithLowerRank(const A& a, const TransformT<typename A::Vec3::Scalar>& X_WA,
                          const ShapeT<typename A::Vec3::Scalar>& b, const TransformT<typename A::Vec3::Scalar>& X_WB,
                          ContactSinkT<typename A::Vec3::Scalar>& sink);

/// What holds a shape: a Geometry, or a Composite for its children. Asked,
/// after a shape it holds has changed (its size, children, heights), whether
/// it can take the change, and told once the change stands: the body that
/// owns it all refuses mass properties that would not be valid, and
/// recomputes them when they are.
template <Scalar S>
struct ShapeOwner {
  /// Throws spook::Error when the change could not be taken; changes nothing.
  virtual void checkShapeChange() const = 0;
  virtual void shapeChanged() = 0;

 protected:
  ~ShapeOwner() = default;
};

/// How geometries and composites register as the owners of their shapes.
template <Scalar S>
struct ShapeOwners {
  static void add(ShapeT<S>& shape, ShapeOwner<S>* owner) { shape.owners_.push_back(owner); }
  /// Drops one registration of `owner` (a composite may hold a shape twice).
  static void remove(ShapeT<S>& shape, ShapeOwner<S>* owner) {
    const auto it = std::find(shape.owners_.begin(), shape.owners_.end(), owner);
    if (it != shape.owners_.end()) shape.owners_.erase(it);
  }
};

}  // namespace detail

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

  /// Writes the contacts of this shape at X_WA with `other` at X_WB (shape
  /// frame → world; normals from this shape toward the other) when the
  /// other's type ranks at or below this one's (dispatchRank); returns
  /// whether the pair has a collider. The narrow phase asks the
  /// higher-ranked shape of a pair (detail::collideShapes), so that a
  /// program compiles the colliders of the shape types it constructs only.
  virtual bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT& other, const TransformT<S>& X_WB,
                                    ContactSinkT<S>& sink) const = 0;

 protected:
  ~ShapeT() override = default;

  /// Makes a change (`apply`) and has every owner check it; when one
  /// refuses, undoes it (`undo`) and rethrows, else tells them all.
  template <class Apply, class Undo>
  void change(Apply&& apply, Undo&& undo) {
    apply();
    try {
      checkOwners();
    } catch (...) {
      undo();
      throw;
    }
    notifyOwners();
  }
  void checkOwners() const;
  void notifyOwners();

  static void requireMass(const char* kind, S mass);
  static S requireLength(const char* kind, const char* what, S value);

 private:
  friend struct detail::ShapeOwners<S>;
  std::vector<detail::ShapeOwner<S>*> owners_;
};

template <Scalar S>
void ShapeT<S>::checkOwners() const {
  for (const detail::ShapeOwner<S>* owner : owners_) owner->checkShapeChange();
}

template <Scalar S>
void ShapeT<S>::notifyOwners() {
  for (detail::ShapeOwner<S>* owner : owners_) owner->shapeChanged();
}

template <Scalar S>
void ShapeT<S>::requireMass(const char* kind, S mass) {
  if (!(std::isfinite(mass) && mass > S(0)))
    throw detail::makeError(kind, "", "mass for the inertia must be finite and > 0 kg", mass);
}

template <Scalar S>
S ShapeT<S>::requireLength(const char* kind, const char* what, S value) {
  if (!(std::isfinite(value) && value > S(0)))
    throw detail::makeError(kind, "", std::string(what) + " must be finite and > 0 m", value);
  return value;
}

SPOOK_COMPILED_WITH_COLLIDERS(class, ShapeT)

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
