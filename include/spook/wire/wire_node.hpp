#pragma once

// The nodes a wire is routed with (wire/wire.hpp), after agxWire's: a
// FreeNode is a routing point (a free end when first or last), a
// BodyFixedNode fixes an end of the wire to a body or to the world.

#include <cmath>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook {

template <Scalar S>
class WireNodeT : public Referenced {
 public:
  using Vec3 = Vec3T<S>;
  enum class Type { FREE, BODY_FIXED };

  [[nodiscard]] Type getType() const { return type_; }
  /// A body-fixed node's body; nullptr for the world and for a free node.
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const { return body_.get(); }
  /// Where the node is routed: in the body's model frame for a node fixed
  /// to a body, else in world coordinates (m).
  [[nodiscard]] const Vec3& getPosition() const { return position_; }
  /// The node's routed position in world coordinates now (m).
  [[nodiscard]] Vec3 getWorldPosition() const {
    return body_ ? Vec3(body_->getFrame()->transformPointToWorld(position_)) : position_;
  }

 protected:
  WireNodeT(Type type, RigidBodyT<S>* body, const Vec3& position) : type_(type), body_(body), position_(position) {
    if (!position.allFinite())
      throw detail::makeError(type == Type::FREE ? "FreeNode" : "BodyFixedNode", "",
                              "position must be finite m", position);
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

using WireNode = WireNodeT<double>;
using FreeNode = FreeNodeT<double>;
using BodyFixedNode = BodyFixedNodeT<double>;
namespace f32 {
using WireNode = WireNodeT<float>;
using FreeNode = FreeNodeT<float>;
using BodyFixedNode = BodyFixedNodeT<float>;
}  // namespace f32

}  // namespace spook
