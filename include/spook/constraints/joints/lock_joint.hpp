#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// All six DOF removed: a Spherical and a QuatLock (seed 001 §12.8).
template <Scalar S>
class LockJointT : public ElementaryJointT<S, detail::Spherical, detail::QuatLock> {
  using Base = ElementaryJointT<S, detail::Spherical, detail::QuatLock>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, ROTATIONAL_1, ROTATIONAL_2, ROTATIONAL_3, NUM_DOF };

  /// Locks body1 where it is (to body2, or to the world).
  explicit LockJointT(RigidBodyT<S>* body1, FrameT<S>* frame1 = nullptr, RigidBodyT<S>* body2 = nullptr,
                      FrameT<S>* frame2 = nullptr)
      : Base("LockJoint", body1, frame1, body2, frame2) {}

 protected:
  ~LockJointT() override = default;
  void addRows(const detail::Attachments& a, detail::RowSink& sink, double) override { this->addElementaryRows(a, sink); }
};

SPOOK_COMPILED_ONCE(class, LockJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Spherical, detail::QuatLock)

/// The three rotational DOF removed, translation free: a QuatLock.
template <Scalar S>
class AngularLockJointT : public ElementaryJointT<S, detail::QuatLock> {
  using Base = ElementaryJointT<S, detail::QuatLock>;

 public:
  enum DOF { ALL_DOF = -1, ROTATIONAL_1 = 0, ROTATIONAL_2, ROTATIONAL_3, NUM_DOF };

  explicit AngularLockJointT(RigidBodyT<S>* body1, FrameT<S>* frame1 = nullptr, RigidBodyT<S>* body2 = nullptr,
                             FrameT<S>* frame2 = nullptr)
      : Base("AngularLockJoint", body1, frame1, body2, frame2) {}

 protected:
  ~AngularLockJointT() override = default;
  void addRows(const detail::Attachments& a, detail::RowSink& sink, double) override { this->addElementaryRows(a, sink); }
};

SPOOK_COMPILED_ONCE(class, AngularLockJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::QuatLock)

using LockJoint = LockJointT<double>;
using LockJointRef = ref_ptr<LockJoint>;
using AngularLockJoint = AngularLockJointT<double>;
using AngularLockJointRef = ref_ptr<AngularLockJoint>;
namespace f32 {
using LockJoint = LockJointT<float>;
using LockJointRef = ref_ptr<LockJoint>;
using AngularLockJoint = AngularLockJointT<float>;
using AngularLockJointRef = ref_ptr<AngularLockJoint>;
}  // namespace f32

}  // namespace spook
