#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

#include <spook/constraints/secondary/friction_controller.hpp>
#include <spook/constraints/secondary/secondary_constraint.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

namespace detail {

/// Where frame 1's z axis is relative to an elliptic cone about frame 2's z
/// axis (seed 001 §12.4.1). With d = R₂ᵀ z₁ = (sin θ cos φ, sin θ sin φ,
/// cos θ) the tilt θ and its azimuth φ are measured in frame 2; the cone's
/// half-angle towards azimuth φ is that of the ellipse with semi-axes a₁
/// (towards frame 2's x, the x–z plane) and a₂ (towards y, the y–z plane)
/// in the plane of tilt vectors θ (cos φ, sin φ):
///   α(φ) = a₁ a₂ / √(a₂² cos²φ + a₁² sin²φ),   g = θ − α(φ)  (rad, ≤ 0 inside).
/// With Ω = R₂ᵀ(ω₁ − ω₂), ḋ = Ω × d, θ̇ = Ω·(e_z × d)/sin θ and
/// φ̇ = Ω·(e_z − d_z d)/sin²θ, so ġ = Ω·n₂ with n₂ = (e_z × d)/sin θ − α′(φ)(e_z − d_z d)/sin²θ.
struct ConeState {
  double tilt = 0.0;       ///< θ (rad)
  double limit = 0.0;      ///< α(φ) (rad)
  Vec3d axis = Vec3d::Zero();  ///< n = R₂ n₂ (world): ġ = n·(ω₁ − ω₂)
};

[[nodiscard]] SPOOK_INLINE ConeState coneState(const Attachments& a, double a1, double a2);

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE ConeState coneState(const Attachments& a, double a1, double a2) {
  const Vec3d d = a.R2.transpose() * a.R1.col(2);
  const double rho = std::hypot(d.x(), d.y());
  ConeState s;
  s.tilt = std::atan2(rho, d.z());
  if (rho < 1e-12) {
    // z axes (anti)parallel: no azimuth; push about frame 2's y (towards x).
    s.limit = a1;
    s.axis = a.R2.col(1) * (d.z() >= 0.0 ? 1.0 : -1.0);
    return s;
  }
  const double c = d.x() / rho, sn = d.y() / rho;
  const double D = a2 * a2 * c * c + a1 * a1 * sn * sn;
  s.limit = a1 * a2 / std::sqrt(D);
  const double dLimit = -a1 * a2 * (a1 * a1 - a2 * a2) * sn * c / (D * std::sqrt(D));
  const Vec3d ez = Vec3d::UnitZ();
  const Vec3d n2 = Vec3d(-d.y(), d.x(), 0.0) / rho - dLimit * (ez - d.z() * d) / (rho * rho);
  s.axis = a.R2 * n2;
  return s;
}
#endif
}  // namespace detail

/// Keeps frame 1's z axis inside a cone about frame 2's z axis, the base
/// (seed 001 §12.4.1): a one-sided row g = θ − α(φ) ≤ 0 (detail::coneState),
/// pushing only inward, added when the axis is on or beyond the cone or would
/// reach it within two steps at its current rate. Equal half-angles give a
/// circular cone, different ones an elliptic cone: a₁ in frame 2's x–z
/// plane, a₂ in its y–z plane. Disabled by default; both angles π/4.
template <Scalar S>
class ConeLimitT : public SecondaryConstraintT<S> {
 public:
  ConeLimitT() : SecondaryConstraintT<S>("ConeLimit") {}

  /// Half-angle (rad) in frame 2's x–z plane (index 0) or y–z plane (1).
  [[nodiscard]] S getLimitAngle(int index) const { return index == 0 ? a1_ : a2_; }
  /// Both half-angles (rad), each in (0, π/2).
  void setLimitAngles(S a1, S a2);

  /// The tilt of frame 1's z axis from frame 2's (rad) in the last step it
  /// was enabled.
  [[nodiscard]] S getAngle() const { return S(tilt_); }

  // Called by the joint each step.
  void addRows(detail::RowSink& sink, const detail::Attachments& a, double h);
  /// The joint this limit belongs to (for error messages).
  void setJoint(const ConstraintT<S>* joint) { label_.set(joint); }

 protected:
  ~ConeLimitT() override = default;

 private:
  S a1_ = std::numbers::pi_v<S> / S(4);
  S a2_ = std::numbers::pi_v<S> / S(4);
  double tilt_ = 0.0;
  detail::JointLabel<S> label_;
};

template <Scalar S>
void ConeLimitT<S>::setLimitAngles(S a1, S a2) {
  const auto valid = [](S angle) { return std::isfinite(angle) && angle > S(0) && angle < std::numbers::pi_v<S> / S(2); };
  if (!valid(a1) || !valid(a2))
    throw label_.error(this->kind_, "limit angles must both be in (0, pi/2) rad", Eigen::Matrix<S, 2, 1>(a1, a2));
  a1_ = a1;
  a2_ = a2;
}

template <Scalar S>
void ConeLimitT<S>::addRows(detail::RowSink& sink, const detail::Attachments& a, double h) {
  if (!this->enable_) return;
  const detail::ConeState s = detail::coneState(a, double(a1_), double(a2_));
  tilt_ = s.tilt;
  const detail::Coordinate c = detail::angleAbout(a, s.tilt - s.limit, s.axis);
  if (c.value < -2.0 * h * std::abs(c.speed)) return;
  detail::Row& row = this->addRow(sink, c);
  row.violation = c.value;
  row.lower = std::min(row.lower, 0.0);
  row.upper = std::min(row.upper, 0.0);
}

SPOOK_COMPILED_ONCE(class, ConeLimitT)

using ConeLimit = ConeLimitT<double>;
using ConeLimitRef = ref_ptr<ConeLimit>;
namespace f32 {
using ConeLimit = ConeLimitT<float>;
using ConeLimitRef = ref_ptr<ConeLimit>;
}  // namespace f32

}  // namespace spook
