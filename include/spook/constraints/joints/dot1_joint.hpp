#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// Keeps the x axis of frame 1 perpendicular to the y axis of frame 2: a
/// single Dot1 row (seed 001 table 12.3), relaxed when the frames coincide.
/// Removes one rotational DOF; translation and the other two rotations are
/// free. It is the rotational row of a UniversalJoint (a UniversalJoint is a
/// BallJoint plus a Dot1Joint at the same frames).
template <Scalar S>
class Dot1JointT : public ElementaryJointT<S, detail::Dot1<0, 1>> {
  using Base = ElementaryJointT<S, detail::Dot1<0, 1>>;

 public:
  enum DOF { ALL_DOF = -1, ROTATIONAL_1 = 0, NUM_DOF };

  Dot1JointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr)
      : Base("Dot1Joint", body1, frame1, body2, frame2) {}

 protected:
  ~Dot1JointT() override = default;
  void addRows(const detail::Attachments& a, detail::RowSink& sink, double) override { this->addElementaryRows(a, sink); }
};

SPOOK_COMPILED_ONCE(class, Dot1JointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot1<0, 1>)

using Dot1Joint = Dot1JointT<double>;
using Dot1JointRef = ref_ptr<Dot1Joint>;
namespace f32 {
using Dot1Joint = Dot1JointT<float>;
using Dot1JointRef = ref_ptr<Dot1Joint>;
}  // namespace f32

}  // namespace spook
