#pragma once

// The nodes a wire is routed with (wire/wire.hpp), after agxWire's: a
// FreeNode is a routing point (a free end when first or last), a
// BodyFixedNode fixes an end of the wire to a body or to the world (a
// ConnectingNode clamps it to a body), a
// ContactNode routes it over a geometry (a sheave), an EyeNode through an
// eye on a body or the world.

#include <cmath>
#include <limits>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/collide/shapes/box.hpp>
#include <spook/collide/shapes/cylinder.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook {

template <Scalar S>
class WireT;
template <Scalar S>
class WireLinkT;

template <Scalar S>
class WireNodeT : public Referenced {
 public:
  using Vec3 = Vec3T<S>;
  enum class Type { FREE, BODY_FIXED, CONTACT, EYE, CONNECTING };

  [[nodiscard]] Type getType() const { return type_; }
  /// The body a body-fixed, eye or contact node moves with; nullptr for
  /// the world and for a free node.
  [[nodiscard]] virtual RigidBodyT<S>* getRigidBody() const { return body_.get(); }
  /// Where the node is routed: in the body's model frame for a node fixed
  /// to a body (an end or an eye), in the geometry's frame for a contact
  /// node, else in world coordinates (m).
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
                              : type == Type::EYE        ? "EyeNode"
                              : type == Type::CONNECTING ? "ConnectingNode"
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

/// An end of the wire clamped to `body` at `position` in its model frame
/// (agxWire's ConnectingNode): as a BodyFixedNode, and the wire leaves the
/// body along the line from its center of mass through `position` (an
/// extra point at the center of mass, moving with the body), its bend
/// across the connection held by a bending modulus (setBendStiffness; until
/// set, the wire's): a socket, a clamped pipe. Optionally the body's twist
/// about the wire is held too (setTwistStiffness). `body` may not be
/// nullptr, and `position` not at its center of mass while the bend is
/// held. Only the first or last node of a route. A WireLink
/// (wire/wire_link.hpp) connects wires through such nodes.
template <Scalar S>
class ConnectingNodeT : public WireNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  ConnectingNodeT(RigidBodyT<S>* body, const Vec3& position)
      : WireNodeT<S>(WireNodeT<S>::Type::CONNECTING, body, position) {
    if (!body) throw detail::makeError("ConnectingNode", "", "needs a body", "nullptr");
  }
  ConnectingNodeT(RigidBodyT<S>* body, S x, S y, S z) : ConnectingNodeT(body, Vec3(x, y, z)) {}

  /// Young's modulus (Pa, finite, >= 0) of the bend across the connection,
  /// between the line from the body's center of mass through the node and
  /// the wire's first segment: 0 lets the wire turn freely there (a pin); at
  /// most the wire's own modulus of bending takes effect. Until set, the
  /// wire's (a link's connections: 0).
  [[nodiscard]] bool hasBendStiffness() const { return bendStiffness_ >= S(0); }
  [[nodiscard]] S getBendStiffness() const { return bendStiffness_; }
  void setBendStiffness(S youngsModulus) {
    if (!(std::isfinite(youngsModulus) && youngsModulus >= S(0)))
      throw detail::makeError("ConnectingNode", "", "bend stiffness must be finite and >= 0 Pa", youngsModulus);
    bendStiffness_ = youngsModulus;
  }
  /// Shear modulus G (Pa, finite, >= 0) of the wire's twist: the body's
  /// rotation about the wire at the connection meets the torsional
  /// stiffness G·J/L of the whole wire (J = πr⁴/2, L its rest length), its
  /// other end taken as held against twist (it feels no torque back).
  /// 0 (the default): the body turns freely about the wire.
  [[nodiscard]] S getTwistStiffness() const { return twistStiffness_; }
  void setTwistStiffness(S shearModulus) {
    if (!(std::isfinite(shearModulus) && shearModulus >= S(0)))
      throw detail::makeError("ConnectingNode", "", "twist stiffness must be finite and >= 0 Pa", shearModulus);
    twistStiffness_ = shearModulus;
  }
  /// The body's rotation about the wire at the connection since the node
  /// was connected (rad, right-handed about the direction into the wire).
  [[nodiscard]] S getTwistAngle() const { return S(twist_); }
  /// The link this node connects the wire to, nullptr for a plain
  /// ConnectingNode.
  [[nodiscard]] WireLinkT<S>* getLink() const { return link_; }

 protected:
  ~ConnectingNodeT() override = default;

 private:
  template <Scalar>
  friend class WireT;
  template <Scalar>
  friend class WireLinkT;
  S bendStiffness_ = S(-1);
  S twistStiffness_ = S(0);
  WireLinkT<S>* link_ = nullptr;
  ref_ptr<Referenced> linkHeld_;  ///< keeps link_ alive
  /// Twist state, kept by the wire: angle (rad), the last step's row
  /// impulse (N·m·s) and time step (s; 0 before the first).
  double twist_ = 0.0;
  double twistImpulse_ = 0.0;
  double twistStep_ = 0.0;
};

