#pragma once

#include <cmath>
#include <limits>
#include <string>

#include <spook/constraints/attachments.hpp>
#include <spook/constraints/rows/elementary.hpp>
#include <spook/constraints/regularization.hpp>
#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// A force range [lower, upper] (N or N·m); lower ≤ upper.
template <Scalar S>
struct RangeT {
  S lower = -std::numeric_limits<S>::infinity();
  S upper = std::numeric_limits<S>::infinity();
};

/// A controller on one free degree of freedom of a joint (seed 001 §12.15):
/// disabled by default, with its own compliance and damping, a force range,
/// and the force it applied in the last step. Adds at most one row.
template <Scalar S>
class SecondaryConstraintT : public Referenced {
 public:
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  [[nodiscard]] RegularizationParametersT<S>* getRegularizationParameters() { return &regularization_; }
  [[nodiscard]] const RegularizationParametersT<S>* getRegularizationParameters() const { return &regularization_; }
  void setCompliance(S compliance) { regularization_.setCompliance(compliance); }
  void setDamping(S damping) { regularization_.setDamping(damping); }
  [[nodiscard]] S getCompliance() const { return regularization_.getCompliance(); }
  [[nodiscard]] S getDamping() const { return regularization_.getDamping(); }

  /// The largest force (N, or N·m for a rotational DOF) it may apply in each
  /// direction; default unbounded.
  [[nodiscard]] RangeT<S> getForceRange() const { return forceRange_; }
  void setForceRange(S lower, S upper);
  void setForceRange(RangeT<S> range) { setForceRange(range.lower, range.upper); }

  /// The force (N) or torque (N·m) applied along the DOF in the last step;
  /// zero when it added no row.
  [[nodiscard]] S getCurrentForce() const { return force_; }

 protected:
  explicit SecondaryConstraintT(const char* kind) : kind_(kind) {}
  ~SecondaryConstraintT() override = default;

  [[nodiscard]] detail::RowParameters rowParameters() const {
    return {double(regularization_.getCompliance()), double(regularization_.getDamping())};
  }
  detail::Row& addRow(detail::RowSink& sink, const detail::Coordinate& c);

 public:
  // Called by the joint once per step around the solve.
  void beginStep() { active_ = false; }
  void endStep(double h);

 protected:
  const char* kind_;
  bool enable_ = false;
  RegularizationParametersT<S> regularization_;
  RangeT<S> forceRange_;
  double impulse_ = 0.0;
  bool active_ = false;
  S force_ = S(0);
};

template <Scalar S>
void SecondaryConstraintT<S>::setForceRange(S lower, S upper) {
  if (std::isnan(lower) || std::isnan(upper) || lower > upper)
    throw detail::makeError(kind_, "", "force range must have lower <= upper (N or N·m)",
                            Eigen::Matrix<S, 2, 1>(lower, upper));
  forceRange_ = {lower, upper};
}

template <Scalar S>
detail::Row& SecondaryConstraintT<S>::addRow(detail::RowSink& sink, const detail::Coordinate& c) {
  active_ = true;
  detail::Row& row = sink.add(c.J1, c.J2, &impulse_);
  row.compliance = double(regularization_.getCompliance());
  row.damping = double(regularization_.getDamping());
  row.lower = double(forceRange_.lower);
  row.upper = double(forceRange_.upper);
  sink.setCurvature(c.curvature);
  return row;
}

template <Scalar S>
void SecondaryConstraintT<S>::endStep(double h) {
  force_ = active_ ? S(impulse_ / h) : S(0);
  if (!active_) impulse_ = 0.0;
}

SPOOK_COMPILED_ONCE(class, SecondaryConstraintT)

}  // namespace spook
