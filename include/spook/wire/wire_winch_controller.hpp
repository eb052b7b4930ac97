#pragma once

// A winch (agxWire's WireWinchController; PHYSICS.md §3.2): a drum on a
// body or the world at which one end of a wire starts, holding some of the
// wire's length pulled in. Its motor drives the rate at which wire leaves
// the drum towards a target speed within a force range, and its brake holds
// the drum while the speed is 0:
//
//   ref_ptr<WireWinchController> winch =
//       new WireWinchController(boom, Vec3(0, 0, -0.5), Vec3(0, 0, -1));
//   wire->add(winch, 50.0);                 // 50 m on the drum
//   wire->add(new FreeNode(0, 0, -5));
//   winch->setSpeed(-0.4);                  // haul in at 0.4 m/s
//   winch->setForceRange(30e3);             // pulling with at most 30 kN
//
// The drum is a degree of freedom of the step (the free length of the wire
// segment at the winch, with the inertia of that segment's wire): the
// tension pulls wire out, the motor and brake forces act against it.

#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <utility>

#include <spook/core/error.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/wire/wire_nodes.hpp>

namespace spook {

template <Scalar S>
class WireT;

template <Scalar S>
class WireWinchControllerT : public Referenced {
 public:
  using Vec3 = Vec3T<S>;

  /// A winch on `body` (nullptr: the world) at `position`, from which the
  /// wire leaves along `direction` (both in the body's model frame, or
  /// world; the direction need not be normalized). Its motor is off (speed
  /// 0, force range 0) and its brake holds the drum until set.
  WireWinchControllerT(RigidBodyT<S>* body, const Vec3& position, const Vec3& direction)
      : body_(body), position_(position), direction_(direction) {
    if (!position.allFinite()) throw error("position must be finite m", position);
    if (!(direction.allFinite() && direction.norm() > S(0)))
      throw error("direction must be finite and nonzero", direction);
    direction_.normalize();
  }

  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  /// The body it sits on; nullptr for the world.
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const { return body_.get(); }
  /// Where the wire leaves the drum (body model frame or world, m).
  [[nodiscard]] const Vec3& getPosition() const { return position_; }
  /// The direction the wire leaves along (body model frame or world), unit.
  [[nodiscard]] const Vec3& getDirection() const { return direction_; }

  /// Target rate at which wire leaves the drum (m/s): > 0 pays out, < 0
  /// hauls in; finite.
  [[nodiscard]] S getSpeed() const { return speed_; }
  void setSpeed(S speed) {
    if (!std::isfinite(speed)) throw error("speed must be finite m/s", speed);
    speed_ = speed;
  }
  /// The motor's force range (N): it pulls wire in with at most −lower and
  /// pushes it out with at most upper; finite, lower ≤ 0 ≤ upper.
  [[nodiscard]] S getForceRangeLower() const { return forceLower_; }
  [[nodiscard]] S getForceRangeUpper() const { return forceUpper_; }
  void setForceRange(S lower, S upper) { checkRange("force range", lower, upper, forceLower_, forceUpper_); }
  /// Symmetric range [−force, force] (N), force ≥ 0.
  void setForceRange(S force) { setForceRange(-force, force); }
  /// The brake's force range (N), acting while the speed is 0: the drum
  /// holds while the tension is within it and slips beyond; finite,
  /// lower ≤ 0 ≤ upper. Until set, the brake holds whatever the tension.
  [[nodiscard]] S getBrakeForceRangeLower() const { return brakeLower_; }
  [[nodiscard]] S getBrakeForceRangeUpper() const { return brakeUpper_; }
  void setBrakeForceRange(S lower, S upper) {
    checkRange("brake force range", lower, upper, brakeLower_, brakeUpper_);
  }
  void setBrakeForceRange(S force) { setBrakeForceRange(-force, force); }

  /// Auto-feed (off by default): when its wire is added to a simulation
  /// with both ends held (no free end), the wire's routing points (free
  /// nodes) are dropped and it starts straight between the rest of its
  /// route (winches, eyes, contact nodes, fixed ends), this winch taking in
  /// the slack they made, or paying out what the straight route needs more
  /// (shared equally with an auto-feeding winch at the other end). The wire
  /// may then start through geometry the routing points led it around.
  /// Set before the wire is in a simulation.
  [[nodiscard]] bool getEnableAutoFeed() const { return autoFeed_; }
  void setEnableAutoFeed(bool enable) {
    if (store_) throw error("auto-feed acts when its wire is added to a simulation; it is in one already", enable);
    autoFeed_ = enable;
  }

  /// Wire on the drum (m): the initial length given to Wire::add, then what
  /// the winch has hauled in or paid out.
  [[nodiscard]] S getPulledInLength() const { return S(store_ ? store_->drum(drum_).pulledIn : pulledIn_); }
  /// Rate at which wire left the drum in the last step (m/s).
  [[nodiscard]] S getCurrentSpeed() const { return S(store_ ? store_->drum(drum_).speed : 0.0); }
  /// Force of the motor on the wire in the last step (N, < 0 hauling in).
  [[nodiscard]] S getCurrentForce() const { return S(motorForce_); }
  /// Force of the brake in the last step (N).
  [[nodiscard]] S getCurrentBrakeForce() const { return S(brakeForce_); }

 protected:
  ~WireWinchControllerT() override = default;

 private:
  friend class WireT<S>;

  template <class T>
  [[nodiscard]] Error error(const char* what, const T& value) const {
    return detail::makeError("WireWinchController", name_, what, value);
  }
  void checkRange(const char* what, S lower, S upper, S& toLower, S& toUpper) {
    if (!(std::isfinite(lower) && lower <= S(0)))
      throw error((std::string(what) + ": lower must be finite and <= 0 N").c_str(), lower);
    if (!(std::isfinite(upper) && upper >= S(0)))
      throw error((std::string(what) + ": upper must be finite and >= 0 N").c_str(), upper);
    toLower = lower;
    toUpper = upper;
  }

  ref_ptr<RigidBodyT<S>> body_;
  Vec3 position_;
  Vec3 direction_;
  std::string name_;
  S speed_ = S(0);
  bool autoFeed_ = false;
  S forceLower_ = S(0), forceUpper_ = S(0);
  S brakeLower_ = -std::numeric_limits<S>::infinity(), brakeUpper_ = std::numeric_limits<S>::infinity();
  // Kept by the wire it is routed in: the initial pulled-in length, then
  // its drum in the wire's store, and the forces of the last step.
  const void* wire_ = nullptr;
  double pulledIn_ = 0.0;
  ref_ptr<detail::WireNodes> store_;
  std::size_t drum_ = 0;
  double motorForce_ = 0.0;
  double brakeForce_ = 0.0;
};

using WireWinchController = WireWinchControllerT<double>;
using WireWinchControllerRef = ref_ptr<WireWinchController>;
namespace f32 {
using WireWinchController = WireWinchControllerT<float>;
using WireWinchControllerRef = ref_ptr<WireWinchController>;
}  // namespace f32

}  // namespace spook
