#pragma once

#include <cmath>
#include <optional>

#include <spook/constraints/secondary/secondary_constraint.hpp>

namespace spook {

/// Drives a free DOF at a target speed (m/s or rad/s) with a force no larger
/// than its force range (seed 001 §12.15.1): a velocity row
/// G v⁺ + (ε/h) Λ = speed, the compliance ε acting as a viscosity. A motor
/// drifts in position; with setLockedAtZeroSpeed it holds the position it had
/// when the speed became zero, with the same force range.
template <Scalar S>
class Motor1DT : public SecondaryConstraintT<S> {
 public:
  Motor1DT() : SecondaryConstraintT<S>("Motor1D") {}

  [[nodiscard]] S getSpeed() const { return speed_; }
  void setSpeed(S speed);
  [[nodiscard]] bool getLockedAtZeroSpeed() const { return lockedAtZeroSpeed_; }
  void setLockedAtZeroSpeed(bool locked) { lockedAtZeroSpeed_ = locked; }

  void addRows(detail::RowSink& sink, const detail::Coordinate& c);

 protected:
  ~Motor1DT() override = default;

 private:
  S speed_ = S(0);
  bool lockedAtZeroSpeed_ = false;
  std::optional<double> lockPosition_;
};

template <Scalar S>
void Motor1DT<S>::setSpeed(S speed) {
  if (!std::isfinite(speed)) throw detail::makeError("Motor1D", "", "speed must be finite (m/s or rad/s)", speed);
  speed_ = speed;
}

template <Scalar S>
void Motor1DT<S>::addRows(detail::RowSink& sink, const detail::Coordinate& c) {
  if (!this->enable_) {
    lockPosition_.reset();
    return;
  }
  if (lockedAtZeroSpeed_ && speed_ == S(0)) {
    if (!lockPosition_) lockPosition_ = c.value;
    detail::Row& row = this->addRow(sink, c);
    row.violation = c.value - *lockPosition_;
    return;
  }
  lockPosition_.reset();
  detail::Row& row = this->addRow(sink, c);
  row.holonomic = false;
  row.speed = double(speed_);
}

SPOOK_COMPILED_ONCE(class, Motor1DT)

/// The seeds' spelling (AGX's agx::Motor1D): `spook::Motor1D* m = hinge->getMotor1D();`.
using Motor1D = Motor1DT<double>;
namespace f32 {
using Motor1D = Motor1DT<float>;
}  // namespace f32

}  // namespace spook
