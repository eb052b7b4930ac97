#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>

#include <spook/constraints/constraint.hpp>

namespace spook {

/// Extra inertia along and about a constraint's axis (seed 001 §12.19): a
/// virtual mass (kg) that resists each body's acceleration along the z axis
/// of its attachment frame and a virtual moment of inertia (kg·m²) that
/// resists its angular acceleration about that axis. Virtual inertia has no
/// weight: gravity still acts on the body's own mass only. Add it to the
/// simulation after the constraint; it keeps acting while the constraint is
/// disabled (its axis is still defined by the frames).
///
/// Each non-zero inertia m is one velocity row G v⁺ + (γ/h)Λ = G v on the
/// body alone, with G its direction and γ = h/m: the row's impulse is
/// Λ = −m G(v⁺ − v), the force m a of the extra inertia over the step, which
/// is what adding m·G Gᵀ to the body's mass matrix gives in the implicit
/// step (PHYSICS.md §1.3).
template <Scalar S>
class VirtualConstraintInertiaT : public ConstraintT<S> {
 public:
  using Constraint = ConstraintT<S>;

  enum DOF { BODY1_TRANSLATIONAL = 0, BODY1_ROTATIONAL, BODY2_TRANSLATIONAL, BODY2_ROTATIONAL, NUM_DOF };

  /// Virtual mass (kg) and moment of inertia (kg·m²) of each body of
  /// `constraint`; zero for none. A body the constraint does not have (the
  /// world) takes no inertia.
  VirtualConstraintInertiaT(Constraint* constraint, S body1Translational, S body1Rotational, S body2Translational,
                            S body2Rotational);

  [[nodiscard]] Constraint* getConstraint() const { return constraint_.get(); }

  /// Sets the virtual mass (kg) and moment of inertia (kg·m²) of body `index` (0 or 1).
  void setInertia(int index, S translational, S rotational);
  [[nodiscard]] S getTranslationalInertia(int index) const { return inertia_[slot(checkedIndex(index), false)]; }
  [[nodiscard]] S getRotationalInertia(int index) const { return inertia_[slot(checkedIndex(index), true)]; }

  /// Rows this step: one per non-zero inertia.
  [[nodiscard]] int getNumDOF() const override;

 protected:
  ~VirtualConstraintInertiaT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  /// The frames are the constraint's: rebind leaves them to it.
  [[nodiscard]] bool rebindsFrames() const override { return false; }

 private:
  static Constraint* checked(Constraint* constraint);
  static std::size_t slot(int index, bool rotational) {
    return static_cast<std::size_t>(2 * index + (rotational ? 1 : 0));
  }
  int checkedIndex(int index) const;
  void checkInertia(int index, const char* what, S value) const;

  ref_ptr<Constraint> constraint_;
  std::array<S, NUM_DOF> inertia_{};
  std::array<double, NUM_DOF> impulse_{};
};

template <Scalar S>
VirtualConstraintInertiaT<S>::VirtualConstraintInertiaT(Constraint* constraint, S body1Translational, S body1Rotational,
                                                        S body2Translational, S body2Rotational)
    : Constraint("VirtualConstraintInertia", checked(constraint)->getBodyAt(0),
                 checked(constraint)->getAttachmentFrame(0), checked(constraint)->getBodyAt(1),
                 checked(constraint)->getAttachmentFrame(1)),
      constraint_(constraint) {
  setInertia(0, body1Translational, body1Rotational);
  setInertia(1, body2Translational, body2Rotational);
}

template <Scalar S>
void VirtualConstraintInertiaT<S>::setInertia(int index, S translational, S rotational) {
  if (index != 0 && index != 1) throw this->error("body index must be 0 or 1", index);
  checkInertia(index, "translational inertia (kg)", translational);
  checkInertia(index, "rotational inertia (kg m^2)", rotational);
  inertia_[slot(index, false)] = translational;
  inertia_[slot(index, true)] = rotational;
}

template <Scalar S>
int VirtualConstraintInertiaT<S>::getNumDOF() const {
  int n = 0;
  for (S m : inertia_) n += m > S(0) ? 1 : 0;
  return n;
}

template <Scalar S>
void VirtualConstraintInertiaT<S>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  for (std::size_t k = 0; k < NUM_DOF; ++k) {
    const double mass = double(inertia_[k]);
    if (!(mass > 0.0)) continue;
    const bool second = k >= BODY2_TRANSLATIONAL;
    const bool rotational = k % 2 == 1;
    const detail::Vec3d axis = (second ? a.R2 : a.R1).col(2);
    const detail::Vec6d J = rotational ? detail::linearAngular(detail::Vec3d::Zero(), axis)
                                       : detail::linearAngular(axis, detail::Vec3d::Zero());
    const detail::Vec6d none = detail::Vec6d::Zero();
    detail::Row& row = second ? sink.add(none, J, &impulse_[k]) : sink.add(J, none, &impulse_[k]);
    row.holonomic = false;
    row.speed = second ? J.dot(a.v2) : J.dot(a.v1);
    row.compliance = h / mass;
  }
}

template <Scalar S>
auto VirtualConstraintInertiaT<S>::checked(Constraint* constraint) -> Constraint* {
  if (!constraint) throw detail::makeError("VirtualConstraintInertia", "", "needs a constraint", "nullptr");
  return constraint;
}

template <Scalar S>
int VirtualConstraintInertiaT<S>::checkedIndex(int index) const {
  if (index != 0 && index != 1) throw this->error("body index must be 0 or 1", index);
  return index;
}

template <Scalar S>
void VirtualConstraintInertiaT<S>::checkInertia(int index, const char* what, S value) const {
  if (!std::isfinite(double(value)) || value < S(0))
    throw this->error(std::string(what) + " of body " + std::to_string(index) + " must be finite and >= 0", value);
  if (value > S(0) && !this->getBodyAt(index))
    throw this->error(std::string(what) + " given for body " + std::to_string(index) + ", which is the world", value);
}

SPOOK_COMPILED_ONCE(class, VirtualConstraintInertiaT)

using VirtualConstraintInertia = VirtualConstraintInertiaT<double>;
using VirtualConstraintInertiaRef = ref_ptr<VirtualConstraintInertia>;
namespace f32 {
using VirtualConstraintInertia = VirtualConstraintInertiaT<float>;
using VirtualConstraintInertiaRef = ref_ptr<VirtualConstraintInertia>;
}  // namespace f32

}  // namespace spook
