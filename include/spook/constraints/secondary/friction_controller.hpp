#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <spook/constraints/constraint.hpp>
#include <spook/constraints/secondary/secondary_constraint.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/observer_ptr.hpp>

namespace spook {

namespace detail {

/// The joint a secondary constraint belongs to, for error messages:
/// "spook::ConeLimit of BallJoint 'shoulder': ...". Observed, not owned: a
/// controller kept alive after its joint just names itself.
template <Scalar S>
class JointLabel {
 public:
  void set(const ConstraintT<S>* joint) { joint_ = joint; }

  template <class T>
  [[nodiscard]] Error error(std::string_view kind, std::string_view what, const T& value) const {
    std::string label(kind);
    std::string name;
    if (const ConstraintT<S>* joint = joint_.get()) {
      label += std::string(" of ") + joint->getKind();
      name = joint->getName();
    }
    return makeError(label, name, what, value);
  }

 private:
  observer_ptr<const ConstraintT<S>> joint_;
};

/// The force the elementary rows of a joint applied on body 1 in a step, read
/// back after the solve from their impulses: F = Σ J1ᵢ(linear) Λᵢ / h (N,
/// world). The normal force of the seed (001 §12.15.4.2) is the part of F
/// across the joint axis z (frame 2): N = √(Fx² + Fy²).
class JointLoad {
 public:
  /// Records the rows written to `sink` from index `first` on (the joint's
  /// elementary rows of this step) and the joint axis (world, unit).
  void record(const RowSink& sink, std::size_t first, const Vec3d& axis);
  /// Force on body 1 from the recorded rows (N, world); zero when the joint
  /// wrote no rows this step. Call once per step, after the solve.
  [[nodiscard]] Vec3d force(double h);
  /// The part of `force` across the axis (N); with `across` false its whole
  /// magnitude (a ball joint has no axis).
  [[nodiscard]] double normal(const Vec3d& force, bool across = true) const;

 private:
  struct Entry {
    Vec3d linear;
    const double* impulse;
  };
  std::vector<Entry> rows_;
  Vec3d axis_ = Vec3d::UnitZ();
  bool recorded_ = false;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void JointLoad::record(const RowSink& sink, std::size_t first, const Vec3d& axis) {
  rows_.clear();
  for (std::size_t i = first; i < sink.rows->size(); ++i) rows_.push_back({(*sink.rows)[i].J1.head<3>(), sink.slot(i)});
  axis_ = axis;
  recorded_ = true;
}

SPOOK_INLINE Vec3d JointLoad::force(double h) {
  Vec3d f = Vec3d::Zero();
  if (recorded_)
    for (const auto& r : rows_)
      if (r.impulse) f += r.linear * (*r.impulse / h);
  recorded_ = false;
  return f;
}

SPOOK_INLINE double JointLoad::normal(const Vec3d& force, bool across) const {
  return across ? (force - force.dot(axis_) * axis_).norm() : force.norm();
}
#endif

}  // namespace detail

/// Internal friction of a joint's free DOF (seed 001 §12.15.4): a velocity
/// row with target speed 0 whose force may not exceed
///   |F| ≤ max(μ N, minimum static friction)   (N, or N·m for a rotation),
/// so the DOF sticks while the driving force is below the bound and slides
/// with exactly the bound otherwise. N (N) is the joint's constraint force
/// across its axis (√(Fx² + Fy²) with the axis along z, seed §12.15.4.2).
/// For a rotational DOF the bound is a torque and the axle radius is part of
/// μ (τ ≤ μ r N: pass μ·r, in m). The row's compliance acts as a viscosity:
/// a stuck DOF creeps at compliance × force (PHYSICS.md §1.3).
///
/// N is the previous step's by default (the first step after enabling has no
/// friction beyond the minimum range). setEnableNonLinearDirectSolveUpdate
/// asks for the current step's N; AGX iterates the direct solve for it. Our
/// solver has no outer loop for bounds that depend on other rows, so this
/// mode is approximated: the bound uses N extrapolated to the current step,
/// max(0, 2Nₖ − Nₖ₋₁), which removes the one-step lag for a normal force
/// that changes linearly in time (error O(h²) instead of O(h)). A friction
/// row only ever dissipates, so a wrong bound cannot add energy.
///
/// The bounds replace the force range of SecondaryConstraint (unused here).
/// Disabled by default; default μ = 0.4167 (seed).
template <Scalar S>
class FrictionControllerT : public SecondaryConstraintT<S> {
 public:
  FrictionControllerT() : SecondaryConstraintT<S>("FrictionController") {}

