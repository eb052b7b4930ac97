#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include <spook/constraints/joint.hpp>
#include <spook/core/cubic_spline.hpp>
#include <spook/core/implementation.hpp>
#include <spook/solver/spook_parameters.hpp>

namespace spook {

namespace detail {

/// The spline at the joint's tracked parameter, in world coordinates.
struct SplinePlace {
  Vec3d point = Vec3d::Zero();      ///< P(t) (m)
  Vec3d tangent = Vec3d::UnitZ();   ///< unit τ = dP/ds
  Vec3d normal = Vec3d::UnitX();    ///< unit reference across τ for the angle about it
  Vec3d curvature = Vec3d::Zero();  ///< κ = dτ/ds (1/m), zero beyond the ends
  double arcLength = 0.0;           ///< s(t) (m)
};

/// The attachments as SplineJoint's rows see them: frame 2 becomes the
/// tangent frame (x = n₁, y = n₂ across τ, z = τ) with its origin moved back
/// along τ by the arc length, P − sτ. Then Dot2<0>, Dot2<1> measure the
/// offset of frame 1's origin across the curve, Dot1<2,0>, Dot1<2,1> the tilt
/// of z₁ off the tangent, translationalCoordinate the arc length
/// s + (p₁ − P)·τ and rotationalCoordinate the angle about τ. The centers
/// and velocities stay those of the bodies.
SPOOK_INLINE Attachments alongSpline(const Attachments& a, const SplinePlace& place);

/// The tilt rows g = z₁·nₖ written by Dot1 treat nₖ as fixed in frame 2,
/// but nₖ follows the curve: carried without twist, dnₖ/ds = −(κ·nₖ)τ, so
/// ġ gains −(κ·nₖ)(z₁·τ) ṡ with ṡ = J_s v the rate of the arc length. This
/// adds that term to the two rows from `first` on, so that a body moving
/// along a curved spline is turned with the tangent to first order.
SPOOK_INLINE void addCurvatureCoupling(const Attachments& b, const Vec3d& curvature, std::vector<Row>& rows,
                                 std::size_t first);

/// The centripetal term of the rows across the curve. Frame 1's origin
/// moving along the tangent at arc rate ṡ for a step h ends ½h²Qₖ off the
/// curve, Qₖ = −(κ·nₖ)ṡ²: the row's second-order term κ = ½Qₖ (SecondOrder).
SPOOK_INLINE double centripetalCurvature(double curvatureAcross, double rate);

/// Without post-stabilization (second-order terms dropped), the same term goes
/// into the violation: following the curve takes Gv⁺ + ½hQₖ where a
/// straight row has Gv⁺, and SPOOK's right-hand side is −a g + b'Gv
/// (SpookParameters), so the shift is ½hQₖ/a (m). The curve is fixed, so
/// unlike the body-rotation terms of the other rows this feedforward does
/// not feed back.
SPOOK_INLINE double centripetalShift(const Row& row, double curvatureAcross, double rate, double h);

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Attachments alongSpline(const Attachments& a, const SplinePlace& place) {
  Attachments b = a;
  b.R2.col(0) = place.normal;
  b.R2.col(1) = place.tangent.cross(place.normal);
  b.R2.col(2) = place.tangent;
  b.q2 = Quatd(b.R2).normalized();
  b.p2 = place.point - place.arcLength * place.tangent;
  return b;
}

SPOOK_INLINE void addCurvatureCoupling(const Attachments& b, const Vec3d& curvature, std::vector<Row>& rows, std::size_t first) {
  const Coordinate along = translationalCoordinate(b);
  const double alignment = b.R1.col(2).dot(b.R2.col(2));
  for (std::size_t k = 0; k < 2; ++k) {
    const double rate = curvature.dot(b.R2.col(static_cast<Eigen::Index>(k))) * alignment;
    Row& row = rows[first + k];
    row.J1 -= rate * along.J1;
    row.J2 -= rate * along.J2;
  }
}

SPOOK_INLINE double centripetalCurvature(double curvatureAcross, double rate) {
  return -0.5 * curvatureAcross * rate * rate;
}

SPOOK_INLINE double centripetalShift(const Row& row, double curvatureAcross, double rate, double h) {
  const SpookParameters spook = SpookParameters::holonomic(row.compliance, row.damping, h);
  return spook.violationForSpeed(h * centripetalCurvature(curvatureAcross, rate));
}
#endif
}  // namespace detail

/// A body whose attachment frame slides along a cubic spline (seed 001
/// §12.11): the frame's origin stays on the curve and its z axis along the
/// curve's tangent, which leaves two DOFs. FIRST is the translation along the
/// spline, measured as arc length from the spline's first point (m); SECOND
/// is the rotation about the tangent (rad, with winding), zero at creation.
/// Each has a Motor1D, Lock1D, Range1D and FrictionController, as in
/// CylindricalJoint. The spline lives in the world, or in body 2's model
/// frame when a second body is given, and is shared, not copied: points
/// added later take effect.
///
/// Rows: two Dot2-like rows across the tangent at the tracked nearest point
/// P(t) (violation: the perpendicular offset of the frame origin; Jacobian:
/// the origin's velocity across the curve, which is exact to first order
/// because P moves along τ as t changes), and two Dot1-like rows keeping z
/// along τ, with the term that turns the tangent as the body moves along a
/// curved spline. The rows linearize the curve at P(t): moving along it
/// at arc rate ṡ for a step h leaves the body ½h²κṡ² off the curve, a
/// second-order drift that the step's linear prediction does not see. Left
/// to the violation it settles at (1 + 4τ/h)/4 times that (6.7 mm for 4.4
/// m/s on a 1 m radius at 60 Hz). So the rows across the curve carry that
/// centripetal term: as SecondOrder::curvature when the solver post-stabilizes them,
/// otherwise as a shift of their violation (detail::centripetalShift).
///
/// The tracked parameter t starts at the point of the curve nearest to the
/// frame origin and is updated each step from the previous one (see
/// CubicSplineT::findNearestParameter), so a body stays on its branch of a
/// curve that comes back near itself. Beyond the ends the curve continues
/// as its end tangent (use a Range1D on FIRST to stop the body). Create the
/// joint with the frame's z axis along the spline's direction (z·τ > 0).
template <Scalar S>
class SplineJointT : public ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<2, 0>, detail::Dot1<2, 1>> {
  using Base = ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<2, 0>, detail::Dot1<2, 1>>;

