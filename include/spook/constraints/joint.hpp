#pragma once

#include <array>
#include <cstddef>
#include <utility>

#include <spook/constraints/constraint.hpp>
#include <spook/constraints/rows/elementary.hpp>
#include <spook/constraints/regularization.hpp>
#include <spook/constraints/secondary/friction_controller.hpp>
#include <spook/constraints/secondary/lock_1d.hpp>
#include <spook/constraints/secondary/motor_1d.hpp>
#include <spook/constraints/secondary/range_1d.hpp>

namespace spook {

/// A joint made of elementary constraints at compile time (seed 001
/// table 12.5): its rows are the elementary rows in order, one DOF each, each
/// with its own compliance and damping. No virtual call per row. A joint
/// whose DOF is held by another row (DistanceJoint: its Lock1D) overrides
/// getNumDOF and dofParameters.
template <Scalar S, class... Elementary>
class ElementaryJointT : public ConstraintT<S> {
 public:
  static constexpr int kNumRows = (Elementary::kRows + ... + 0);
  static constexpr int ALL_DOF = -1;

  [[nodiscard]] int getNumDOF() const override { return kNumRows; }

  /// Compliance (m/N or rad/(N·m)) of one DOF, or of all with ALL_DOF.
  void setCompliance(S compliance, int dof = ALL_DOF);
  /// SPOOK damping (s) of one DOF, or of all with ALL_DOF.
  void setDamping(S damping, int dof = ALL_DOF);
  [[nodiscard]] S getCompliance(int dof) const { return parameters(dof).getCompliance(); }
  [[nodiscard]] S getDamping(int dof) const { return parameters(dof).getDamping(); }
  [[nodiscard]] RegularizationParametersT<S>* getRegularizationParameters(int dof);

  /// Quaternion-based rows (QuatLock) follow Hooke's law in radians when on
  /// (seed 001 §12.1.3); default off.
  [[nodiscard]] bool getEnableLinearization() const { return options_.linearize; }
  void setEnableLinearization(bool enable) { options_.linearize = enable; }

 protected:
  using typename ConstraintT<S>::Body;
  using typename ConstraintT<S>::Frame;
  ElementaryJointT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2)
      : ConstraintT<S>(kind, body1, frame1, body2, frame2) {}
  ~ElementaryJointT() override = default;

  /// Compliance and damping of DOF `dof` (0 ≤ dof < getNumDOF()).
  [[nodiscard]] virtual const RegularizationParametersT<S>& dofParameters(int dof) const {
    return parameters_[static_cast<std::size_t>(dof)];
  }

  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override {
    addElementaryRows(a, sink);
  }
  void addElementaryRows(const detail::Attachments& a, detail::RowSink& sink);

 private:
  void checkDof(int dof, bool allowAll = true) const;
  template <class F>
  void forDof(int dof, F&& f);
  [[nodiscard]] RegularizationParametersT<S>& mutableDofParameters(int dof) {
    return const_cast<RegularizationParametersT<S>&>(std::as_const(*this).dofParameters(dof));
  }
  [[nodiscard]] const RegularizationParametersT<S>& parameters(int dof) const;

  std::array<RegularizationParametersT<S>, kNumRows> parameters_{};
  std::array<double, kNumRows> impulses_{};
  detail::ElementaryOptions options_;
};

template <Scalar S, class... Elementary>
void ElementaryJointT<S, Elementary...>::setCompliance(S compliance, int dof) {
  checkDof(dof);
  RegularizationParametersT<S>{}.setCompliance(compliance);
  forDof(dof, [&](RegularizationParametersT<S>& p) { p.setCompliance(compliance); });
}

template <Scalar S, class... Elementary>
void ElementaryJointT<S, Elementary...>::setDamping(S damping, int dof) {
  checkDof(dof);
  RegularizationParametersT<S>{}.setDamping(damping);
  forDof(dof, [&](RegularizationParametersT<S>& p) { p.setDamping(damping); });
}

