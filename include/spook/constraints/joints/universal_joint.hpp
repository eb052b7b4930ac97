#pragma once

#include <cmath>

#include <spook/constraints/joint.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

namespace detail {

// The two free rotations of a universal (Cardan) joint. The shafts are the z
// axes of the frames; the cross (spider) has one arm along x₁, fixed in
// frame 1, and one along y₂, fixed in frame 2, kept perpendicular by the
// Dot1 row x₁·y₂ = 0. Every relative orientation that satisfies it is
//   R₂ᵀ R₁ = R_y(b) R_x(a),
// the spider turned by b about y₂ and frame 1 turned by a about the spider's
// x arm x₁. On that manifold ω₁ − ω₂ = ȧ x₁ + ḃ y₂ with x₁ ⊥ y₂, so
// ȧ = x₁·(ω₁ − ω₂) and ḃ = y₂·(ω₁ − ω₂). With Q = R₂ᵀR₁:
// Q e_x = (cos b, 0, −sin b) and Q e_z = (cos a sin b, −sin a, cos a cos b).

/// a: frame 1 about the arm x₁ (rad).
struct UniversalArm1 {
  static Coordinate measure(const Attachments& a);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Coordinate UniversalArm1::measure(const Attachments& a) {
  const Mat3d Q = a.R2.transpose() * a.R1;
  return angleAbout(a, std::atan2(-Q(1, 2), Q(1, 1)), a.R1.col(0));
}
#endif

/// b: the spider about the arm y₂ (rad).
struct UniversalArm2 {
  static Coordinate measure(const Attachments& a);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Coordinate UniversalArm2::measure(const Attachments& a) {
  const Mat3d Q = a.R2.transpose() * a.R1;
  return angleAbout(a, std::atan2(-Q(2, 0), Q(0, 0)), a.R2.col(1));
}
#endif

}  // namespace detail

/// A universal (Cardan) joint (seed 001 §12.5): the frame origins held
/// together (Spherical) and the cross arms x₁ and y₂ kept perpendicular
/// (one Dot1), so twist about the shafts (the z axes) is transmitted while the
/// shafts may bend. The two free rotations, about x₁ and about y₂
/// (ROTATIONAL_CONTROLLER_1 and _2, also FIRST and SECOND), each have a
/// Motor1D, Lock1D and Range1D; getAngle(index) gives them in rad (with
/// winding), zero when the frames coincide. Create it with frames whose z
/// axes run along the shafts and whose x₁ and y₂ are perpendicular.
template <Scalar S>
class UniversalJointT : public Constraint2DOFT<S, detail::UniversalArm1, detail::UniversalArm2, detail::Spherical,
                                               detail::Dot1<0, 1>> {
  using Base =
      Constraint2DOFT<S, detail::UniversalArm1, detail::UniversalArm2, detail::Spherical, detail::Dot1<0, 1>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, ROTATIONAL_1, NUM_DOF };
  /// The free rotations, for getMotor1D, getLock1D, getRange1D, getAngle.
  enum CONTROLLER { ROTATIONAL_CONTROLLER_1 = 0, ROTATIONAL_CONTROLLER_2 = 1 };

  UniversalJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                  FrameT<S>* frame2 = nullptr)
      : Base("UniversalJoint", body1, frame1, body2, frame2) {}

 protected:
  ~UniversalJointT() override = default;
};

SPOOK_COMPILED_ONCE(class, UniversalJointT)
SPOOK_COMPILED_JOINT_BASE(Constraint2DOFT, detail::UniversalArm1, detail::UniversalArm2, detail::Spherical,
                          detail::Dot1<0, 1>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Spherical, detail::Dot1<0, 1>)