 public:
  using Body = RigidBodyT<S>;
  using Frame = FrameT<S>;
  using Spline = CubicSplineT<S>;

  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, ROTATIONAL_2, NUM_DOF };
  enum DOF_INDEX { FIRST = 0, SECOND = 1 };

  /// `frame` is the attachment frame on `body` (nullptr: its model frame);
  /// `spline` (at least two points) is in the world, or in `body2`'s model frame.
  SplineJointT(Body* body, Frame* frame, Spline* spline, Body* body2 = nullptr);

  [[nodiscard]] Spline* getSpline() const { return spline_.get(); }
  /// The tracked curve parameter t in [0, n − 1] (CubicSplineT), as of the last step.
  [[nodiscard]] S getParameter() const { return parameter_; }

  [[nodiscard]] Motor1DT<S>* getMotor1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.motor(); });
  }
  [[nodiscard]] Lock1DT<S>* getLock1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.lock(); });
  }
  [[nodiscard]] Range1DT<S>* getRange1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.range(); });
  }
  /// Internal friction of DOF `index` (seed 001 §12.15.4), with the joint's
  /// force across the tangent as normal force; disabled by default.
  [[nodiscard]] FrictionControllerT<S>* getFrictionController(int index) const {
    return visit(index, [](const auto& dof) { return dof.friction(); });
  }
  /// FIRST: arc length from the spline's first point (m); SECOND: angle about the tangent (rad, with winding).
  [[nodiscard]] S getAngle(int index) const;
  /// Rate of getAngle (m/s or rad/s).
  [[nodiscard]] S getCurrentSpeed(int index) const;

 protected:
  ~SplineJointT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override;
  void afterSolve(double h) override;
  /// The current pose becomes angle zero; the spline is not moved.
  void onRebind() override;
  [[nodiscard]] bool rebindsFrames() const override { return false; }

 private:
  static Body* checked(Body* body, const Frame* frame, const Spline* spline, const Body* body2);

  template <class F>
  auto visit(int index, F&& f) const {
    switch (index) {
      case FIRST: return f(slide_);
      case SECOND: return f(twist_);
      default: throw this->error("DOF index must be FIRST (0) or SECOND (1)", index);
    }
  }

  /// Frame 1's origin in the spline's frame (m).
  [[nodiscard]] static Vec3T<S> splinePoint(const detail::Attachments& a);

  /// The spline at parameter t in world coordinates, for frame 1 at a.p1.
  [[nodiscard]] detail::SplinePlace placeAt(const detail::Attachments& a, S t) const;

  /// Updates the tracked parameter from frame 1's pose, writes the four
  /// curve rows and returns the attachments along the spline. With a step
  /// h > 0 the rows across the curve get their centripetal term; with h = 0
  /// (post-stabilization) they are the plain rows.
  detail::Attachments writeCurveRows(const detail::Attachments& a, detail::RowSink& sink, double h);

  [[nodiscard]] detail::Attachments alongSplineNow() const;

  /// Angle zero at the current pose: the reference normal is turned about
  /// the tangent by the angle frame 1 has about it now.
  void restart(const detail::Attachments& a);

  ref_ptr<Spline> spline_;
  S parameter_ = S(0);
  double zeroAngle_ = 0.0;  // rad, turn of the reference normal about the tangent
  FreeDofT<S, detail::TranslationalZ> slide_;
  FreeDofT<S, detail::RotationalZ> twist_;
  detail::JointLoad load_;  // the normal force for the friction controllers
};

