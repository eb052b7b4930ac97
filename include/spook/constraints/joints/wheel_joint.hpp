#pragma once

#include <cmath>
#include <string>
#include <type_traits>

#include <spook/constraints/joint.hpp>
#include <spook/core/implementation.hpp>

namespace spook {

namespace detail {

// The two free rotations of a wheel joint (seed 001 §12.12). The Dot1 row
// y₁·z₂ = 0 keeps the axle y₁ perpendicular to the steering axis z₂, so every
// admissible relative orientation is
//   Q = R₂ᵀ R₁ = R_z(s) R_y(w),
// the knuckle steered by s about z₂, then the wheel rolled by w about its
// axle. On that manifold ω₁ − ω₂ = ṡ z₂ + ẇ y₁ with y₁ ⊥ z₂, hence
// ṡ = z₂·(ω₁ − ω₂) and ẇ = y₁·(ω₁ − ω₂). From the closed form,
// Q e_y = (−sin s, cos s, 0) and the last row of Q is (−sin w, 0, cos w).

/// s: the steering angle, frame 1 about z₂ (rad).
struct WheelSteeringAngle {
  static Coordinate measure(const Attachments& a);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Coordinate WheelSteeringAngle::measure(const Attachments& a) {
  const Mat3d Q = a.R2.transpose() * a.R1;
  return angleAbout(a, std::atan2(-Q(0, 1), Q(1, 1)), a.R2.col(2));
}
#endif

/// w: the wheel's roll about its axle y₁ (rad).
struct WheelRollAngle {
  static Coordinate measure(const Attachments& a);
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE Coordinate WheelRollAngle::measure(const Attachments& a) {
  const Mat3d Q = a.R2.transpose() * a.R1;
  return angleAbout(a, std::atan2(-Q(2, 0), Q(2, 2)), a.R1.col(1));
}
#endif

}  // namespace detail

/// Where a wheel joint sits, in world coordinates (seed 001 §12.12): the
/// point where the wheel axle meets the steering (suspension) axis, the axle
/// direction and the steering direction. The two axes must be perpendicular:
/// |â·b̂| ≤ perpendicularTolerance() for the unit axes.
template <Scalar S>
class WheelJointFrameT {
 public:
  using Vec3 = spook::Vec3T<S>;

  /// |cos| of the angle between the axes accepted as perpendicular.
  static constexpr S perpendicularTolerance() { return std::is_same_v<S, float> ? S(1e-4) : S(1e-6); }

  /// `worldAttach` (m, world), `worldWheelAxle` and `worldSteeringAxle`
  /// (world directions, any non-zero length, perpendicular).
  WheelJointFrameT(const Vec3& worldAttach, const Vec3& worldWheelAxle, const Vec3& worldSteeringAxle);

  /// Intersection of the two axes (m, world).
  [[nodiscard]] const Vec3& getWorldAttach() const { return attach_; }
  /// Unit wheel axle (world).
  [[nodiscard]] const Vec3& getWorldWheelAxle() const { return wheel_; }
  /// Unit steering and suspension axis (world).
  [[nodiscard]] const Vec3& getWorldSteeringAxle() const { return steering_; }

  /// The joint frame in world: origin at the attachment point, y along the
  /// axle made exactly perpendicular to z, z along the steering axis.
  [[nodiscard]] TransformT<S> getWorldTransform() const;

 private:
  template <class T>
  static Error error(const std::string& what, const T& value) {
    return detail::makeError("WheelJointFrame", "", what, value);
  }
  static void checkAxis(const char* what, const Vec3& axis);

