#pragma once

#include <cmath>
#include <string>

#include <spook/core/error.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook {

/// A simulation's sleeping (SimulationT::getAutoSleep), off by default: an
/// island of dynamic bodies that has stayed below both velocity thresholds
/// for getTime() seconds falls asleep: its bodies keep their pose, their
/// velocities become zero and the step no longer solves or moves them
/// (RigidBody::isSleeping). They still collide, so an awake or moving body
/// that meets one wakes its island (RigidBody::isSleeping lists the other
/// ways to wake). A body of a body store (wire nodes, particles) never
/// sleeps, nor does an island holding one. Sleeping trades accuracy for
/// speed: a body at 2 cm/s that falls asleep stops there.
class AutoSleep {
 public:
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  /// Speed of the center of mass (m/s, finite and >= 0) under which a body
  /// counts as resting. Default 0.02.
  [[nodiscard]] double getLinearVelocityThreshold() const { return linear_; }
  void setLinearVelocityThreshold(double speed) {
    linear_ = checked("linear velocity threshold must be finite and >= 0 m/s", speed);
  }
  /// Angular speed (rad/s, finite and >= 0) under which a body counts as
  /// resting. Default 0.05.
  [[nodiscard]] double getAngularVelocityThreshold() const { return angular_; }
  void setAngularVelocityThreshold(double speed) {
    angular_ = checked("angular velocity threshold must be finite and >= 0 rad/s", speed);
  }
  /// How long (s, finite and > 0) every body of an island must rest before
  /// the island falls asleep. Default 0.5.
  [[nodiscard]] double getTime() const { return time_; }
  void setTime(double time) {
    if (!(std::isfinite(time) && time > 0.0))
      throw detail::makeError("AutoSleep", "", "time must be finite and > 0 s", time);
    time_ = time;
  }

 private:
  static double checked(const char* what, double value) {
    if (!(std::isfinite(value) && value >= 0.0)) throw detail::makeError("AutoSleep", "", what, value);
    return value;
  }

  bool enable_ = false;
  double linear_ = 0.02;
  double angular_ = 0.05;
  double time_ = 0.5;
};

namespace detail {

/// A body's sleep state, kept by the simulation's step (sim/simulation_step.hpp).
template <Scalar S>
struct BodySleep {
  using Body = RigidBodyT<S>;

  /// Whether a sleeping body was moved, disabled, switched from DYNAMICS or
  /// given a velocity, force or torque since it fell asleep.
  static bool disturbed(const Body& body) {
    const Vec3T<S> zero = Vec3T<S>::Zero();
    return !body.enable_ || body.motionControl_ != Body::DYNAMICS || body.velocity_ != zero ||
           body.angularVelocity_ != zero || body.force_ != zero || body.torque_ != zero ||
           body.getTransform().matrix() != body.sleepPose_.matrix();
  }

  /// Counts the step of h a dynamic awake body spent at rest (or restarts the
  /// count); true when it has rested long enough to sleep.
  static bool rest(Body& body, const AutoSleep& sleep, S h) {
    const bool resting = double(body.velocity_.norm()) <= sleep.getLinearVelocityThreshold() &&
                         double(body.angularVelocity_.norm()) <= sleep.getAngularVelocityThreshold();
    body.restingTime_ = resting ? body.restingTime_ + h : S(0);
    return double(body.restingTime_) >= sleep.getTime();
  }

  static void fallAsleep(Body& body) {
    body.sleeping_ = true;
    body.velocity_ = body.angularVelocity_ = Vec3T<S>::Zero();
    body.sleepPose_ = body.getTransform();
  }
};

}  // namespace detail
}  // namespace spook
