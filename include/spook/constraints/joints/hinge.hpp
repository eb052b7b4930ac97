#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// Rotation about the z axis of the attachment frames, the other five DOF
/// removed: a Spherical and two Dot1 rows (seed 001 §12.3). getAngle is the
/// angle of frame 1 about z of frame 2 (rad, with winding).
template <Scalar S>
class HingeT : public Constraint1DOFT<S, detail::RotationalZ, detail::Spherical, detail::Dot1<0, 2>, detail::Dot1<1, 2>> {
  using Base = Constraint1DOFT<S, detail::RotationalZ, detail::Spherical, detail::Dot1<0, 2>, detail::Dot1<1, 2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, TRANSLATIONAL_3, ROTATIONAL_1, ROTATIONAL_2, NUM_DOF };

  /// body2 == nullptr: hinged to the world. A missing frame2 is placed where
  /// frame1 is now.
  HingeT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr)
      : Base("Hinge", body1, frame1, body2, frame2) {}

 protected:
  ~HingeT() override = default;
};

SPOOK_COMPILED_ONCE(class, HingeT)
SPOOK_COMPILED_JOINT_BASE(Constraint1DOFT, detail::RotationalZ, detail::Spherical, detail::Dot1<0, 2>,
                          detail::Dot1<1, 2>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Spherical, detail::Dot1<0, 2>, detail::Dot1<1, 2>)

using Hinge = HingeT<double>;
using HingeRef = ref_ptr<Hinge>;
namespace f32 {
using Hinge = HingeT<float>;
using HingeRef = ref_ptr<Hinge>;
}  // namespace f32

}  // namespace spook