template <Scalar S>
SplineJointT<S>::SplineJointT(Body* body, Frame* frame, Spline* spline, Body* body2)
    : Base("SplineJoint", checked(body, frame, spline, body2), frame, body2, nullptr), spline_(spline) {
  this->getAttachmentFrame(1)->setLocalMatrix(TransformT<S>::Identity());
  const detail::Attachments a = this->attachments();
  parameter_ = spline_->findNearestParameter(splinePoint(a));
  restart(a);
  slide_.friction()->setJoint(this);
  twist_.friction()->setJoint(this);
}

template <Scalar S>
S SplineJointT<S>::getAngle(int index) const {
  const detail::Attachments b = alongSplineNow();
  return visit(index, [&](const auto& dof) { return S(dof.measure(b).value); });
}

template <Scalar S>
S SplineJointT<S>::getCurrentSpeed(int index) const {
  const detail::Attachments b = alongSplineNow();
  return visit(index, [&](const auto& dof) { return S(dof.measure(b).speed); });
}

template <Scalar S>
void SplineJointT<S>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  const std::size_t first = sink.rows->size();
  const detail::Attachments b = writeCurveRows(a, sink, h);
  load_.record(sink, first, b.R2.col(2));
  slide_.addRows(b, sink, h);
  twist_.addRows(b, sink, h);
}

template <Scalar S>
void SplineJointT<S>::addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) {
  const detail::Attachments b = writeCurveRows(a, sink, 0.0);
  slide_.addProjectionRows(b, sink);
  twist_.addProjectionRows(b, sink);
}

template <Scalar S>
void SplineJointT<S>::afterSolve(double h) {
  slide_.afterSolve(h);
  twist_.afterSolve(h);
  const double normal = load_.normal(load_.force(h));
  slide_.friction()->setStepNormalForce(normal);
  twist_.friction()->setStepNormalForce(normal);
}

template <Scalar S>
void SplineJointT<S>::onRebind() {
  const detail::Attachments a = this->attachments();
  parameter_ = spline_->findNearestParameter(splinePoint(a), parameter_);
  restart(a);
}

template <Scalar S>
auto SplineJointT<S>::checked(Body* body, const Frame* frame, const Spline* spline, const Body* body2) -> Body* {
  if (!spline) throw detail::makeError("SplineJoint", "", "needs a spline", "nullptr");
  if (spline->getNumPoints() < 2)
    throw detail::makeError("SplineJoint", "", "spline needs at least two points", spline->getNumPoints());
  if (!body) return body;  // reported by ConstraintT
  const TransformT<S> X1 = !frame ? body->getTransform()
                          : frame->getParent() ? frame->getMatrix()
                                               : TransformT<S>(body->getTransform() * frame->getLocalMatrix());
  if (!X1.matrix().allFinite())
    throw detail::makeError("SplineJoint", "", "attachment frame must be finite (m)", X1.translation());
  const TransformT<S> X2 = body2 ? body2->getTransform() : TransformT<S>::Identity();
  const S t = spline->findNearestParameter(X2.inverse() * X1.translation());
  const S alignment = X1.linear().col(2).dot(X2.linear() * spline->getUnitTangent(t));
  if (!(alignment > S(0)))
    throw detail::makeError("SplineJoint", "",
                            "frame z axis must point along the spline tangent at the nearest point (cosine > 0)",
                            alignment);
  return body;
}

