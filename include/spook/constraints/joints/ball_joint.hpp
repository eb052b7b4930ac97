#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <spook/constraints/joint.hpp>
#include <spook/constraints/secondary/cone_limit.hpp>
#include <spook/constraints/secondary/friction_controller.hpp>
#include <spook/constraints/secondary/twist_range.hpp>

namespace spook {

/// The frame origins held together, rotation free: one Spherical (seed 001
/// §12.4). Frame 2 is the base of its secondary constraints: a ConeLimit on
/// frame 1's z axis, a TwistRangeController on the twist about it, and a
/// rotational FrictionController about each axis U, V, N (x, y, z of frame
/// 2). All disabled by default.
template <Scalar S>
class BallJointT : public ElementaryJointT<S, detail::Spherical> {
  using Base = ElementaryJointT<S, detail::Spherical>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, NUM_DOF };

  BallJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr);

  /// Keeps frame 1's z axis in a cone about frame 2's (seed 001 §12.4.1).
  [[nodiscard]] ConeLimitT<S>* getConeLimit() const { return cone_.get(); }
  /// Limits the twist of frame 1 about its z axis (seed 001 §12.4.2).
  [[nodiscard]] TwistRangeControllerT<S>* getTwistRangeController() const { return twist_.get(); }

  /// Friction on the rotation about frame 2's x (U), y (V) and z (N) axes
  /// (seed 001 §12.4.3). Each bound is μ N (N·m; μ in m, the ball's radius
  /// included) with N the magnitude of the ball joint's constraint force
  /// (N) of the previous step: a ball has no axis, so the whole load presses
  /// it into its socket.
  [[nodiscard]] FrictionControllerT<S>* getRotationalFrictionControllerU() const { return friction_[0].get(); }
  [[nodiscard]] FrictionControllerT<S>* getRotationalFrictionControllerV() const { return friction_[1].get(); }
  [[nodiscard]] FrictionControllerT<S>* getRotationalFrictionControllerN() const { return friction_[2].get(); }
  /// U, V and N in that order.
  [[nodiscard]] std::vector<ref_ptr<FrictionControllerT<S>>> getRotationalFrictionControllers() const;
  /// Enables or disables the three rotational friction controllers.
  void setEnableRotationalFriction(bool enable);
  /// μ (m, radius included, ≥ 0) of the three; on bad input none changes.
  void setRotationalFrictionCoefficient(S mu);

  /// Angle between frame 1's z axis and frame 2's (rad, 0..π).
  [[nodiscard]] S getSwingAngle() const;
  /// Twist of frame 1 about its z axis relative to frame 2's (rad, −π..π).
  [[nodiscard]] S getTwistAngle() const;

 protected:
  ~BallJointT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void afterSolve(double h) override;

 private:
  ref_ptr<ConeLimitT<S>> cone_ = new ConeLimitT<S>();
  ref_ptr<TwistRangeControllerT<S>> twist_ = new TwistRangeControllerT<S>();
  std::array<ref_ptr<FrictionControllerT<S>>, 3> friction_{new FrictionControllerT<S>(), new FrictionControllerT<S>(),
                                                           new FrictionControllerT<S>()};
  detail::JointLoad load_;  // the normal force for the friction controllers
};

template <Scalar S>
BallJointT<S>::BallJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2, FrameT<S>* frame2)
    : Base("BallJoint", body1, frame1, body2, frame2) {
  cone_->setJoint(this);
  twist_->setJoint(this);
  for (auto& f : friction_) f->setJoint(this);
}

template <Scalar S>
std::vector<ref_ptr<FrictionControllerT<S>>> BallJointT<S>::getRotationalFrictionControllers() const {
  return {friction_.begin(), friction_.end()};
}

template <Scalar S>
void BallJointT<S>::setEnableRotationalFriction(bool enable) {
  for (auto& f : friction_) f->setEnable(enable);
}

template <Scalar S>
void BallJointT<S>::setRotationalFrictionCoefficient(S mu) {
  friction_[0]->setFrictionCoefficient(mu);  // throws before anything changed
  for (auto& f : friction_) f->setFrictionCoefficient(mu);
}

template <Scalar S>
S BallJointT<S>::getSwingAngle() const {
  return S(detail::coneState(this->attachments(), 1.0, 1.0).tilt);
}

template <Scalar S>
S BallJointT<S>::getTwistAngle() const {
  return S(detail::twistCoordinate(this->attachments()).value);
}

template <Scalar S>
void BallJointT<S>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  const std::size_t first = sink.rows->size();
  this->addElementaryRows(a, sink);
  load_.record(sink, first, a.R2.col(2));
  cone_->beginStep();
  cone_->addRows(sink, a, h);
  twist_->beginStep();
  twist_->addRows(sink, a, h);
  for (int k = 0; k < 3; ++k) {
    FrictionControllerT<S>& f = *friction_[static_cast<std::size_t>(k)];
    f.beginStep();
    f.addRows(sink, detail::angleAbout(a, 0.0, a.R2.col(k)));
  }
}

template <Scalar S>
void BallJointT<S>::afterSolve(double h) {
  cone_->endStep(h);
  twist_->endStep(h);
  const double normal = load_.normal(load_.force(h), false);
  for (auto& f : friction_) {
    f->endStep(h);
    f->setStepNormalForce(normal);
  }
}

SPOOK_COMPILED_ONCE(class, BallJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Spherical)

using BallJoint = BallJointT<double>;
using BallJointRef = ref_ptr<BallJoint>;
namespace f32 {
using BallJoint = BallJointT<float>;
using BallJointRef = ref_ptr<BallJoint>;
}  // namespace f32

}  // namespace spook
