#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <spook/core/implementation.hpp>
#include <spook/sim/step_extension.hpp>

namespace spook::detail {

/// A wire's lumped mass nodes (wire/wire.hpp), held in arrays: point masses
/// that feel gravity and do not turn; after them, one-dimensional bodies
/// (moving along the solver body's x axis only): its winches' drums
/// (wire/wire_winch_controller.hpp), whose position is the free length of
/// the wire segment at the winch, and its contacts' slip, whose position
/// gathers the length of wire slid over the geometry.
class WireNodes : public BodyStore {
 public:
  using Vec3d = Eigen::Vector3d;
  struct Drum {
    double freeLength = 0.0;  ///< rest length of the segment at the winch (m)
    double pulledIn = 0.0;    ///< wire on the drum (m)
    double speed = 0.0;       ///< rate at which wire leaves the drum (m/s)
    double mass = 0.0;        ///< inertia of the wire moving through it (kg)
    bool winch = true;        ///< a drum (its lengths stay >= 0); false: a contact's slip
  };

  [[nodiscard]] std::size_t size() const override { return position_.size() + drums_.size(); }
  [[nodiscard]] std::size_t numNodes() const { return position_.size(); }
  std::size_t add(const Vec3d& position, double mass) {
    position_.push_back(position);
    velocity_.push_back(Vec3d::Zero());
    mass_.push_back(mass);
    return position_.size() - 1;
  }
  [[nodiscard]] const Vec3d& position(std::size_t i) const { return position_[i]; }
  [[nodiscard]] const Vec3d& velocity(std::size_t i) const { return velocity_[i]; }
  [[nodiscard]] double mass(std::size_t i) const { return mass_[i]; }
  void setMass(std::size_t i, double mass) { mass_[i] = mass; }
  void setVelocity(std::size_t i, const Vec3d& velocity) { velocity_[i] = velocity; }
  void setPosition(std::size_t i, const Vec3d& position) { position_[i] = position; }
  /// Removes node i (the wire's adaptive resolution, in beginStep).
  void erase(std::size_t i) {
    position_.erase(position_.begin() + std::ptrdiff_t(i));
    velocity_.erase(velocity_.begin() + std::ptrdiff_t(i));
    mass_.erase(mass_.begin() + std::ptrdiff_t(i));
  }
  /// Reverses the nodes' order (the wire's reverse()); drums stay.
  void reverseNodes() {
    std::reverse(position_.begin(), position_.end());
    std::reverse(velocity_.begin(), velocity_.end());
    std::reverse(mass_.begin(), mass_.end());
  }
  /// Inserts a node before node i (i = size(): at the end).
  void insert(std::size_t i, const Vec3d& position, const Vec3d& velocity, double mass);
  /// Moves nodes [first, numNodes()) to the end of `to` (a wire's cut and
  /// merge); drums stay.
  void moveNodesTo(std::size_t first, WireNodes& to);
  /// Takes all drums out (their indices start again from 0).
  std::vector<Drum> takeDrums() { return std::exchange(drums_, {}); }
  std::size_t addDrum(const Drum& drum) {
    drums_.push_back(drum);
    return drums_.size() - 1;
  }
  [[nodiscard]] Drum& drum(std::size_t d) { return drums_[d]; }
  [[nodiscard]] const Drum& drum(std::size_t d) const { return drums_[d]; }
  /// The velocity each node's speed is bounded against (m/s; the mean
  /// velocity of its neighbours on the wire), one per node, for the caller
  /// to fill before limitSpeeds; kept from step to step (no allocation).
  [[nodiscard]] std::vector<Vec3d>& speedReferences() {
    speedReferences_.resize(position_.size());
    return speedReferences_;
  }
  /// The step's bound on each node's speed relative to its speed reference
  /// and on its displacement by the projection (limit·h), which move() and
  /// displace() keep: none until set.
  void limitSpeeds(double limit, double h) {
    speedLimit_ = limit;
    limitStep_ = h;
  }
  // Declared SPOOK_INLINE as defined: no key function in a header-only
  // build, so the virtual table is emitted only where a wire is built.
  SPOOK_INLINE void writeSolverBodies(std::span<SolverBody> bodies, const StepContext& step) const override;
  // A solve that failed (non-finite, or beyond a drum's ends: the rows that
  // keep it there are the solver's to meet) must not carry the wire away:
  // such a node stops where it is, such a drum at its end.
  SPOOK_INLINE void move(std::span<const SolverBody> bodies, const StepContext& step) override;
  SPOOK_INLINE void displace(std::span<const SolverBody> bodies) override;