  Vec3 attach_, wheel_, steering_;
};

template <Scalar S>
WheelJointFrameT<S>::WheelJointFrameT(const Vec3& worldAttach, const Vec3& worldWheelAxle,
                                      const Vec3& worldSteeringAxle) {
  if (!worldAttach.allFinite()) throw error("attachment point must be finite (m)", worldAttach);
  checkAxis("wheel axle must be finite and non-zero", worldWheelAxle);
  checkAxis("steering axle must be finite and non-zero", worldSteeringAxle);
  const Vec3 wheel = worldWheelAxle.normalized(), steering = worldSteeringAxle.normalized();
  const S cosine = wheel.dot(steering);
  if (!(std::abs(cosine) <= perpendicularTolerance()))
    throw error(std::is_same_v<S, float> ? "wheel axle and steering axle must be perpendicular (|cos| <= 1e-4)"
                                         : "wheel axle and steering axle must be perpendicular (|cos| <= 1e-6)",
                cosine);
  attach_ = worldAttach;
  wheel_ = wheel;
  steering_ = steering;
}

template <Scalar S>
TransformT<S> WheelJointFrameT<S>::getWorldTransform() const {
  const Vec3 z = steering_;
  const Vec3 y = (wheel_ - wheel_.dot(z) * z).normalized();
  Mat3T<S> R;
  R.col(0) = y.cross(z);
  R.col(1) = y;
  R.col(2) = z;
  TransformT<S> X = TransformT<S>::Identity();
  X.linear() = R;
  X.translation() = attach_;
  return X;
}

template <Scalar S>
void WheelJointFrameT<S>::checkAxis(const char* what, const Vec3& axis) {
  if (!axis.allFinite() || !(axis.norm() > S(0))) throw error(what, axis);
}

SPOOK_COMPILED_ONCE(class, WheelJointFrameT)

/// A wheel on a chassis or on the world (seed 001 §12.12). The wheel is body
/// 1; the chassis is body 2 (nullptr: the world). The y axis of frame 1 is
/// the wheel axle; the z axis of frame 2 is the suspension and steering axis.
/// Constrained: frame 1's origin on the z₂ axis (two Dot2 rows,
/// TRANSLATIONAL_1 and _2) and the axle perpendicular to the steering axis
/// (one Dot1 row, ROTATIONAL_1). Free, each with a Motor1D, Lock1D, Range1D
/// and FrictionController:
/// - WHEEL, the roll about the axle (rad, with winding);
/// - STEERING, the rotation about z₂ (rad, with winding);
/// - SUSPENSION, the position of frame 1's origin along z₂ (m).
/// The SUSPENSION Lock1D is enabled at creation, holding the initial
/// position; disable it (and use its Range1D, or a compliant lock as a
/// spring) for a travelling suspension. The friction controllers take as
/// normal force the joint's force across z₂.
template <Scalar S>
class WheelJointT : public ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<1, 2>> {
  using Base = ElementaryJointT<S, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<1, 2>>;

 public:
  enum DOF { ALL_DOF = -1, TRANSLATIONAL_1 = 0, TRANSLATIONAL_2, ROTATIONAL_1, NUM_DOF };
  /// The free DOFs, for getMotor1D, getLock1D, getRange1D, getAngle.
  enum SecondaryConstraint { WHEEL = 0, STEERING = 1, SUSPENSION = 2 };

  /// Frames in the bodies' model frames (frame 2 in world for chassis ==
  /// nullptr); frame 2 defaults to frame 1's current pose.
  WheelJointT(RigidBodyT<S>* wheel, FrameT<S>* wheelFrame, RigidBodyT<S>* chassis = nullptr,
              FrameT<S>* chassisFrame = nullptr);
  /// Frames from a world description, relaxed in the current configuration.
  WheelJointT(const WheelJointFrameT<S>& frame, RigidBodyT<S>* wheel, RigidBodyT<S>* chassis = nullptr);

  [[nodiscard]] Motor1DT<S>* getMotor1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.motor(); });
  }
  [[nodiscard]] Lock1DT<S>* getLock1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.lock(); });
  }
  [[nodiscard]] Range1DT<S>* getRange1D(int index) const {
    return visit(index, [](const auto& dof) { return dof.range(); });
  }
  /// Internal friction of a free DOF (seed 001 §12.15.4); disabled by default.
  [[nodiscard]] FrictionControllerT<S>* getFrictionController(int index) const {
    return visit(index, [](const auto& dof) { return dof.friction(); });
  }
  /// The free DOF's current value: rad (with winding) for WHEEL and STEERING,
  /// m for SUSPENSION.
  [[nodiscard]] S getAngle(int index) const;
  /// Its rate (rad/s or m/s).
  [[nodiscard]] S getCurrentSpeed(int index) const;

  /// The steering axis z₂ (unit, world).
  [[nodiscard]] Vec3T<S> getWorldSteeringAxis() const;
  /// Frame 2's origin, the steering pivot on the chassis (m, world).
  [[nodiscard]] Vec3T<S> getWorldSteeringPivot() const;

 protected:
  ~WheelJointT() override = default;

  void addRows(const detail::Attachments& a, detail::RowSink& sink, double h) override;
  void addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) override;
  void afterSolve(double h) override;
  void onRebind() override { restart(); }

 private:
  static ref_ptr<FrameT<S>> localFrame(const WheelJointFrameT<S>& frame, const RigidBodyT<S>* body);

  template <class F>
  auto visit(int index, F&& f) const {
    switch (index) {
      case WHEEL:
        return f(wheel_);
      case STEERING:
        return f(steering_);
      case SUSPENSION:
        return f(suspension_);
      default:
        throw this->error("free DOF index must be WHEEL (0), STEERING (1) or SUSPENSION (2)", index);
    }
  }
  void restart();
  void initialize();

  FreeDofT<S, detail::WheelRollAngle> wheel_;
  FreeDofT<S, detail::WheelSteeringAngle> steering_;
  FreeDofT<S, detail::TranslationalZ> suspension_;
  detail::JointLoad load_;  // the normal force for the friction controllers
};