template <Scalar S, class... Elementary>
RegularizationParametersT<S>* ElementaryJointT<S, Elementary...>::getRegularizationParameters(int dof) {
  checkDof(dof, false);
  return &mutableDofParameters(dof);
}

template <Scalar S, class... Elementary>
void ElementaryJointT<S, Elementary...>::addElementaryRows(const detail::Attachments& a, detail::RowSink& sink) {
  std::array<detail::RowParameters, kNumRows> p{};
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = {double(parameters_[i].getCompliance()), double(parameters_[i].getDamping())};
  [[maybe_unused]] int offset = 0;
  ((Elementary::addRows(a, sink, p.data() + offset, impulses_.data() + offset, options_), offset += Elementary::kRows),
   ...);
}

template <Scalar S, class... Elementary>
void ElementaryJointT<S, Elementary...>::checkDof(int dof, bool allowAll) const {
  const int count = this->getNumDOF();
  if (!((allowAll && dof == ALL_DOF) || (dof >= 0 && dof < count)))
    throw this->error("DOF index out of range 0.." + std::to_string(count - 1), dof);
}

template <Scalar S, class... Elementary>
template <class F>
void ElementaryJointT<S, Elementary...>::forDof(int dof, F&& f) {
  if (dof == ALL_DOF)
    for (int i = 0; i < this->getNumDOF(); ++i) f(mutableDofParameters(i));
  else
    f(mutableDofParameters(dof));
}

template <Scalar S, class... Elementary>
const RegularizationParametersT<S>& ElementaryJointT<S, Elementary...>::parameters(int dof) const {
  checkDof(dof, false);
  return dofParameters(dof);
}

/// One free DOF of a joint, measured by `Free::measure` (an angle with
/// winding or a position), with the Motor1D, Lock1D, Range1D and
/// FrictionController acting on it.
template <Scalar S, class Free>
class FreeDofT {
 public:
  [[nodiscard]] Motor1DT<S>* motor() const { return motor_.get(); }
  [[nodiscard]] Lock1DT<S>* lock() const { return lock_.get(); }
  [[nodiscard]] Range1DT<S>* range() const { return range_.get(); }
  [[nodiscard]] FrictionControllerT<S>* friction() const { return friction_.get(); }

  /// The coordinate now (winding applied, not recorded).
  [[nodiscard]] detail::Coordinate measure(const detail::Attachments& a) const {
    detail::Coordinate c = Free::measure(a);
    if (c.rotational) c.value = winding_.unwrap(c.value);
    return c;
  }
  /// The coordinate of this step, recorded for the winding, and the rows of
  /// the enabled controllers.
  detail::Coordinate addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
    const detail::Coordinate c = measure(a);
    winding_.update(c.value);
    motor_->beginStep();
    lock_->beginStep();
    range_->beginStep();
    friction_->beginStep();
    motor_->addRows(sink, c);
    lock_->addRows(sink, c);
    range_->addRows(sink, c, h);
    friction_->addRows(sink, c);
    return c;
  }
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) { lock_->addProjectionRow(sink, measure(a)); }
  void afterSolve(double h) {
    motor_->endStep(h);
    lock_->endStep(h);
    range_->endStep(h);
    friction_->endStep(h);
  }
  /// Restarts the winding at the current value.
  void restart(const detail::Attachments& a) {
    winding_.reset();
    winding_.update(measure(a).value);
  }

 private:
  ref_ptr<Motor1DT<S>> motor_ = new Motor1DT<S>();
  ref_ptr<Lock1DT<S>> lock_ = new Lock1DT<S>();
  ref_ptr<Range1DT<S>> range_ = new Range1DT<S>();
  ref_ptr<FrictionControllerT<S>> friction_ = new FrictionControllerT<S>();
  detail::Winding winding_;
};

/// A joint with one free DOF and Motor1D, Lock1D, Range1D and
/// FrictionController acting on it.
template <Scalar S, class Free, class... Elementary>
class Constraint1DOFT : public ElementaryJointT<S, Elementary...> {
 public:
  [[nodiscard]] Motor1DT<S>* getMotor1D() const { return dof_.motor(); }
  [[nodiscard]] Lock1DT<S>* getLock1D() const { return dof_.lock(); }
  [[nodiscard]] Range1DT<S>* getRange1D() const { return dof_.range(); }
  /// Internal friction of the free DOF (seed 001 §12.15.4); disabled by default.
  [[nodiscard]] FrictionControllerT<S>* getFrictionController() const { return dof_.friction(); }

