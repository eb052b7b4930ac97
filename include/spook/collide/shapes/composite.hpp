#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/shapes/shape.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

/// Child shapes placed by rigid transforms relative to the composite's
/// frame. Volume, inertia and bounding box are those of the union of the
/// children, assumed not to overlap, all of one density.
template <Scalar S>
class CompositeT : public ShapeT<S>, private detail::ShapeOwner<S> {
 public:
  static constexpr ShapeType kType = ShapeType::COMPOSITE;
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;
  using Transform = spook::TransformT<S>;
  using Shape = ShapeT<S>;

  struct Child {
    ref_ptr<Shape> shape;
    Transform transform;  ///< child frame → composite frame
  };

  CompositeT() = default;

  /// Adds a child at `transform` (child to composite); one shape may be
  /// added several times. Throws, adding nothing, on a null child, a child
  /// that contains this composite, a transform that is not finite and
  /// rigid, or a child that a body holding the composite could not take
  /// (its mass properties would not be finite and valid); else the body's
  /// generated mass properties follow.
  void add(ref_ptr<Shape> shape, const Transform& transform = Transform::Identity());

  [[nodiscard]] const std::vector<Child>& getChildren() const { return children_; }

  /// True when `shape` is this composite or anywhere among its descendants.
  [[nodiscard]] bool contains(const Shape* shape) const {
    if (shape == this) return true;
    for (const Child& c : children_) {
      if (c.shape.get() == shape) return true;
      if (const auto* nested = dynamic_cast<const CompositeT*>(c.shape.get()); nested && nested->contains(shape))
        return true;
    }
    return false;
  }

  [[nodiscard]] ShapeType getType() const override { return kType; }
  bool collideWithLowerRank(const TransformT<S>& X_WA, const ShapeT<S>& other, const TransformT<S>& X_WB,
                            ContactSinkT<S>& sink) const override {
    return detail::collideWithLowerRank(*this, X_WA, other, X_WB, sink);
  }

  [[nodiscard]] S getVolume() const override;

  /// Volume-weighted mean of the children's centers, composite frame (m).
  [[nodiscard]] Vec3 getCenterOfVolume() const override;

  /// About the composite origin. Each child gets the mass m Vᵢ/V; its tensor
  /// about its own origin is first moved to its center of volume cᵢ, then
  /// turned into the composite frame and moved to the origin (parallel-axis
  /// theorem both ways, J(m, d) = m(|d|² 1 − d dᵀ)):
  /// I = Σ Rᵢ (Iᵢ − J(mᵢ, cᵢ)) Rᵢᵀ + J(mᵢ, Xᵢ cᵢ).
  [[nodiscard]] SPDMat3T<S> calculateInertia(S mass) const override;

  /// Union of the children's boxes, each child box's corners transformed;
  /// unbounded (±infinity) when a child is.
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const override;

 protected:
  ~CompositeT() override;

 private:
  // A child changed: whatever holds this composite checks it and follows.
  void checkShapeChange() const override { this->checkOwners(); }
  void shapeChanged() override { this->notifyOwners(); }

  std::vector<Child> children_;
};

template <Scalar S>
void CompositeT<S>::add(ref_ptr<Shape> shape, const Transform& transform) {
  if (!shape) throw detail::makeError("Composite", "", "cannot add a null shape", "nullptr");
  const auto* nested = dynamic_cast<const CompositeT*>(shape.get());
  if (nested && nested->contains(this))
    throw detail::makeError("Composite", "", "a composite cannot contain itself", "a composite of its own chain");
  if (!(transform.matrix().allFinite() && isRotation<S>(transform.linear())))
    throw detail::makeError("Composite", "", "child transform must be finite and rigid",
                            SPDMat3T<S>::flat(transform.linear()));
  Shape& child = *shape;
  this->change(
      [&] {
        children_.push_back(
            {std::move(shape), makeTransform<S>(transform.translation(), QuatT<S>(transform.linear()))});
      },
      [&] { children_.pop_back(); });
  detail::ShapeOwners<S>::add(child, this);
}

template <Scalar S>
S CompositeT<S>::getVolume() const {
  S volume = S(0);
  for (const Child& c : children_) volume += c.shape->getVolume();
  return volume;
}

template <Scalar S>
auto CompositeT<S>::getCenterOfVolume() const -> Vec3 {
  Vec3 moment = Vec3::Zero();
  for (const Child& c : children_) moment += c.shape->getVolume() * (c.transform * c.shape->getCenterOfVolume());
  return moment / getVolume();
}

template <Scalar S>
auto CompositeT<S>::calculateInertia(S mass) const -> SPDMat3T<S> {
  this->requireMass("Composite", mass);
  const S volume = getVolume();
  if (!(volume > S(0))) throw detail::makeError("Composite", "", "inertia needs a positive volume (m^3)", volume);
  const auto shift = [](S m, const Vec3& d) {
    return Mat3(m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose()));
  };
  Mat3 inertia = Mat3::Zero();
  for (const Child& c : children_) {
    if (!(c.shape->getVolume() > S(0))) continue;  // a plane or a line carries no mass
    const S childMass = mass * (c.shape->getVolume() / volume);
    const Vec3 center = c.shape->getCenterOfVolume();
    const Mat3 aboutCenter = c.shape->calculateInertia(childMass).matrix() - shift(childMass, center);
    const Mat3 R = c.transform.linear();
    inertia += R * aboutCenter * R.transpose() + shift(childMass, c.transform * center);
  }
  return SPDMat3T<S>(inertia);
}

template <Scalar S>
auto CompositeT<S>::getBoundingBox() const -> BoundingBoxT<S> {
  if (children_.empty()) return {};
  BoundingBoxT<S> box{Vec3::Constant(std::numeric_limits<S>::max()), Vec3::Constant(std::numeric_limits<S>::lowest())};
  for (const Child& c : children_) {
    const BoundingBoxT<S> local = c.shape->getBoundingBox();
    if (!(local.min.allFinite() && local.max.allFinite())) {  // a plane child: unbounded
      return {Vec3::Constant(-std::numeric_limits<S>::infinity()), Vec3::Constant(std::numeric_limits<S>::infinity())};
    }
    const Mat3 R = c.transform.linear();
    const Vec3 center = c.transform * local.center();
    const Vec3 reach = R.cwiseAbs() * local.halfExtents();
    box.min = box.min.cwiseMin(center - reach);
    box.max = box.max.cwiseMax(center + reach);
  }
  return box;
}

template <Scalar S>
CompositeT<S>::~CompositeT() {
  for (Child& c : children_) detail::ShapeOwners<S>::remove(*c.shape, this);
}

SPOOK_COMPILED_WITH_COLLIDERS(class, CompositeT)

using Composite = CompositeT<double>;
using CompositeRef = ref_ptr<Composite>;
namespace f32 {
using Composite = CompositeT<float>;
using CompositeRef = ref_ptr<Composite>;
}  // namespace f32

}  // namespace spook
