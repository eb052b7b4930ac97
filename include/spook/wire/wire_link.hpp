#pragma once

// A body in a wire chain (agxWire's Link): a shackle, a hook block, a
// swivel, connecting the ends of wires. Each wire's end is clamped to the
// link's body through a ConnectingNode (wire/wire_node.hpp) whose bend and
// twist stiffness are that connection's properties:
//
//   ref_ptr<WireLink> link = new WireLink(hookBlock);
//   upper->add(link, Vec3(0, 0, 0.2));   // the upper wire ends at the link
//   lower->add(link, Vec3(0, 0, -0.2));  // the lower wire starts at it
//   link->getConnectionProperties(*upper)->setTwistStiffness(8e10);

#include <spook/core/error.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/wire/wire_node.hpp>

namespace spook {

template <Scalar S>
class WireLinkT : public Referenced {
 public:
  using Vec3 = Vec3T<S>;
  explicit WireLinkT(RigidBodyT<S>* body) : body_(body) {
    if (!body) throw detail::makeError("WireLink", "", "needs a body", "nullptr");
  }
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const { return body_.get(); }

  /// The node clamping `wire`'s begin (looked for first) or end to this
  /// link: its connection properties (bend and twist stiffness, both 0
  /// until set, that is a pin free to turn). nullptr when `wire` is not
  /// connected here.
  template <class Wire>
  [[nodiscard]] ConnectingNodeT<S>* getConnectionProperties(const Wire& wire) const {
    const auto& route = wire.getRoute();
    if (route.empty()) return nullptr;
    for (WireNodeT<S>* node : {route.front().get(), route.back().get()})
      if (node->getType() == WireNodeT<S>::Type::CONNECTING && static_cast<ConnectingNodeT<S>*>(node)->link_ == this)
        return static_cast<ConnectingNodeT<S>*>(node);
    return nullptr;
  }

  /// A node connecting a wire to this link at `position` in its body's
  /// model frame (WireT::add(link, position) makes one).
  [[nodiscard]] ref_ptr<ConnectingNodeT<S>> makeConnection(const Vec3& position) {
    ref_ptr<ConnectingNodeT<S>> node = new ConnectingNodeT<S>(body_.get(), position);
    node->bendStiffness_ = S(0);
    node->link_ = this;
    node->linkHeld_ = this;
    return node;
  }

 protected:
  ~WireLinkT() override = default;

 private:
  ref_ptr<RigidBodyT<S>> body_;
};

using WireLink = WireLinkT<double>;
namespace f32 {
using WireLink = WireLinkT<float>;
}  // namespace f32

}  // namespace spook
