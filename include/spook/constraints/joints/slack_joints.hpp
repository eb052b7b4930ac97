#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>

#include <spook/constraints/joint.hpp>
#include <spook/constraints/rows/slack.hpp>
#include <spook/constraints/secondary/screw_1d.hpp>

namespace spook {

/// A joint whose constrained DOFs have slack (seed 001 §12, table 12.2): each
/// moves freely within an interval [lower, upper] (m or rad) and stops at its
/// ends like a contact, which models a gap in a real joint (a tool with a few
/// millimeters of play) without collision geometry. Default slack 0: the
/// joint is then its rigid counterpart. Each DOF keeps one row, as in the
/// rigid joint (not two, as AGX's slack joints): one-sided at the nearer end,
/// carrying force only at that end or in the step or two before reaching it.
///
/// Translational DOFs are the separation of the frame origins along the axes
/// of frame 2 (m); rotational DOFs are angles about the axes of frame 2 (rad),
/// see rows/slack.hpp. `Rigid<S, Rows...>` is the rigid joint machinery
/// (ElementaryJointT, or a Constraint1DOFT / Constraint2DOFT with the free
/// DOFs) over the slack rows `Rows`, which write bilateral rows; this class
/// bounds them.
template <Scalar S, template <Scalar, class...> class Rigid, class... Rows>
class SlackJointT : public Rigid<S, Rows...> {
  using Base = Rigid<S, Rows...>;
  static constexpr std::size_t kNum = sizeof...(Rows);

 public:
  /// The same slack on every DOF, symmetric about the relaxed configuration:
  /// [−positional, positional] (m) on the translational DOFs and
  /// [−rotational, rotational] (rad) on the rotational ones (as AGX, one
  /// value for all rotational DOFs). Both finite and ≥ 0.
  void setSlackParameters(S positional, S rotational) {
    if (!(std::isfinite(positional) && positional >= S(0) && std::isfinite(rotational) && rotational >= S(0)))
      throw this->error("slack must be finite and >= 0 (positional m, rotational rad)",
                        Eigen::Matrix<S, 2, 1>(positional, rotational));
    for (std::size_t i = 0; i < kNum; ++i) {
      const S s = kRotational[i] ? rotational : positional;
      slack_[i] = {-s, s};
    }
  }
  /// The slack interval of one DOF of the joint's DOF enum (m or rad), or of
  /// every DOF with ALL_DOF; finite, lower ≤ upper (it need not contain 0:
  /// an interval beside the relaxed configuration pushes the DOF into it).
  void setSlack(int dof, S lower, S upper) {
    checkDof(dof, true);
    if (!(std::isfinite(lower) && std::isfinite(upper) && lower <= upper))
      throw this->error("slack must have finite lower <= upper (m or rad)", Eigen::Matrix<S, 2, 1>(lower, upper));
    if (dof == Base::ALL_DOF)
      slack_.fill({lower, upper});
    else
      slack_[static_cast<std::size_t>(dof)] = {lower, upper};
  }
  void setSlack(int dof, RangeT<S> slack) { setSlack(dof, slack.lower, slack.upper); }
  /// The slack interval of one DOF (m or rad).
  [[nodiscard]] RangeT<S> getSlack(int dof) const {
    checkDof(dof, false);
    return slack_[static_cast<std::size_t>(dof)];
  }
  /// The force (N) or torque (N·m) the slack row of that DOF applied in the
  /// last step: zero while the DOF is inside its slack, the load at its end.
  [[nodiscard]] S getSlackForce(int dof) const {
    checkDof(dof, false);
    return force_[static_cast<std::size_t>(dof)];
  }

 protected:
  using typename ConstraintT<S>::Body;
  using typename ConstraintT<S>::Frame;
  SlackJointT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2)
      : Base(kind, body1, frame1, body2, frame2) {
    static_assert(kNum == std::size_t(Base::kNumRows), "one slack interval per row");
  }
  ~SlackJointT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override {
    const std::size_t first = sink.rows->size();
    // ElementaryJointT leaves addRows to the joint; the DOF joints write the
    // elementary rows first, then their controllers' rows.
    if constexpr (std::is_abstract_v<Base>)
      this->addElementaryRows(a, sink);
    else
      Base::addRows(a, sink, h);
    for (std::size_t i = 0; i < kNum; ++i) {
      detail::Row& row = (*sink.rows)[first + i];
      interval(i).restrict(row);
      impulses_[i] = sink.slot(first + i);
    }
  }
  void afterSolve(double h) override {
    Base::afterSolve(h);
    for (std::size_t i = 0; i < kNum; ++i) force_[i] = impulses_[i] ? S(*impulses_[i] / h) : S(0);
  }
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override {
    const std::size_t first = sink.rows->size();
    Base::addProjectionRows(a, sink);
    sink.keepRows(first, [&](detail::Row& row, std::size_t i, const double* impulse) {
      return i >= kNum || interval(i).restrictProjection(row, impulse);
    });
  }