 private:
  std::vector<Vec3d> position_, velocity_;
  std::vector<double> mass_;
  std::vector<Drum> drums_;
  std::vector<Vec3d> speedReferences_;
  double speedLimit_ = 0.0, limitStep_ = 0.0;

  [[nodiscard]] bool limited() const { return speedReferences_.size() == position_.size() && speedLimit_ > 0.0; }
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void WireNodes::insert(std::size_t i, const Vec3d& position, const Vec3d& velocity, double mass) {
  position_.insert(position_.begin() + std::ptrdiff_t(i), position);
  velocity_.insert(velocity_.begin() + std::ptrdiff_t(i), velocity);
  mass_.insert(mass_.begin() + std::ptrdiff_t(i), mass);
}

SPOOK_INLINE void WireNodes::moveNodesTo(std::size_t first, WireNodes& to) {
  const auto from = std::ptrdiff_t(first);
  to.position_.insert(to.position_.end(), position_.begin() + from, position_.end());
  to.velocity_.insert(to.velocity_.end(), velocity_.begin() + from, velocity_.end());
  to.mass_.insert(to.mass_.end(), mass_.begin() + from, mass_.end());
  position_.erase(position_.begin() + from, position_.end());
  velocity_.erase(velocity_.begin() + from, velocity_.end());
  mass_.erase(mass_.begin() + from, mass_.end());
}

SPOOK_INLINE void WireNodes::writeSolverBodies(std::span<SolverBody> bodies, const StepContext& step) const {
  const double h = step.getTimeStep();
  for (std::size_t d = 0; d < drums_.size(); ++d) {
    SolverBody& b = bodies[position_.size() + d];
    b.dynamic = true;
    b.velocity.x() = b.freeVelocity.x() = drums_[d].speed;
    b.inverseMass(0, 0) = 1.0 / drums_[d].mass;
  }
  for (std::size_t i = 0; i < position_.size(); ++i) {
    SolverBody& b = bodies[i];
    b.dynamic = true;
    b.velocity.head<3>() = velocity_[i];
    b.freeVelocity.head<3>() = velocity_[i] + h * step.gravity(position_[i]);
    b.inverseMass = Eigen::Matrix3d::Identity() / mass_[i];
  }
}

SPOOK_INLINE void WireNodes::move(std::span<const SolverBody> bodies, const StepContext& step) {
  const double h = step.getTimeStep();
  for (std::size_t i = 0; i < position_.size(); ++i) {
    Vec3d v = bodies[i].freeVelocity.head<3>();
    if (limited()) {
      const Vec3d relative = v - speedReferences_[i];
      const double speed = relative.norm();
      if (speed > speedLimit_) v = speedReferences_[i] + relative * (speedLimit_ / speed);
    }
    velocity_[i] = v.allFinite() ? v : Vec3d::Zero();
    position_[i] += h * velocity_[i];
  }
  for (std::size_t d = 0; d < drums_.size(); ++d) {
    Drum& drum = drums_[d];
    const double speed = bodies[position_.size() + d].freeVelocity.x();
    drum.speed = std::isfinite(speed) ? speed : 0.0;
    double travel = h * drum.speed;
    if (drum.winch && (travel > drum.pulledIn || -travel > drum.freeLength)) {
      travel = std::clamp(travel, -drum.freeLength, drum.pulledIn);
      drum.speed = 0.0;
    }
    drum.freeLength += travel;
    drum.pulledIn -= travel;
  }
}

SPOOK_INLINE void WireNodes::displace(std::span<const SolverBody> bodies) {
  const double reach = speedLimit_ * limitStep_;
  for (std::size_t i = 0; i < position_.size(); ++i) {
    Vec3d d = bodies[i].displacement.head<3>();
    if (limited() && d.norm() > reach) d *= reach / d.norm();
    if (d.allFinite()) position_[i] += d;
  }
}
#endif

}  // namespace spook::detail