/// A universal joint whose center slides along the z axis of frame 2 (seed
/// 001 §12.6): two Dot2 rows keep frame 1's origin on that axis and a Dot1
/// keeps the cross arms x₁ ⊥ y₂ — a telescopic drive shaft. Three free DOFs,
/// each with a Motor1D, Lock1D and Range1D: ROTATIONAL_CONTROLLER_1 and _2 as
/// in UniversalJoint (rad), TRANSLATIONAL_CONTROLLER_1 the position of frame
/// 1's origin along z₂ (m).
template <Scalar S>
class PrismaticUniversalJointT : public ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<0, 1>> {
  using Base = ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<0, 1>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, NUM_DOF };
  enum CONTROLLER { ROTATIONAL_CONTROLLER_1 = 0, ROTATIONAL_CONTROLLER_2 = 1, TRANSLATIONAL_CONTROLLER_1 = 2 };

  PrismaticUniversalJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                           FrameT<S>* frame2 = nullptr);

  [[nodiscard]] Motor1DT<S>* getMotor1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.motor(); });
  }
  [[nodiscard]] Lock1DT<S>* getLock1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.lock(); });
  }
  [[nodiscard]] Range1DT<S>* getRange1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.range(); });
  }
  /// The free DOF's current value: rad (with winding) or m.
  [[nodiscard]] S getAngle(int index) const;
  /// Its rate (rad/s or m/s).
  [[nodiscard]] S getCurrentSpeed(int index) const;

 protected:
  ~PrismaticUniversalJointT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override;
  void afterSolve(double h) override;
  void onRebind() override { restart(); }

 private:
  template <class F>
  auto visit(int index, F&& f) const {
    switch (index) {
      case ROTATIONAL_CONTROLLER_1: return f(arm1_);
      case ROTATIONAL_CONTROLLER_2: return f(arm2_);
      case TRANSLATIONAL_CONTROLLER_1: return f(slide_);
      default:
        throw this->error("controller index must be ROTATIONAL_CONTROLLER_1 (0), ROTATIONAL_CONTROLLER_2 (1) or "
                          "TRANSLATIONAL_CONTROLLER_1 (2)",
                          index);
    }
  }
  void restart();

  FreeDofT<S, detail::UniversalArm1> arm1_;
  FreeDofT<S, detail::UniversalArm2> arm2_;
  FreeDofT<S, detail::TranslationalZ> slide_;
};

template <Scalar S>
PrismaticUniversalJointT<S>::PrismaticUniversalJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2,
                                                      FrameT<S>* frame2)
    : Base("PrismaticUniversalJoint", body1, frame1, body2, frame2) {
  restart();
}

template <Scalar S>
S PrismaticUniversalJointT<S>::getAngle(int index) const {
  const auto a = this->attachments();
  return visit(index, [&](const auto& dof) { return S(dof.measure(a).value); });
}

template <Scalar S>
S PrismaticUniversalJointT<S>::getCurrentSpeed(int index) const {
  const auto a = this->attachments();
  return visit(index, [&](const auto& dof) { return S(dof.measure(a).speed); });
}

template <Scalar S>
void PrismaticUniversalJointT<S>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  this->addElementaryRows(a, sink);
  arm1_.addRows(a, sink, h);
  arm2_.addRows(a, sink, h);
  slide_.addRows(a, sink, h);
}

template <Scalar S>
void PrismaticUniversalJointT<S>::addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) {
  this->addElementaryRows(a, sink);
  arm1_.addProjectionRows(a, sink);
  arm2_.addProjectionRows(a, sink);
  slide_.addProjectionRows(a, sink);
}

template <Scalar S>
void PrismaticUniversalJointT<S>::afterSolve(double h) {
  arm1_.afterSolve(h);
  arm2_.afterSolve(h);
  slide_.afterSolve(h);
}

template <Scalar S>
void PrismaticUniversalJointT<S>::restart() {
  const auto a = this->attachments();
  arm1_.restart(a);
  arm2_.restart(a);
  slide_.restart(a);
}

SPOOK_COMPILED_ONCE(class, PrismaticUniversalJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<0, 1>)

using UniversalJoint = UniversalJointT<double>;
using UniversalJointRef = ref_ptr<UniversalJoint>;
using PrismaticUniversalJoint = PrismaticUniversalJointT<double>;
using PrismaticUniversalJointRef = ref_ptr<PrismaticUniversalJoint>;
namespace f32 {
using UniversalJoint = UniversalJointT<float>;
using UniversalJointRef = ref_ptr<UniversalJoint>;
using PrismaticUniversalJoint = PrismaticUniversalJointT<float>;
using PrismaticUniversalJointRef = ref_ptr<PrismaticUniversalJoint>;
}  // namespace f32

}  // namespace spook