/// A node the wire slides over or through against friction along it (a
/// ContactNode, an EyeNode): the capstan law over the angle θ the wire turns
/// there, so that it slips once the tensions' ratio on both sides exceeds
/// e^{μθ}. The coefficient may differ by the direction the wire slides in.
template <Scalar S>
class SlidingNodeT : public WireNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  /// FORWARD: the wire slides towards its end (its start side is pulled
  /// in); BACKWARD: towards its start. Relative to the wire: reversing the
  /// wire swaps them.
  enum class Direction { FORWARD, BACKWARD };

  /// Friction coefficient along the wire, >= 0; until set, the wire
  /// material's. Without a direction: both directions (getting: FORWARD).
  [[nodiscard]] bool hasFrictionCoefficient(Direction direction = Direction::FORWARD) const {
    return friction_[int(direction)] >= S(0);
  }
  [[nodiscard]] S getFrictionCoefficient(Direction direction = Direction::FORWARD) const {
    return friction_[int(direction)];
  }
  void setFrictionCoefficient(S coefficient) {
    setFrictionCoefficient(coefficient, Direction::FORWARD);
    friction_[1] = friction_[0];
  }
  void setFrictionCoefficient(S coefficient, Direction direction) {
    if (!(std::isfinite(coefficient) && coefficient >= S(0)))
      throw detail::makeError(this->getType() == WireNodeT<S>::Type::EYE ? "EyeNode" : "ContactNode", "",
                              "friction coefficient must be finite and >= 0", coefficient);
    friction_[int(direction)] = coefficient;
  }
  /// The angle the wire turns at the node (rad): the arc it wraps a
  /// geometry by, or its deflection through an eye; as routed and then
  /// after each step.
  [[nodiscard]] S getWrapAngle() const { return S(wrap_); }
  /// Friction force of the node on the wire along it in the last step (N):
  /// the tension before the node minus the tension after it.
  [[nodiscard]] S getFrictionForce() const { return S(frictionForce_); }

 protected:
  using WireNodeT<S>::WireNodeT;
  ~SlidingNodeT() override = default;

 private:
  template <Scalar>
  friend class WireT;
  S friction_[2] = {S(-1), S(-1)};
  double wrap_ = 0.0;
  double frictionForce_ = 0.0;
};

/// The wire routed over a geometry (agxWire's ContactNode), holding one
/// cylinder, box, convex, trimesh or height field. Over a cylinder (a
/// sheave) the wire wraps it in the plane across its axis through its
/// center, touching it at `position` (geometry frame), arriving and leaving
/// along tangents. Over the others it runs across the edge nearest
/// `position` (a box's or a convex's edge, a trimesh's or a height field's
/// ridge: an edge where the surface folds away), turning there as through
/// an eye at the edge's point where its path is shortest (sliding along the
/// edge as the wire moves, held at its ends; the wire's radius is not offset
/// from the edge). It slides over either against friction (SlidingNodeT).
/// Neither first nor last in a route.
template <Scalar S>
class ContactNodeT : public SlidingNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  ContactNodeT(GeometryT<S>* geometry, const Vec3& position)
      : SlidingNodeT<S>(WireNodeT<S>::Type::CONTACT, nullptr, position), geometry_(geometry) {
    if (!geometry) throw detail::makeError("ContactNode", "", "needs a geometry", "nullptr");
  }
  ContactNodeT(GeometryT<S>* geometry, S x, S y, S z) : ContactNodeT(geometry, Vec3(x, y, z)) {}

  [[nodiscard]] GeometryT<S>* getGeometry() const { return geometry_.get(); }
  /// The geometry's body (as it is now), nullptr when it has none.
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const override { return geometry_->getRigidBody(); }
  [[nodiscard]] Vec3 getWorldPosition() const override {
    return Vec3(geometry_->getFrame()->transformPointToWorld(this->getPosition()));
  }
  /// Whole turns (0 to 1000) the wire makes around the geometry besides the
  /// routed wrap, as on a capstan or a bollard: each adds 2π to the wrap
  /// angle and 2πr of wire on the geometry (the turns lie side by side along
  /// its axis, which is not modeled). Read when the wire joins a simulation.
  [[nodiscard]] int getTurns() const { return turns_; }
  void setTurns(int turns) {
    if (!(turns >= 0 && turns <= 1000))
      throw detail::makeError("ContactNode", "", "turns must be within 0 and 1000", turns);
    turns_ = turns;
  }

 protected:
  ~ContactNodeT() override = default;

 private:
  ref_ptr<GeometryT<S>> geometry_;
  int turns_ = 0;
};

/// An eye the wire runs through (agxWire's EyeNode), fixed to `body` at
/// `position` in its model frame, or to the world (world coordinates) when
/// `body` is nullptr: the wire slides through it against friction
/// (SlidingNodeT) over the angle it is deflected by, in either direction,
/// and the eye's body carries the wire's pull. Neither first nor last in a
/// route.
template <Scalar S>
class EyeNodeT : public SlidingNodeT<S> {
 public:
  using Vec3 = Vec3T<S>;
  EyeNodeT(RigidBodyT<S>* body, const Vec3& position) : SlidingNodeT<S>(WireNodeT<S>::Type::EYE, body, position) {}
  EyeNodeT(RigidBodyT<S>* body, S x, S y, S z) : EyeNodeT(body, Vec3(x, y, z)) {}

 protected:
  ~EyeNodeT() override = default;
};

using WireNode = WireNodeT<double>;
using FreeNode = FreeNodeT<double>;
using BodyFixedNode = BodyFixedNodeT<double>;
using SlidingNode = SlidingNodeT<double>;
using ContactNode = ContactNodeT<double>;
using EyeNode = EyeNodeT<double>;
using ConnectingNode = ConnectingNodeT<double>;
namespace f32 {
using WireNode = WireNodeT<float>;
using FreeNode = FreeNodeT<float>;
using BodyFixedNode = BodyFixedNodeT<float>;
using SlidingNode = SlidingNodeT<float>;
using ContactNode = ContactNodeT<float>;
using EyeNode = EyeNodeT<float>;
using ConnectingNode = ConnectingNodeT<float>;
}  // namespace f32

}  // namespace spook
