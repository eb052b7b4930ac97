#pragma once

#include <spook/core/math.hpp>
#include <spook/dynamics/gravity_field.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/solver/free_rotation.hpp>

namespace spook::detail {

/// Advances one body over one step of the SPOOK stepper without
/// constraints: velocities first (symplectic Euler), then positions from the
/// new velocities.
template <Scalar S>
struct BodyIntegrator {
  using Vec3 = spook::Vec3<S>;
  using Quat = spook::Quat<S>;
  using Mat3 = spook::Mat3<S>;
  using Body = RigidBodyT<S>;

  /// Returns false when the new state would not be finite; the body is then
  /// frozen (velocities zeroed, pose kept) instead of spreading NaN.
  static bool step(Body& body, const GravityFieldT<S>& gravity, S h) {
    if (!body.enable_) return true;
    switch (body.motionControl_) {
      case Body::STATIC:
        return true;
      case Body::KINEMATICS:
        return stepKinematic(body, h);
      case Body::DYNAMICS:
        return stepDynamic(body, gravity, h);
    }
    return true;
  }

  static void clearForces(Body& body) { body.force_ = body.torque_ = Vec3::Zero(); }

 private:
  // v⁺ = (v + h(M⁻¹f + g)) / (1 + h d) per CM axis: the applied force sees the
  // inertial mass m(1 + c), gravity is an acceleration; damping is implicit.
  // Angular: Π = I Ω + h Rᵀτ (body frame), damped the same way, then the
  // momentum-conserving free rotation (free_rotation.hpp) moves the frame.
  static bool stepDynamic(Body& body, const GravityFieldT<S>& gravity, S h) {
    const MassPropertiesT<S>& mass = body.massProperties_;
    const Quat q = body.getCmRotation();
    const Mat3 R = q.toRotationMatrix();
    const Vec3 x = body.getCmPosition();

    const Vec3 damping = Vec3::Ones() + h * body.linearDamping_;
    const Vec3 acceleration =
        R * (R.transpose() * body.force_).cwiseQuotient(mass.getEffectiveMass()) + gravity.calculateGravity(x);
    const Vec3 v = R * (R.transpose() * (body.velocity_ + h * acceleration)).cwiseQuotient(damping);

    const Mat3& inertia = mass.getInertiaTensor();
    const Mat3 inertiaInverse = inertia.inverse();
    Vec3 omega =
        inertiaInverse * (inertia * (R.transpose() * body.angularVelocity_) + h * (R.transpose() * body.torque_));
    omega = omega.cwiseQuotient(Vec3::Ones() + h * body.angularDamping_);

    const Vec3 xNext = x + h * v;
    const FreeRotation<S> rotation = rotateFreely<S>(inertiaInverse, inertia * omega, h);
    const Quat qNext = (q * rotation.increment).normalized();
    const Vec3 omegaNext = qNext * (inertiaInverse * rotation.momentum);
    return commit(body, xNext, qNext, v, omegaNext);
  }

  // Kinematic bodies move with their velocities: x⁺ = x + h v, q⁺ = exp(h ω) q.
  // A moveTo re-aims the velocities at the target each step and lands on it
  // at the step boundary nearest to its end time (the half-step margin makes
  // that decision immune to round-off in the remaining time).
  static bool stepKinematic(Body& body, S h) {
    bool arriving = false;
    if (body.target_) {
      arriving = body.target_->remaining < S(1.5) * h;
      body.aimAtTarget(arriving ? h : body.target_->remaining);
      body.target_->remaining -= h;
    }
    const Vec3 xNext = body.getCmPosition() + h * body.velocity_;
    const Quat qNext = (expRotation<S>(h * body.angularVelocity_) * body.getCmRotation()).normalized();
    if (!commit(body, xNext, qNext, body.velocity_, body.angularVelocity_)) return false;
    if (arriving) {
      body.frame_->setMatrix(body.target_->pose);
      body.velocity_ = body.angularVelocity_ = Vec3::Zero();
      body.target_.reset();
    }
    return true;
  }

  // Writes the new center-of-mass state back through the model frame.
  static bool commit(Body& body, const Vec3& x, const Quat& q, const Vec3& v, const Vec3& omega) {
    if (!(x.allFinite() && q.coeffs().allFinite() && v.allFinite() && omega.allFinite())) {
      body.velocity_ = body.angularVelocity_ = Vec3::Zero();
      body.target_.reset();
      return false;
    }
    const Quat modelRotation = (q * body.cmFrame_->getLocalRotate().conjugate()).normalized();
    body.frame_->setRotate(modelRotation);
    body.frame_->setTranslate(x - modelRotation * body.getCmLocalTranslate());
    body.velocity_ = v;
    body.angularVelocity_ = omega;
    return true;
  }
};

}  // namespace spook::detail
