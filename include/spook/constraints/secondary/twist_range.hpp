#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <spook/constraints/secondary/friction_controller.hpp>
#include <spook/constraints/secondary/secondary_constraint.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

namespace detail {

/// The twist of frame 1 about its own z axis relative to frame 2's z axis
/// (seed 001 §12.4.2), from the swing–twist split of q = q₂* q₁ = swing ⊗
/// twist with the swing about an axis in the xy plane: ψ = 2 atan2(q_z, q_w)
/// (rad, −π..π; the same for the twist taken first or last). With
/// q̇ = ½ Ω ⊗ q, Ω = R₂ᵀ(ω₁ − ω₂):
///   ψ̇ = Ω·(q_w q_y + q_x q_z, q_y q_z − q_w q_x, q_w² + q_z²)/(q_w² + q_z²).
/// Undefined when z₁ = −z₂ (q_w = q_z = 0), as the seed warns.
[[nodiscard]] SPOOK_INLINE Coordinate twistCoordinate(const Attachments& a);

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Coordinate twistCoordinate(const Attachments& a) {
  const Quatd q = relativeRotation(a);
  const double den = q.w() * q.w() + q.z() * q.z();
  Vec3d n2 = Vec3d::UnitZ();
  if (den > 1e-12)
    n2 = Vec3d(q.w() * q.y() + q.x() * q.z(), q.y() * q.z() - q.w() * q.x(), den) / den;
  return angleAbout(a, 2.0 * std::atan2(q.z(), q.w()), a.R2 * n2);
}
#endif
}  // namespace detail

/// Keeps the twist of a ball joint (detail::twistCoordinate, rad) within
/// [lower, upper] like a contact at each end (seed 001 §12.4.2): a one-sided
/// row pushing only inward, added when the twist is beyond a limit or would
/// reach it within two steps; lower == upper locks the twist. The range lies
/// in [−π, π]; by default none is set and the controller does nothing even
/// when enabled. Meant to be used with the ConeLimit, which keeps z₁ away
/// from −z₂ where the twist is undefined. Disabled by default.
template <Scalar S>
class TwistRangeControllerT : public SecondaryConstraintT<S> {
 public:
  TwistRangeControllerT() : SecondaryConstraintT<S>("TwistRangeController") {}

  [[nodiscard]] RangeT<S> getRange() const { return range_; }
  /// Twist limits (rad), −π ≤ lower ≤ upper ≤ π.
  void setRange(S lower, S upper);
  void setRange(RangeT<S> range) { setRange(range.lower, range.upper); }

  /// The twist (rad) in the last step it was enabled.
  [[nodiscard]] S getAngle() const { return S(twist_); }

  // Called by the joint each step.
  void addRows(detail::RowSink& sink, const detail::Attachments& a, double h);
  /// The joint this controller belongs to (for error messages).
  void setJoint(const ConstraintT<S>* joint) { label_.set(joint); }

 protected:
  ~TwistRangeControllerT() override = default;

 private:
  RangeT<S> range_;
  double twist_ = 0.0;
  detail::JointLabel<S> label_;
};

template <Scalar S>
void TwistRangeControllerT<S>::setRange(S lower, S upper) {
  const S pi = std::numbers::pi_v<S>;
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower <= upper && lower >= -pi && upper <= pi))
    throw label_.error(this->kind_, "range must have -pi <= lower <= upper <= pi (rad)",
                       Eigen::Matrix<S, 2, 1>(lower, upper));
  range_ = {lower, upper};
}

template <Scalar S>
void TwistRangeControllerT<S>::addRows(detail::RowSink& sink, const detail::Attachments& a, double h) {
  if (!this->enable_) return;
  const detail::Coordinate c = detail::twistCoordinate(a);
  twist_ = c.value;
  const double lower = double(range_.lower), upper = double(range_.upper);
  const double reach = 2.0 * h * std::abs(c.speed);
  const bool atLower = c.value - lower <= reach;
  const bool atUpper = upper - c.value <= reach;
  if (!atLower && !atUpper) return;
  detail::Row& row = this->addRow(sink, c);
  const bool lowerSide = atLower && (!atUpper || c.value - lower <= upper - c.value);
  row.violation = c.value - (lowerSide ? lower : upper);
  if (lower == upper) return;  // a lock
  if (lowerSide) {
    row.lower = std::max(row.lower, 0.0);
    row.upper = std::max(row.upper, 0.0);
  } else {
    row.lower = std::min(row.lower, 0.0);
    row.upper = std::min(row.upper, 0.0);
  }
}

SPOOK_COMPILED_ONCE(class, TwistRangeControllerT)

using TwistRangeController = TwistRangeControllerT<double>;
using TwistRangeControllerRef = ref_ptr<TwistRangeController>;
namespace f32 {
using TwistRangeController = TwistRangeControllerT<float>;
using TwistRangeControllerRef = ref_ptr<TwistRangeController>;
}  // namespace f32

}  // namespace spook