  /// The free DOF's current value: rad (with winding) or m.
  [[nodiscard]] S getAngle() const;
  /// Its rate (rad/s or m/s).
  [[nodiscard]] S getCurrentSpeed() const;

 protected:
  using typename ConstraintT<S>::Body;
  using typename ConstraintT<S>::Frame;
  Constraint1DOFT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2);
  ~Constraint1DOFT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override;
  void afterSolve(double h) override;
  void onRebind() override;

 private:
  FreeDofT<S, Free> dof_;
  detail::JointLoad load_;  // the normal force for the friction controller
};

template <Scalar S, class Free, class... Elementary>
S Constraint1DOFT<S, Free, Elementary...>::getAngle() const {
  return S(dof_.measure(this->attachments()).value);
}

template <Scalar S, class Free, class... Elementary>
S Constraint1DOFT<S, Free, Elementary...>::getCurrentSpeed() const {
  return S(dof_.measure(this->attachments()).speed);
}

template <Scalar S, class Free, class... Elementary>
Constraint1DOFT<S, Free, Elementary...>::Constraint1DOFT(const char* kind, Body* body1, Frame* frame1, Body* body2,
                                                         Frame* frame2)
    : ElementaryJointT<S, Elementary...>(kind, body1, frame1, body2, frame2) {
  dof_.restart(this->attachments());
  dof_.friction()->setJoint(this);
}

template <Scalar S, class Free, class... Elementary>
void Constraint1DOFT<S, Free, Elementary...>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  const std::size_t first = sink.rows->size();
  this->addElementaryRows(a, sink);
  load_.record(sink, first, a.R2.col(2));
  dof_.addRows(a, sink, h);
}

template <Scalar S, class Free, class... Elementary>
void Constraint1DOFT<S, Free, Elementary...>::addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) {
  this->addElementaryRows(a, sink);
  dof_.addProjectionRows(a, sink);
}

template <Scalar S, class Free, class... Elementary>
void Constraint1DOFT<S, Free, Elementary...>::afterSolve(double h) {
  dof_.afterSolve(h);
  dof_.friction()->setStepNormalForce(load_.normal(load_.force(h)));
}

template <Scalar S, class Free, class... Elementary>
void Constraint1DOFT<S, Free, Elementary...>::onRebind() {
  dof_.restart(this->attachments());
}

/// A joint with two free DOFs (FIRST, SECOND), each with its Motor1D, Lock1D
/// and Range1D (seed 001 §12.10).
template <Scalar S, class Free1, class Free2, class... Elementary>
class Constraint2DOFT : public ElementaryJointT<S, Elementary...> {
 public:
  enum DOF_INDEX { FIRST = 0, SECOND = 1 };

  [[nodiscard]] Motor1DT<S>* getMotor1D(int index) const { return index == FIRST ? first_.motor() : second(index).motor(); }
  [[nodiscard]] Lock1DT<S>* getLock1D(int index) const { return index == FIRST ? first_.lock() : second(index).lock(); }
  [[nodiscard]] Range1DT<S>* getRange1D(int index) const { return index == FIRST ? first_.range() : second(index).range(); }
  /// Internal friction of DOF `index` (seed 001 §12.15.4); disabled by default.
  [[nodiscard]] FrictionControllerT<S>* getFrictionController(int index) const {
    return index == FIRST ? first_.friction() : second(index).friction();
  }
  /// The free DOF's current value: rad (with winding) or m.
  [[nodiscard]] S getAngle(int index) const;
  [[nodiscard]] S getCurrentSpeed(int index) const;

