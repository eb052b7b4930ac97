#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include <spook/constraints/joints/wheel_joint.hpp>
#include <spook/constraints/steering/linkages.hpp>
#include <spook/constraints/steering/steering_parameters.hpp>
#include <spook/core/error.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/sim/step_event_listener.hpp>

namespace spook {

/// A steering mechanism between two wheel joints on one chassis (seed 001
/// §12.13). The steering angle (rad, positive turning left, i.e.
/// counterclockwise about the steering axes) is position-controlled, so the
/// linkage has no free DOF left: each wheel's steering angle is a known
/// function of the input, given in closed form by the linkage's loop closure
/// (linkages.hpp). The mechanism acts through the wheel joints'
/// STEERING Lock1D: it enables each lock and sets its position to the
/// wheel's angle plus the STEERING angle the joint had when the mechanism was
/// built (straight ahead); compliance, damping and force range of the locks
/// stay the user's.
///
/// setSteeringAngle applies at once, so a mechanism works without being
/// added anywhere; added to a simulation (sim->add(steering)) it also
/// re-applies its targets before every step, so the locks cannot be left
/// disabled while it is enabled. As in AGX, requests beyond the reachable
/// range ±getMaximumSteeringAngle() are clamped to it: getSteeringAngle is
/// the angle held, getRequestedSteeringAngle the one asked for.
///
/// The left wheel joint is the one whose steering pivot (frame 2 origin) the
/// mechanism's x axis starts from; see SteeringParameters for the plane.
template <Scalar S>
class SteeringT : public StepEventListenerT<S> {
 public:
  using WheelJoint = WheelJointT<S>;

  /// Steering angles of the left and right wheels (rad) relative to straight ahead.
  struct WheelAngles {
    S left = S(0);
    S right = S(0);
  };

  /// The mechanism, e.g. "Ackermann".
  [[nodiscard]] const char* getKind() const { return kind_; }
  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  [[nodiscard]] WheelJoint* getLeftWheelJoint() const { return left_.get(); }
  [[nodiscard]] WheelJoint* getRightWheelJoint() const { return right_.get(); }
  [[nodiscard]] const SteeringParameters& getParameters() const { return parameters_; }

  /// The largest |steering angle| (rad): on [−max, max] the linkage closes,
  /// both wheels stay within ±π/2 of straight ahead and turn strictly with
  /// the input (no dead centre), in both directions.
  [[nodiscard]] S getMaximumSteeringAngle() const { return S(maximum_); }

  /// The steering input the mechanism holds (rad): the last request clamped
  /// to ±getMaximumSteeringAngle().
  [[nodiscard]] S getSteeringAngle() const { return S(input_); }
  /// The last steering input asked for (rad), before clamping.
  [[nodiscard]] S getRequestedSteeringAngle() const { return S(requested_); }
  /// The wheel angles the mechanism holds for the current input (rad).
  [[nodiscard]] WheelAngles getWheelAngles() const { return {S(angles_.left), S(angles_.right)}; }

  /// Steers to `angle` (rad) clamped to ±getMaximumSteeringAngle(); only a
  /// non-finite angle throws (and changes nothing).
  void setSteeringAngle(S angle);

  void pre(const TimeStampT<S>&) override { apply(); }

 protected:
  SteeringT(const char* kind, WheelJoint* left, WheelJoint* right, const SteeringParameters& parameters);
  ~SteeringT() override = default;

  /// Wheel angles for an input (rad); none where the linkage does not close.
  [[nodiscard]] virtual std::optional<detail::LinkageAngles> solve(double input) const = 0;

  /// Called by the mechanism's constructor once its linkage is built.
  void start(double maximum);

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError(kind_, name_, what, value);
  }

 private:
  void checkWheelJoints(const WheelJoint* left, const WheelJoint* right) const;

  void apply();
  static void steer(WheelJoint& joint, double angle);

  const char* kind_;
  std::string name_;
  SteeringParameters parameters_;
  ref_ptr<WheelJoint> left_, right_;
  double straightLeft_ = 0.0, straightRight_ = 0.0;
  double maximum_ = 0.0;
  double input_ = 0.0;
  double requested_ = 0.0;
  detail::LinkageAngles angles_;
};

template <Scalar S>
void SteeringT<S>::setSteeringAngle(S angle) {
  if (!std::isfinite(angle)) throw error("steering angle must be finite (rad)", angle);
  const double held = std::clamp(double(angle), -maximum_, maximum_);
  const auto angles = solve(held);
  if (!angles) throw error("linkage does not close at this steering angle (rad)", held);
  requested_ = double(angle);
  input_ = held;
  angles_ = *angles;
  apply();
}

template <Scalar S>
SteeringT<S>::SteeringT(const char* kind, WheelJoint* left, WheelJoint* right, const SteeringParameters& parameters)
    : StepEventListenerT<S>(StepEventListenerT<S>::PRE_STEP), kind_(kind), parameters_(parameters) {
  checkWheelJoints(left, right);
  left_ = left;
  right_ = right;
  straightLeft_ = double(left->getAngle(WheelJoint::STEERING));
  straightRight_ = double(right->getAngle(WheelJoint::STEERING));
}

template <Scalar S>
void SteeringT<S>::start(double maximum) {
  if (!(maximum > 0.0)) throw error("linkage cannot turn from straight ahead: maximum steering angle (rad)", maximum);
  maximum_ = maximum;
  apply();
}

