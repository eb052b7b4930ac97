#pragma once

#include <spook/constraints/joint.hpp>
#include <spook/constraints/secondary/screw_1d.hpp>

namespace spook {

/// Translation along and rotation about the z axis of the attachment frames,
/// the other four DOF removed by two Dot2 and two Dot1 rows (seed 001
/// §12.10). FIRST is the translation (m), SECOND the rotation (rad, with
/// winding); Screw1D couples them.
template <Scalar S>
class CylindricalJointT : public Constraint2DOFT<S, detail::TranslationalZ, detail::RotationalZ, detail::Dot2<0>,
                                                 detail::Dot2<1>, detail::Dot1<0, 2>, detail::Dot1<1, 2>> {
  using Base = Constraint2DOFT<S, detail::TranslationalZ, detail::RotationalZ, detail::Dot2<0>, detail::Dot2<1>,
                               detail::Dot1<0, 2>, detail::Dot1<1, 2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, ROTATIONAL_2, NUM_DOF };

  CylindricalJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr,
                    FrameT<S>* frame2 = nullptr)
      : Base("CylindricalJoint", body1, frame1, body2, frame2) {}

  [[nodiscard]] Screw1DT<S>* getScrew1D() const { return screw_.get(); }
  /// The screw's lead (m per revolution).
  void setLead(S lead) { screw_->setLead(lead); }

 protected:
  ~CylindricalJointT() override = default;
  void addCouplingRows(const detail::Coordinate& translation, const detail::Coordinate& angle,
                       detail::RowSink& sink) override;
  void afterCoupling(double h) override { screw_->endStep(h); }

 private:
  ref_ptr<Screw1DT<S>> screw_ = new Screw1DT<S>();
};

template <Scalar S>
void CylindricalJointT<S>::addCouplingRows(const detail::Coordinate& translation, const detail::Coordinate& angle,
                                           detail::RowSink& sink) {
  screw_->beginStep();
  screw_->addRows(sink, translation, angle);
}

SPOOK_COMPILED_ONCE(class, CylindricalJointT)
SPOOK_COMPILED_JOINT_BASE(Constraint2DOFT, detail::TranslationalZ, detail::RotationalZ, detail::Dot2<0>,
                          detail::Dot2<1>, detail::Dot1<0, 2>, detail::Dot1<1, 2>)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<0, 2>, detail::Dot1<1, 2>)

/// Translation within the xy plane of frame 2, rotation free: one Dot2 row.
template <Scalar S>
class PlaneJointT : public ElementaryJointT<S, detail::Dot2<2>> {
  using Base = ElementaryJointT<S, detail::Dot2<2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, NUM_DOF };

  PlaneJointT(RigidBodyT<S>* body1, FrameT<S>* frame1, RigidBodyT<S>* body2 = nullptr, FrameT<S>* frame2 = nullptr)
      : Base("PlaneJoint", body1, frame1, body2, frame2) {}

 protected:
  ~PlaneJointT() override = default;
  void addRows(const detail::Attachments& a, detail::RowSink& sink, double) override { this->addElementaryRows(a, sink); }
};

SPOOK_COMPILED_ONCE(class, PlaneJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<2>)

using CylindricalJoint = CylindricalJointT<double>;
using CylindricalJointRef = ref_ptr<CylindricalJoint>;
using PlaneJoint = PlaneJointT<double>;
using PlaneJointRef = ref_ptr<PlaneJoint>;
namespace f32 {
using CylindricalJoint = CylindricalJointT<float>;
using CylindricalJointRef = ref_ptr<CylindricalJoint>;
using PlaneJoint = PlaneJointT<float>;
using PlaneJointRef = ref_ptr<PlaneJoint>;
}  // namespace f32

}  // namespace spook
