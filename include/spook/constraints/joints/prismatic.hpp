#pragma once

#include <spook/constraints/joint.hpp>

namespace spook {

/// Translation along the z axis of the attachment frames, the other five DOF
/// removed: two Dot2 rows and a QuatLock (seed 001 §12.9). getAngle is the
/// position of frame 1 along z of frame 2 (m).
template <Scalar S>
class PrismaticT
    : public Constraint1DOFT<S, detail::TranslationalZ, detail::Dot2<0>, detail::Dot2<1>, detail::QuatLock> {
  using Base = Constraint1DOFT<S, detail::TranslationalZ, detail::Dot2<0>, detail::Dot2<1>, detail::QuatLock>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, ROTATIONAL_2, ROTATIONAL_3, NUM_DOF };

  PrismaticT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr)
      : Base("Prismatic", body1, frame1, body2, frame2) {}

 protected:
  ~PrismaticT() override = default;
};

SPOOK_COMPILED_ONCE(class, PrismaticT)
SPOOK_COMPILED_JOINT_BASE(Constraint1DOFT, detail::TranslationalZ, detail::Dot2<0>, detail::Dot2<1>, detail::QuatLock)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::QuatLock)

using Prismatic = PrismaticT<double>;
using PrismaticRef = ref_ptr<Prismatic>;
namespace f32 {
using Prismatic = PrismaticT<float>;
using PrismaticRef = ref_ptr<Prismatic>;
}  // namespace f32

}  // namespace spook