  /// μ (dimensionless; m for a rotational DOF, the axle radius included), ≥ 0.
  [[nodiscard]] S getFrictionCoefficient() const { return mu_; }
  void setFrictionCoefficient(S mu);

  /// Friction force (N or N·m) available even without a normal force:
  /// [lower, upper] with lower ≤ 0 ≤ upper. Default [0, 0].
  [[nodiscard]] RangeT<S> getMinimumStaticFrictionForceRange() const { return minimum_; }
  void setMinimumStaticFrictionForceRange(S lower, S upper);
  void setMinimumStaticFrictionForceRange(RangeT<S> range) { setMinimumStaticFrictionForceRange(range.lower, range.upper); }

  /// Current-step normal force (approximated, see the class comment); default off.
  [[nodiscard]] bool getEnableNonLinearDirectSolveUpdate() const { return nonLinear_; }
  void setEnableNonLinearDirectSolveUpdate(bool enable) { nonLinear_ = enable; }

  /// The normal force (N) the joint carried in the last step.
  [[nodiscard]] S getNormalForce() const { return S(normal_); }
  /// The friction bound (N or N·m) used in the last step, ≥ 0.
  [[nodiscard]] S getCurrentFrictionBound() const { return S(bound_); }

  // Called by the joint: this step's row on the DOF `c`.
  void addRows(detail::RowSink& sink, const detail::Coordinate& c);
  /// The joint's normal force of the step just solved (N).
  void setStepNormalForce(double normal);
  /// The joint this controller belongs to (for error messages).
  void setJoint(const ConstraintT<S>* joint) { label_.set(joint); }

 protected:
  ~FrictionControllerT() override = default;

 private:
  S mu_ = S(0.4167);
  RangeT<S> minimum_{S(0), S(0)};
  bool nonLinear_ = false;
  double normal_ = 0.0, previousNormal_ = 0.0;
  int samples_ = 0;
  double bound_ = 0.0;
  detail::JointLabel<S> label_;
};

template <Scalar S>
void FrictionControllerT<S>::setFrictionCoefficient(S mu) {
  if (!(std::isfinite(mu) && mu >= S(0)))
    throw label_.error(this->kind_, "friction coefficient must be finite and >= 0", mu);
  mu_ = mu;
}

template <Scalar S>
void FrictionControllerT<S>::setMinimumStaticFrictionForceRange(S lower, S upper) {
  if (!(std::isfinite(lower) && std::isfinite(upper) && lower <= S(0) && upper >= S(0)))
    throw label_.error(this->kind_, "minimum static friction range must be finite with lower <= 0 <= upper (N or N·m)",
                       Eigen::Matrix<S, 2, 1>(lower, upper));
  minimum_ = {lower, upper};
}

template <Scalar S>
void FrictionControllerT<S>::addRows(detail::RowSink& sink, const detail::Coordinate& c) {
  if (!this->enable_) {
    bound_ = 0.0;
    return;
  }
  double n = normal_;
  if (nonLinear_ && samples_ >= 2) n = std::max(0.0, 2.0 * normal_ - previousNormal_);
  const double slide = double(mu_) * n;
  const double lower = std::min(-slide, double(minimum_.lower));
  const double upper = std::max(slide, double(minimum_.upper));
  bound_ = std::max(-lower, upper);
  if (lower == 0.0 && upper == 0.0) return;  // nothing to hold
  detail::Row& row = this->addRow(sink, c);
  row.holonomic = false;
  row.speed = 0.0;
  row.lower = lower;
  row.upper = upper;
}

template <Scalar S>
void FrictionControllerT<S>::setStepNormalForce(double normal) {
  previousNormal_ = normal_;
  normal_ = std::isfinite(normal) ? normal : 0.0;
  samples_ = std::min(samples_ + 1, 2);
}

SPOOK_COMPILED_ONCE(class, FrictionControllerT)

using FrictionController = FrictionControllerT<double>;
using FrictionControllerRef = ref_ptr<FrictionController>;
namespace f32 {
using FrictionController = FrictionControllerT<float>;
using FrictionControllerRef = ref_ptr<FrictionController>;
}  // namespace f32

}  // namespace spook