template <Scalar S>
void SteeringT<S>::checkWheelJoints(const WheelJoint* left, const WheelJoint* right) const {
  if (!left || !right)
    throw error("needs a left and a right WheelJoint", !left && !right ? "nullptr and nullptr" : "nullptr");
  if (left == right) throw error("left and right must be different wheel joints", left->getName());
  if (left->getBodyAt(1) != right->getBodyAt(1))
    throw error("wheel joints must share one chassis (body 2)", left->getName() + " and " + right->getName());
  const double track = double((right->getWorldSteeringPivot() - left->getWorldSteeringPivot()).norm());
  if (!(std::isfinite(track) && track > 0.0))
    throw error("wheel joints' steering pivots must be apart (wheel track, m)", track);
  const double sameWay = double(left->getWorldSteeringAxis().dot(right->getWorldSteeringAxis()));
  if (!(sameWay > 0.0)) throw error("wheel joints' steering axes must point the same way (cosine)", sameWay);
}

template <Scalar S>
void SteeringT<S>::apply() {
  steer(*left_, straightLeft_ + angles_.left);
  steer(*right_, straightRight_ + angles_.right);
}

template <Scalar S>
void SteeringT<S>::steer(WheelJoint& joint, double angle) {
  Lock1DT<S>* lock = joint.getLock1D(WheelJoint::STEERING);
  lock->setPosition(S(angle));
  lock->setEnable(true);
}

SPOOK_COMPILED_ONCE(class, SteeringT)

/// A steering mechanism with the kinematics of `Linkage` (linkages.hpp).
template <Scalar S, class Linkage>
class SteeringMechanismT : public SteeringT<S> {
 public:
  /// Between two wheel joints on one chassis, with Table 12.6 defaults
  /// unless parameters are given; holds the wheels straight ahead.
  SteeringMechanismT(WheelJointT<S>* leftWheel, WheelJointT<S>* rightWheel,
                     const SteeringParameters& parameters = Linkage::defaults());

  /// The linkage's closed-form kinematics.
  [[nodiscard]] const Linkage& getLinkage() const { return linkage_; }

 protected:
  ~SteeringMechanismT() override = default;
  [[nodiscard]] std::optional<detail::LinkageAngles> solve(double input) const override {
    return linkage_.solve(input);
  }

 private:
  Linkage linkage_;
};

template <Scalar S, class Linkage>
SteeringMechanismT<S, Linkage>::SteeringMechanismT(WheelJointT<S>* leftWheel, WheelJointT<S>* rightWheel,
                                                   const SteeringParameters& parameters)
    : SteeringT<S>(Linkage::kName, leftWheel, rightWheel, parameters), linkage_(parameters) {
  this->start(detail::maximumLinkageInput(linkage_));
}

SPOOK_COMPILED_DOUBLE(class SteeringMechanismT<double, detail::AckermannLinkage>)
SPOOK_COMPILED_FLOAT(class SteeringMechanismT<float, detail::AckermannLinkage>)
SPOOK_COMPILED_DOUBLE(class SteeringMechanismT<double, detail::BellCrankLinkage>)
SPOOK_COMPILED_FLOAT(class SteeringMechanismT<float, detail::BellCrankLinkage>)
SPOOK_COMPILED_DOUBLE(class SteeringMechanismT<double, detail::RackPinionLinkage>)
SPOOK_COMPILED_FLOAT(class SteeringMechanismT<float, detail::RackPinionLinkage>)
SPOOK_COMPILED_DOUBLE(class SteeringMechanismT<double, detail::DavisLinkage>)
SPOOK_COMPILED_FLOAT(class SteeringMechanismT<float, detail::DavisLinkage>)

/// Ackermann trapezoid four-bar (seed 001 §12.13).
template <Scalar S>
using AckermannT = SteeringMechanismT<S, detail::AckermannLinkage>;
/// Bell crank (central lever) steering.
template <Scalar S>
using BellCrankT = SteeringMechanismT<S, detail::BellCrankLinkage>;
/// Rack-and-pinion steering.
template <Scalar S>
using RackPinionT = SteeringMechanismT<S, detail::RackPinionLinkage>;
/// Davis steering: Ackermann's rule exactly, for W_b = W_t/(2 tan(φ₀ − π/2)).
template <Scalar S>
using DavisT = SteeringMechanismT<S, detail::DavisLinkage>;

using Steering = SteeringT<double>;
using SteeringRef = ref_ptr<Steering>;
using Ackermann = AckermannT<double>;
using AckermannRef = ref_ptr<Ackermann>;
using BellCrank = BellCrankT<double>;
using BellCrankRef = ref_ptr<BellCrank>;
using RackPinion = RackPinionT<double>;
using RackPinionRef = ref_ptr<RackPinion>;
using Davis = DavisT<double>;
using DavisRef = ref_ptr<Davis>;
namespace f32 {
using Steering = SteeringT<float>;
using SteeringRef = ref_ptr<Steering>;
using Ackermann = AckermannT<float>;
using AckermannRef = ref_ptr<Ackermann>;
using BellCrank = BellCrankT<float>;
using BellCrankRef = ref_ptr<BellCrank>;
using RackPinion = RackPinionT<float>;
using RackPinionRef = ref_ptr<RackPinion>;
using Davis = DavisT<float>;
using DavisRef = ref_ptr<Davis>;
}  // namespace f32

}  // namespace spook