 private:
  static constexpr std::array<bool, kNum> kRotational{detail::kRotationalSlackRow<Rows>...};

  [[nodiscard]] detail::SlackInterval interval(std::size_t i) const {
    return {double(slack_[i].lower), double(slack_[i].upper)};
  }
  void checkDof(int dof, bool allowAll) const {
    if (!((allowAll && dof == Base::ALL_DOF) || (dof >= 0 && dof < int(kNum))))
      throw this->error("DOF index out of range 0.." + std::to_string(kNum - 1), dof);
  }

  std::array<RangeT<S>, kNum> slack_ = [] {
    std::array<RangeT<S>, kNum> zero{};
    zero.fill({S(0), S(0)});
    return zero;
  }();
  std::array<const double*, kNum> impulses_{};
  std::array<S, kNum> force_{};
};

namespace detail {
// The rigid joint machinery each slack joint bounds: its free DOFs and their controllers.
template <Scalar S, class... Rows>
using RotationalDofOver = Constraint1DOFT<S, RotationalZ, Rows...>;
template <Scalar S, class... Rows>
using TranslationalDofOver = Constraint1DOFT<S, TranslationalZ, Rows...>;
template <Scalar S, class... Rows>
using CylindricalDofsOver = Constraint2DOFT<S, TranslationalZ, RotationalZ, Rows...>;
}  // namespace detail

/// A Hinge with slack (seed 001 table 12.2): rotation about z of the frames
/// free, with its Motor1D, Lock1D and Range1D; the three translations (along
/// x, y, z of frame 2, m) and the two tilts of z₁ about x₂ and y₂ (rad)
/// constrained within their slack.
template <Scalar S>
class SlackHingeJointT : public SlackJointT<S, detail::RotationalDofOver, detail::Dot2<0>, detail::Dot2<1>,
                                            detail::Dot2<2>, detail::TiltAngle<0>, detail::TiltAngle<1>> {
  using Base = SlackJointT<S, detail::RotationalDofOver, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                           detail::TiltAngle<0>, detail::TiltAngle<1>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, ROTATIONAL_1, ROTATIONAL_2, NUM_DOF };

  SlackHingeJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                   FrameT<S>* frame2 = nullptr)
      : Base("SlackHingeJoint", body1, frame1, body2, frame2) {}

 protected:
  ~SlackHingeJointT() override = default;
};

SPOOK_COMPILED_ONCE(class, SlackHingeJointT)
SPOOK_COMPILED_JOINT_BASE(SlackJointT, detail::RotationalDofOver, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                          detail::TiltAngle<0>, detail::TiltAngle<1>)
SPOOK_COMPILED_JOINT_BASE(Constraint1DOFT, detail::RotationalZ, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                          detail::TiltAngle<0>, detail::TiltAngle<1>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>, detail::TiltAngle<0>,
                          detail::TiltAngle<1>)

/// A Prismatic with slack: translation along z free, with its Motor1D, Lock1D
/// and Range1D; the two translations across z (along x₂, y₂, m) and the three
/// rotations about x₂, y₂, z₂ (rad) constrained within their slack.
template <Scalar S>
class SlackPrismaticJointT
    : public SlackJointT<S, detail::TranslationalDofOver, detail::Dot2<0>, detail::Dot2<1>, detail::RotationAngle<0>,
                         detail::RotationAngle<1>, detail::RotationAngle<2>> {
  using Base = SlackJointT<S, detail::TranslationalDofOver, detail::Dot2<0>, detail::Dot2<1>,
                           detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, ROTATIONAL_2, ROTATIONAL_3, NUM_DOF };

  SlackPrismaticJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                       FrameT<S>* frame2 = nullptr)
      : Base("SlackPrismaticJoint", body1, frame1, body2, frame2) {}

 protected:
  ~SlackPrismaticJointT() override = default;
};

SPOOK_COMPILED_ONCE(class, SlackPrismaticJointT)
SPOOK_COMPILED_JOINT_BASE(SlackJointT, detail::TranslationalDofOver, detail::Dot2<0>, detail::Dot2<1>,
                          detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>)
SPOOK_COMPILED_JOINT_BASE(Constraint1DOFT, detail::TranslationalZ, detail::Dot2<0>, detail::Dot2<1>,
                          detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::RotationAngle<0>,
                          detail::RotationAngle<1>, detail::RotationAngle<2>)

