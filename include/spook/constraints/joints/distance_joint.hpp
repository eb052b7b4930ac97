#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// Keeps the distance between the frame origins (seed 001 §12.7): one
/// translational DOF (table 12.4), held by its Lock1D, which is enabled at the
/// distance at creation. The joint's compliance and damping (setCompliance,
/// setDamping, getRegularizationParameters(TRANSLATIONAL_1)) are that lock's,
/// so the joint acts as a stiff rod or, with a compliance c (m/N), a spring
/// that a load F stretches by F·c. Disable the lock to drive the distance
/// with the motor (a hydraulic actuator) or bound it with the range.
/// getAngle is the distance (m).
template <Scalar S>
class DistanceJointT : public Constraint1DOFT<S, detail::DistanceBetween> {
  using Base = Constraint1DOFT<S, detail::DistanceBetween>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, NUM_DOF = 1 };

  [[nodiscard]] int getNumDOF() const override { return NUM_DOF; }

  DistanceJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr);
  /// From body1's frame to a fixed world point (m).
  DistanceJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, const Vec3T<S>& worldPoint);

 protected:
  ~DistanceJointT() override = default;
  [[nodiscard]] const RegularizationParametersT<S>& dofParameters(int) const override {
    return *this->getLock1D()->getRegularizationParameters();
  }
  [[nodiscard]] bool rebindsFrames() const override { return false; }
  void onRebind() override;

 private:
  static ref_ptr<FrameT<S>> worldFrame(const Vec3T<S>& p);
  void holdCurrentDistance();
};

template <Scalar S>
DistanceJointT<S>::DistanceJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2, FrameT<S>* frame2)
    : Base("DistanceJoint", body1, frame1, body2, frame2) {
  holdCurrentDistance();
}

template <Scalar S>
DistanceJointT<S>::DistanceJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, const Vec3T<S>& worldPoint)
    : Base("DistanceJoint", body1, frame1, nullptr, worldFrame(worldPoint).get()) {
  holdCurrentDistance();
}

template <Scalar S>
void DistanceJointT<S>::onRebind() {
  Base::onRebind();
  holdCurrentDistance();
}

template <Scalar S>
ref_ptr<FrameT<S>> DistanceJointT<S>::worldFrame(const Vec3T<S>& p) {
  if (!p.allFinite()) throw detail::makeError("DistanceJoint", "", "world point must be finite (m)", p);
  ref_ptr<FrameT<S>> frame = new FrameT<S>();
  frame->setTranslate(p);
  return frame;
}

template <Scalar S>
void DistanceJointT<S>::holdCurrentDistance() {
  this->getLock1D()->setPosition(this->getAngle());
  this->getLock1D()->setEnable(true);
}

SPOOK_COMPILED_ONCE(class, DistanceJointT)
SPOOK_COMPILED_DOUBLE(class Constraint1DOFT<double, detail::DistanceBetween>)
SPOOK_COMPILED_FLOAT(class Constraint1DOFT<float, detail::DistanceBetween>)
SPOOK_COMPILED_DOUBLE(class ElementaryJointT<double>)
SPOOK_COMPILED_FLOAT(class ElementaryJointT<float>)

using DistanceJoint = DistanceJointT<double>;
using DistanceJointRef = ref_ptr<DistanceJoint>;
namespace f32 {
using DistanceJoint = DistanceJointT<float>;
using DistanceJointRef = ref_ptr<DistanceJoint>;
}  // namespace f32

}  // namespace spook