template <Scalar S>
WheelJointT<S>::WheelJointT(RigidBodyT<S>* wheel, FrameT<S>* wheelFrame, RigidBodyT<S>* chassis,
                            FrameT<S>* chassisFrame)
    : Base("WheelJoint", wheel, wheelFrame, chassis, chassisFrame) {
  initialize();
}

template <Scalar S>
WheelJointT<S>::WheelJointT(const WheelJointFrameT<S>& frame, RigidBodyT<S>* wheel, RigidBodyT<S>* chassis)
    : Base("WheelJoint", wheel, localFrame(frame, wheel).get(), chassis, localFrame(frame, chassis).get()) {
  initialize();
}

template <Scalar S>
S WheelJointT<S>::getAngle(int index) const {
  const auto a = this->attachments();
  return visit(index, [&](const auto& dof) { return S(dof.measure(a).value); });
}

template <Scalar S>
S WheelJointT<S>::getCurrentSpeed(int index) const {
  const auto a = this->attachments();
  return visit(index, [&](const auto& dof) { return S(dof.measure(a).speed); });
}

template <Scalar S>
Vec3T<S> WheelJointT<S>::getWorldSteeringAxis() const {
  return Vec3T<S>(this->attachments().R2.col(2).template cast<S>());
}

template <Scalar S>
Vec3T<S> WheelJointT<S>::getWorldSteeringPivot() const {
  return Vec3T<S>(this->attachments().p2.template cast<S>());
}

template <Scalar S>
void WheelJointT<S>::addRows(const detail::Attachments& a, detail::RowSink& sink, double h) {
  const std::size_t first = sink.rows->size();
  this->addElementaryRows(a, sink);
  load_.record(sink, first, a.R2.col(2));
  wheel_.addRows(a, sink, h);
  steering_.addRows(a, sink, h);
  suspension_.addRows(a, sink, h);
}

template <Scalar S>
void WheelJointT<S>::addProjectionRows(const detail::Attachments& a, detail::RowSink& sink) {
  this->addElementaryRows(a, sink);
  wheel_.addProjectionRows(a, sink);
  steering_.addProjectionRows(a, sink);
  suspension_.addProjectionRows(a, sink);
}

template <Scalar S>
void WheelJointT<S>::afterSolve(double h) {
  wheel_.afterSolve(h);
  steering_.afterSolve(h);
  suspension_.afterSolve(h);
  const double normal = load_.normal(load_.force(h));
  wheel_.friction()->setStepNormalForce(normal);
  steering_.friction()->setStepNormalForce(normal);
  suspension_.friction()->setStepNormalForce(normal);
}

template <Scalar S>
ref_ptr<FrameT<S>> WheelJointT<S>::localFrame(const WheelJointFrameT<S>& frame, const RigidBodyT<S>* body) {
  const TransformT<S> world = frame.getWorldTransform();
  return new FrameT<S>(body ? TransformT<S>(body->getTransform().inverse() * world) : world);
}

template <Scalar S>
void WheelJointT<S>::restart() {
  const auto a = this->attachments();
  wheel_.restart(a);
  steering_.restart(a);
  suspension_.restart(a);
}

template <Scalar S>
void WheelJointT<S>::initialize() {
  restart();
  wheel_.friction()->setJoint(this);
  steering_.friction()->setJoint(this);
  suspension_.friction()->setJoint(this);
  suspension_.lock()->setPosition(S(suspension_.measure(this->attachments()).value));
  suspension_.lock()->setEnable(true);
}

SPOOK_COMPILED_ONCE(class, WheelJointT)
SPOOK_COMPILED_JOINT_BASE(ElementaryJointT, detail::Dot2<0>, detail::Dot2<1>, detail::Dot1<1, 2>)

using WheelJointFrame = WheelJointFrameT<double>;
using WheelJoint = WheelJointT<double>;
using WheelJointRef = ref_ptr<WheelJoint>;
namespace f32 {
using WheelJointFrame = WheelJointFrameT<float>;
using WheelJoint = WheelJointT<float>;
using WheelJointRef = ref_ptr<WheelJoint>;
}  // namespace f32

}  // namespace spook
