#pragma once

// The nodes a wire is routed with (wire/wire.hpp), after agxWire's: a
// FreeNode is a routing point (a free end when first or last), a
// BodyFixedNode fixes an end of the wire to a body or to the world, a
// ContactNode routes it over a geometry (a sheave).

#include <cmath>
#include <limits>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook {

template <Scalar S>
class WireT;

template <Scalar S>
class WireNodeT : public Referenced {
 public:
  using Vec3 = Vec3T<S>;
  enum class Type { FREE, BODY_FIXED, CONTACT };

  [[nodiscard]] Type getType() const { return type_; }
  /// The body a body-fixed or contact node moves with; nullptr for the
  /// world and for a free node.
  [[nodiscard]] virtual RigidBodyT<S>* getRigidBody() const { return body_.get(); }
  /// Where the node is routed: in the body's model frame for a node fixed
  /// to a body, in the geometry's frame for a contact node, else in world
  /// coordinates (m).
  [[nodiscard]] const Vec3& getPosition() const { return position_; }
  /// The node's routed position in world coordinates now (m).
  [[nodiscard]] virtual Vec3 getWorldPosition() const {
    return body_ ? Vec3(body_->getFrame()->transformPointToWorld(position_)) : position_;
  }

 protected:
  WireNodeT(Type type, RigidBodyT<S>* body, const Vec3& position) : type_(type), body_(body), position_(position) {
    if (!position.allFinite())
      throw detail::makeError(type == Type::FREE         ? "FreeNode"
                              : type == Type::BODY_FIXED ? "BodyFixedNode"
                                                         : "ContactNode",
                              "", "position must be finite m", position);
  }
  ~WireNodeT() override = default;

 private:
  Type type_;
  ref_ptr<RigidBodyT<S>> body_;
  Vec3 position_;
};

/// A routing point at a world position (m); a free end of the wire when it
/// is the first or last node of the route.
template <Scalar S>
class FreeNodeT : public WireNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  explicit FreeNodeT(const Vec3& position) : WireNodeT<S>(WireNodeT<S>::Type::FREE, nullptr, position) {}
  FreeNodeT(S x, S y, S z) : FreeNodeT(Vec3(x, y, z)) {}
};

/// An end of the wire fixed to `body` at `position` in its model frame, or
/// to the world at `position` (world coordinates) when `body` is nullptr.
/// Only the first or last node of a route may be body-fixed.
template <Scalar S>
class BodyFixedNodeT : public WireNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  BodyFixedNodeT(RigidBodyT<S>* body, const Vec3& position)
      : WireNodeT<S>(WireNodeT<S>::Type::BODY_FIXED, body, position) {}
  BodyFixedNodeT(RigidBodyT<S>* body, S x, S y, S z) : BodyFixedNodeT(body, Vec3(x, y, z)) {}
};

/// The wire routed over a geometry (agxWire's ContactNode): a sheave. The
/// geometry's shape must be a cylinder; the wire wraps it in the plane across
/// its axis through its center, touching it at `position` (geometry frame),
/// arriving and leaving along tangents, and slides over it against friction
/// along the wire (the capstan law: it slips once the tensions' ratio on
/// both sides exceeds e^{μθ}). Neither first nor last in a route.
template <Scalar S>
class ContactNodeT : public WireNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  ContactNodeT(GeometryT<S>* geometry, const Vec3& position)
      : WireNodeT<S>(WireNodeT<S>::Type::CONTACT, nullptr, position), geometry_(geometry) {
    if (!geometry) throw detail::makeError("ContactNode", "", "needs a geometry", "nullptr");
  }
  ContactNodeT(GeometryT<S>* geometry, S x, S y, S z) : ContactNodeT(geometry, Vec3(x, y, z)) {}

  [[nodiscard]] GeometryT<S>* getGeometry() const { return geometry_.get(); }
  /// The geometry's body (as it is now), nullptr when it has none.
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const override { return geometry_->getRigidBody(); }
  [[nodiscard]] Vec3 getWorldPosition() const override {
    return Vec3(geometry_->getFrame()->transformPointToWorld(this->getPosition()));
  }
  /// Friction coefficient along the wire, >= 0; until set, the wire
  /// material's.
  [[nodiscard]] bool hasFrictionCoefficient() const { return friction_ >= S(0); }
  [[nodiscard]] S getFrictionCoefficient() const { return friction_; }
  void setFrictionCoefficient(S coefficient) {
    if (!(std::isfinite(coefficient) && coefficient >= S(0)))
      throw detail::makeError("ContactNode", "", "friction coefficient must be finite and >= 0", coefficient);
    friction_ = coefficient;
  }
  /// The angle the wire wraps the geometry (rad), as routed and then after
  /// each step.
  [[nodiscard]] S getWrapAngle() const { return S(wrap_); }
  /// Friction force of the geometry on the wire along it in the last step
  /// (N): the tension before the node minus the tension after it.
  [[nodiscard]] S getFrictionForce() const { return S(frictionForce_); }

 protected:
  ~ContactNodeT() override = default;

 private:
  template <Scalar>
  friend class WireT;
  ref_ptr<GeometryT<S>> geometry_;
  S friction_ = S(-1);
  double wrap_ = 0.0;
  double frictionForce_ = 0.0;
};

using WireNode = WireNodeT<double>;
using FreeNode = FreeNodeT<double>;
using BodyFixedNode = BodyFixedNodeT<double>;
using ContactNode = ContactNodeT<double>;
namespace f32 {
using WireNode = WireNodeT<float>;
using FreeNode = FreeNodeT<float>;
using BodyFixedNode = BodyFixedNodeT<float>;
using ContactNode = ContactNodeT<float>;
}  // namespace f32

}  // namespace spook