/// A LockJoint with slack: all six DOFs (translations along and rotations
/// about the axes of frame 2) move freely within their slack.
template <Scalar S>
class SlackLockJointT
    : public SlackJointT<S, ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                         detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>> {
  using Base = SlackJointT<S, ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                           detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, ROTATIONAL_1, ROTATIONAL_2, ROTATIONAL_3, NUM_DOF };

  explicit SlackLockJointT(RigidBodyT<S>* body1, FrameT<S>* frame1 = nullptr, RigidBodyT<S>* body2 = nullptr,
                           FrameT<S>* frame2 = nullptr)
      : Base("SlackLockJoint", body1, frame1, body2, frame2) {}

 protected:
  ~SlackLockJointT() override = default;
};

SPOOK_COMPILED_ONCE(class, SlackLockJointT)
SPOOK_COMPILED_JOINT_BASE(SlackJointT, ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>,
                          detail::RotationAngle<0>, detail::RotationAngle<1>, detail::RotationAngle<2>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot2<2>, detail::RotationAngle<0>,
                          detail::RotationAngle<1>, detail::RotationAngle<2>)

/// A CylindricalJoint with slack: translation along and rotation about z free
/// (FIRST, SECOND) with their controllers and the Screw1D coupling; the two
/// translations across z (m) and the two tilts of z₁ about x₂, y₂ (rad)
/// constrained within their slack.
template <Scalar S>
class SlackCylindricalJointT : public SlackJointT<S, detail::CylindricalDofsOver, detail::Dot2<0>, detail::Dot2<1>,
                                                  detail::TiltAngle<0>, detail::TiltAngle<1>> {
  using Base = SlackJointT<S, detail::CylindricalDofsOver, detail::Dot2<0>, detail::Dot2<1>, detail::TiltAngle<0>,
                           detail::TiltAngle<1>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, ROTATIONAL_2, NUM_DOF };

  SlackCylindricalJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                         FrameT<S>* frame2 = nullptr)
      : Base("SlackCylindricalJoint", body1, frame1, body2, frame2) {}

  [[nodiscard]] Screw1DT<S>* getScrew1D() const { return screw_.get(); }
  /// The screw's lead (m per revolution).
  void setLead(S lead) { screw_->setLead(lead); }

 protected:
  ~SlackCylindricalJointT() override = default;
  void addCouplingRows(const detail::Coordinate& translation, const detail::Coordinate& angle,
                       detail::RowSink& sink) override;
  void afterCoupling(double h) override { screw_->endStep(h); }

 private:
  ref_ptr<Screw1DT<S>> screw_ = new Screw1DT<S>();
};

template <Scalar S>
void SlackCylindricalJointT<S>::addCouplingRows(const detail::Coordinate& translation, const detail::Coordinate& angle,
                                                detail::RowSink& sink) {
  screw_->beginStep();
  screw_->addRows(sink, translation, angle);
}

SPOOK_COMPILED_ONCE(class, SlackCylindricalJointT)
SPOOK_COMPILED_JOINT_BASE(SlackJointT, detail::CylindricalDofsOver, detail::Dot2<0>, detail::Dot2<1>,
                          detail::TiltAngle<0>, detail::TiltAngle<1>)
SPOOK_COMPILED_JOINT_BASE(Constraint2DOFT, detail::TranslationalZ, detail::RotationalZ, detail::Dot2<0>,
                          detail::Dot2<1>, detail::TiltAngle<0>, detail::TiltAngle<1>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::TiltAngle<0>,
                          detail::TiltAngle<1>)

using SlackHingeJoint = SlackHingeJointT<double>;
using SlackHingeJointRef = ref_ptr<SlackHingeJoint>;
using SlackPrismaticJoint = SlackPrismaticJointT<double>;
using SlackPrismaticJointRef = ref_ptr<SlackPrismaticJoint>;
using SlackLockJoint = SlackLockJointT<double>;
using SlackLockJointRef = ref_ptr<SlackLockJoint>;
using SlackCylindricalJoint = SlackCylindricalJointT<double>;
using SlackCylindricalJointRef = ref_ptr<SlackCylindricalJoint>;
namespace f32 {
using SlackHingeJoint = SlackHingeJointT<float>;
using SlackHingeJointRef = ref_ptr<SlackHingeJoint>;
using SlackPrismaticJoint = SlackPrismaticJointT<float>;
using SlackPrismaticJointRef = ref_ptr<SlackPrismaticJoint>;
using SlackLockJoint = SlackLockJointT<float>;
using SlackLockJointRef = ref_ptr<SlackLockJoint>;
using SlackCylindricalJoint = SlackCylindricalJointT<float>;
using SlackCylindricalJointRef = ref_ptr<SlackCylindricalJoint>;
}  // namespace f32

}  // namespace spook