 protected:
  using typename ConstraintT<S>::Body;
  using typename ConstraintT<S>::Frame;
  Constraint2DOFT(const char* kind, Body* body1, Frame* frame1, Body* body2, Frame* frame2);
  ~Constraint2DOFT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override;
  void afterSolve(double h) override;
  void onRebind() override { restart(); }
  /// Rows tying the two DOFs together (Screw1D); none by default.
  virtual void addCouplingRows(const detail::Coordinate&, const detail::Coordinate&, detail::RowSink&) {}
  virtual void afterCoupling(double) {}

 private:
  const FreeDofT<S, Free2>& second(int index) const;
  void restart();

  FreeDofT<S, Free1> first_;
  FreeDofT<S, Free2> second_;
  detail::JointLoad load_;  // the normal force for the friction controllers
};

template <Scalar S, class Free1, class Free2, class... Elementary>
S Constraint2DOFT<S, Free1, Free2, Elementary...>::getAngle(int index) const {
  const auto a = this->attachments();
  return S(index == FIRST ? first_.measure(a).value : second(index).measure(a).value);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
S Constraint2DOFT<S, Free1, Free2, Elementary...>::getCurrentSpeed(int index) const {
  const auto a = this->attachments();
  return S(index == FIRST ? first_.measure(a).speed : second(index).measure(a).speed);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
Constraint2DOFT<S, Free1, Free2, Elementary...>::Constraint2DOFT(const char* kind, Body* body1, Frame* frame1,
                                                                 Body* body2, Frame* frame2)
    : ElementaryJointT<S, Elementary...>(kind, body1, frame1, body2, frame2) {
  restart();
  first_.friction()->setJoint(this);
  second_.friction()->setJoint(this);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
void Constraint2DOFT<S, Free1, Free2, Elementary...>::addRows(const detail::Attachments& a, detail::RowSink& sink,
                                                              double h) {
  const std::size_t first = sink.rows->size();
  this->addElementaryRows(a, sink);
  load_.record(sink, first, a.R2.col(2));
  const detail::Coordinate c1 = first_.addRows(a, sink, h);
  const detail::Coordinate c2 = second_.addRows(a, sink, h);
  addCouplingRows(c1, c2, sink);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
void Constraint2DOFT<S, Free1, Free2, Elementary...>::addProjectionRows(const detail::Attachments& a,
                                                                        detail::RowSink& sink) {
  this->addElementaryRows(a, sink);
  first_.addProjectionRows(a, sink);
  second_.addProjectionRows(a, sink);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
void Constraint2DOFT<S, Free1, Free2, Elementary...>::afterSolve(double h) {
  first_.afterSolve(h);
  second_.afterSolve(h);
  afterCoupling(h);
  const double normal = load_.normal(load_.force(h));
  first_.friction()->setStepNormalForce(normal);
  second_.friction()->setStepNormalForce(normal);
}

template <Scalar S, class Free1, class Free2, class... Elementary>
auto Constraint2DOFT<S, Free1, Free2, Elementary...>::second(int index) const -> const FreeDofT<S, Free2>& {
  if (index != SECOND) throw this->error("DOF index must be FIRST (0) or SECOND (1)", index);
  return second_;
}

template <Scalar S, class Free1, class Free2, class... Elementary>
void Constraint2DOFT<S, Free1, Free2, Elementary...>::restart() {
  const auto a = this->attachments();
  first_.restart(a);
  second_.restart(a);
}

namespace detail {
struct RotationalZ {
  static Coordinate measure(const Attachments& a) { return rotationalCoordinate(a); }
};
struct TranslationalZ {
  static Coordinate measure(const Attachments& a) { return translationalCoordinate(a); }
};
struct DistanceBetween {
  static Coordinate measure(const Attachments& a) { return distanceCoordinate(a); }
};
}  // namespace detail

// SPOOK_COMPILED_ONCE for a joint's base: the class template `Base` with the
// arguments that follow the scalar.
#define SPOOK_COMPILED_JOINT_BASE(Base, ...) \
  SPOOK_COMPILED_DOUBLE(class Base<double, __VA_ARGS__>) SPOOK_COMPILED_FLOAT(class Base<float, __VA_ARGS__>)

}  // namespace spook