template <Scalar S>
Vec3T<S> SplineJointT<S>::splinePoint(const detail::Attachments& a) {
  return (a.R2.transpose() * (a.p1 - a.p2)).template cast<S>();
}

template <Scalar S>
detail::SplinePlace SplineJointT<S>::placeAt(const detail::Attachments& a, S t) const {
  using detail::Vec3d;
  detail::SplinePlace place;
  const Vec3d d1 = a.R2 * spline_->getFirstDerivative(t).template cast<double>();
  const Vec3d d2 = a.R2 * spline_->getSecondDerivative(t).template cast<double>();
  place.point = a.p2 + a.R2 * spline_->getPosition(t).template cast<double>();
  place.tangent = (a.R2 * spline_->getUnitTangent(t).template cast<double>()).normalized();
  place.arcLength = double(spline_->getLength(t));
  const double along = (a.p1 - place.point).dot(place.tangent);
  const bool beyondEnd = (t <= S(0) && along < 0.0) || (t >= spline_->getMaxParameter() && along > 0.0);
  if (!beyondEnd && d1.squaredNorm() > 0.0)
    place.curvature = (d2 - d2.dot(place.tangent) * place.tangent) / d1.squaredNorm();
  const Vec3d reference = a.R2 * spline_->getNormal(t).template cast<double>();
  const Vec3d across = (reference - reference.dot(place.tangent) * place.tangent).normalized();
  place.normal = std::cos(zeroAngle_) * across + std::sin(zeroAngle_) * place.tangent.cross(across);
  return place;
}

template <Scalar S>
detail::Attachments SplineJointT<S>::writeCurveRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  parameter_ = spline_->findNearestParameter(splinePoint(a), parameter_);
  const detail::SplinePlace place = placeAt(a, parameter_);
  const detail::Attachments b = detail::alongSpline(a, place);
  const std::size_t first = sink.rows->size();
  this->addElementaryRows(b, sink);
  detail::addCurvatureCoupling(b, place.curvature, *sink.rows, first + 2);
  if (h > 0.0) {
    const double rate = detail::translationalCoordinate(b).speed;
    for (std::size_t k = 0; k < 2; ++k) {
      detail::Row& row = (*sink.rows)[first + k];
      const double across = place.curvature.dot(b.R2.col(static_cast<Eigen::Index>(k)));
      if (sink.secondOrder)
        sink.addCurvature(first + k, detail::centripetalCurvature(across, rate));
      else
        row.violation += detail::centripetalShift(row, across, rate, h);
    }
  }
  return b;
}

template <Scalar S>
detail::Attachments SplineJointT<S>::alongSplineNow() const {
  const detail::Attachments a = this->attachments();
  return detail::alongSpline(a, placeAt(a, spline_->findNearestParameter(splinePoint(a), parameter_)));
}

template <Scalar S>
void SplineJointT<S>::restart(const detail::Attachments& a) {
  zeroAngle_ = 0.0;
  zeroAngle_ = detail::rotationalCoordinate(detail::alongSpline(a, placeAt(a, parameter_))).value;
  const detail::Attachments b = detail::alongSpline(a, placeAt(a, parameter_));
  slide_.restart(b);
  twist_.restart(b);
}

SPOOK_COMPILED_ONCE(class, SplineJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<2, 0>, detail::Dot1<2, 1>)

using SplineJoint = SplineJointT<double>;
using SplineJointRef = ref_ptr<SplineJoint>;
namespace f32 {
using SplineJoint = SplineJointT<float>;
using SplineJointRef = ref_ptr<SplineJoint>;
}  // namespace f32

}  // namespace spook
