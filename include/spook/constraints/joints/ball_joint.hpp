#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// The frame origins held together, rotation free: one Spherical (seed 001 §12.4).
template <Scalar S>
class BallJointT : public ElementaryJointT<S, detail::Spherical> {
  using Base = ElementaryJointT<S, detail::Spherical>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, NUM_DOF };

  BallJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr)
      : Base("BallJoint", body1, frame1, body2, frame2) {}

 protected:
  ~BallJointT() override = default;
  void addRows(const detail::Attachments& a, detail::RowSink& sink, double) override { this->addElementaryRows(a, sink); }
};

using BallJoint = BallJointT<double>;
using BallJointRef = ref_ptr<BallJoint>;
namespace f32 {
using BallJoint = BallJointT<float>;
using BallJointRef = ref_ptr<BallJoint>;
}  // namespace f32

}  // namespace spook
