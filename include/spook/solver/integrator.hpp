#pragma once

#include <algorithm>
#include <cmath>

#include <spook/core/math.hpp>
#include <spook/dynamics/gravity_field.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/solver/free_rotation.hpp>
#include <spook/solver/island_problem.hpp>

namespace spook::detail {

/// Advances one body over one step of the SPOOK stepper in two halves around
/// the constraint solve: `prepare` computes the velocities the applied forces
/// alone would give (symplectic Euler), the solver adds the constraint
/// impulses, and `move` advances the pose with the final velocities.
template <Scalar S>
struct BodyIntegrator {
  using Vec3 = spook::Vec3T<S>;
  using Quat = spook::QuatT<S>;
  using Mat3 = spook::Mat3T<S>;
  using Body = RigidBodyT<S>;

  /// The body as the solver sees it. Dynamic bodies get their force-driven
  /// velocities v*; kinematic ones re-aim a moveTo; static, disabled and
  /// sleeping ones stand still with infinite mass.
  ///
  /// Velocity damping dv/dt = −D v is implicit, a force −h D̃ v⁺ on the end
  /// velocity, so it belongs in the mass: M(v⁺ − v) = h f − h D̃ v⁺ + Gᵀλ
  /// is M_d v⁺ = M v + h f + Gᵀλ with the damped mass M_d = M + h D̃, and
  /// the solver gets M_d⁻¹: v⁺ = v* + M_d⁻¹Gᵀλ with v* = M_d⁻¹(M v + h f).
  /// Damping then slows the body but does not scale the loads it carries: a
  /// damped body at rest still puts its whole weight on its contacts and
  /// joints. In the CM frame, with D = diag(dᵢ) (1/s) and D̃ = D^½ M D^½:
  ///   linear   M_d = diag(mᵢ(1 + cᵢ)(1 + h dᵢ)), i.e. vᵢ / (1 + h dᵢ) free;
  ///   angular  I_d = I + h D^½ I D^½, i.e. (I_d)ᵢⱼ = Iᵢⱼ(1 + h√(dᵢdⱼ)).
  /// I_d is symmetric positive definite; it is (1 + h d) I for isotropic
  /// damping and Iᵢ(1 + h dᵢ) on principal axes; its damping torque
  /// D^½ I D^½ Ω is positive semi-definite, so damping never adds energy.
  static SolverBody solverBody(Body& body, const GravityFieldT<S>& gravity, S h) {
    SolverBody b;
    if (!body.enable_ || body.motionControl_ == Body::STATIC || body.sleeping_) return b;
    if (body.motionControl_ == Body::KINEMATICS) {
      if (body.target_) {
        body.aimAtTarget(body.target_->remaining < S(1.5) * h ? h : body.target_->remaining);
        body.target_->remaining -= h;
      }
      b.velocity = b.freeVelocity = stack(body.velocity_, body.angularVelocity_);
      return b;
    }
    b.dynamic = true;
    b.velocity = stack(body.velocity_, body.angularVelocity_);
    const MassPropertiesT<S>& mass = body.massProperties_;
    const Mat3 R = body.getCmRotation().toRotationMatrix();
    // Linear, per CM axis: v* = (v + h(M⁻¹f + g)) / (1 + h d); the applied
    // force sees the inertial mass m(1 + c), gravity is an acceleration.
    const Vec3 damping = Vec3::Ones() + h * body.linearDamping_;
    const Vec3 acceleration = R * (R.transpose() * body.force_).cwiseQuotient(mass.getEffectiveMass()) +
                              gravity.calculateGravity(body.getCmPosition());
    const Vec3 v = R * (R.transpose() * (body.velocity_ + h * acceleration)).cwiseQuotient(damping);
    // Angular, CM frame: Ω* = I_d⁻¹ (I Ω + h Rᵀτ).
    const Mat3 dampedInertiaInverse = setDampedInverseMass(body, R, h, b);
    const Vec3 omega = dampedInertiaInverse * (mass.getInertiaTensor() * (R.transpose() * body.angularVelocity_) +
                                               h * (R.transpose() * body.torque_));
    b.freeVelocity = stack(v, R * omega);
    return b;
  }

  /// Advances the pose with the solved velocities v⁺ = (v, ω). Returns false
  /// when the new state would not be finite; the body is then frozen
  /// (velocities zeroed, pose kept) instead of spreading NaN.
  static bool move(Body& body, const SolverBody& solved, S h) {
    if (!body.enable_ || body.sleeping_) return true;
    switch (body.motionControl_) {
      case Body::STATIC:
        return true;
      case Body::KINEMATICS:
        return moveKinematic(body, h);
      case Body::DYNAMICS:
        return moveDynamic(body, solved, h);
    }
    return true;
  }

  static void clearForces(Body& body) { body.force_ = body.torque_ = Vec3::Zero(); }

  /// Freezes a body for this step: pose kept, velocities zeroed, a moveTo
  /// dropped.
  static void freeze(Body& body) {
    body.velocity_ = body.angularVelocity_ = Vec3::Zero();
    body.target_.reset();
  }

  /// Inverse damped mass and inertia (as in solverBody, for a step of h) at
  /// the current pose, and the current velocities (dynamic bodies; the
  /// others stand still with infinite mass). Post-stabilization distributes
  /// its corrections with the same mass as the step's impulses.
  static SolverBody massAndVelocity(const Body& body, S h) {
    SolverBody b;
    if (!body.enable_ || body.motionControl_ == Body::STATIC || body.sleeping_) return b;
    b.velocity = stack(body.velocity_, body.angularVelocity_);
    if (body.motionControl_ != Body::DYNAMICS) return b;
    b.dynamic = true;
    setDampedInverseMass(body, body.getCmRotation().toRotationMatrix(), h, b);
    return b;
  }

  /// R B Rᵀ in double and exactly symmetric. Formed in a float body's own
  /// precision it is symmetric only to ~1e-7, and where many rows share a
  /// body's few degrees of freedom (contacts fighting a joint) that
  /// asymmetry, larger than the rows' regularization, makes the solver's
  /// matrix G M⁻¹Gᵀ + Σ indefinite and the direct solve's pivoting cycle.
  static Mat3d toWorld(const Mat3& R, const Mat3& inBody) {
    const Mat3d Rd = R.template cast<double>();
    const Mat3d world = Rd * inBody.template cast<double>() * Rd.transpose();
    return 0.5 * (world + world.transpose());
  }

  /// Moves a body by a post-stabilization displacement: its center by Δx,
  /// its orientation by the rotation vector Δθ (world); the velocities take
  /// Δx/h and Δθ/h so that they stay consistent with the motion, as far as
  /// that adds no more than kProjectionEnergyShare of the body's kinetic
  /// energy. The projection removes the step's higher-order drift, whose
  /// velocity is tiny; where a large violation (contacts tearing a joint)
  /// makes the linearized projection overshoot, Δq/h would otherwise pump
  /// energy into the motion each step, and the chain diverges.
  static bool displace(Body& body, const SolverBody& b, S h) {
    if (!b.dynamic || b.displacement.isZero(0.0)) return true;
    const Vec3 dx = b.displacement.head<3>().template cast<S>();
    const Vec3 dtheta = b.displacement.tail<3>().template cast<S>();
    const Quat q = (expRotation<S>(dtheta) * body.getCmRotation()).normalized();
    const S share = S(energyBoundedShare(body, b.displacement / double(h)));
    return commit(body, body.getCmPosition() + dx, q, body.velocity_ + share * dx / h,
                  body.angularVelocity_ + share * dtheta / h);
  }
  /// The kinetic energy a projection's velocity change may add, as a share
  /// of the body's.
  static constexpr double kProjectionEnergyShare = 0.01;

 private:
  // Sets b's inverse damped mass M_d⁻¹ and inertia I_d⁻¹ (world; solverBody
  // has the forms) for the CM rotation R; returns I_d⁻¹ in the CM frame.
  static Mat3 setDampedInverseMass(const Body& body, const Mat3& R, S h, SolverBody& b) {
    const MassPropertiesT<S>& mass = body.massProperties_;
    const Vec3 dampedMass = mass.getEffectiveMass().cwiseProduct(Vec3::Ones() + h * body.linearDamping_);
    const Mat3& inertia = mass.getInertiaTensor();
    const Vec3 root = body.angularDamping_.cwiseSqrt();
    const Mat3 dampedInertiaInverse = Mat3(inertia + h * (root.asDiagonal() * inertia * root.asDiagonal())).inverse();
    b.inverseMass = toWorld(R, dampedMass.cwiseInverse().asDiagonal());
    b.inverseInertia = toWorld(R, dampedInertiaInverse);
    return dampedInertiaInverse;
  }

  // The largest s in [0, 1] with ΔE(s) = s vᵀMu + ½s² uᵀMu ≤ share·½vᵀMv
  // for the velocity change u (M: effective mass and world inertia).
  static double energyBoundedShare(const Body& body, const Vec6d& u) {
    const MassPropertiesT<S>& mass = body.massProperties_;
    const Mat3d R = body.getCmRotation().toRotationMatrix().template cast<double>();
    const Vec3d m = mass.getEffectiveMass().template cast<double>();
    const Mat3d I = mass.getInertiaTensor().template cast<double>();
    const Vec6d v = stack(body.velocity_, body.angularVelocity_);
    const auto dot = [&](const Vec6d& a, const Vec6d& c) {
      return (R.transpose() * a.head<3>()).cwiseProduct(m).dot(R.transpose() * c.head<3>()) +
             (R.transpose() * a.tail<3>()).dot(I * (R.transpose() * c.tail<3>()));
    };
    const double B = dot(v, u), C = dot(u, u), allowed = kProjectionEnergyShare * 0.5 * dot(v, v);
    if (B + 0.5 * C <= allowed) return 1.0;
    return std::clamp((-B + std::sqrt(B * B + 2.0 * C * allowed)) / C, 0.0, 1.0);
  }

  static Vec6d stack(const Vec3& v, const Vec3& w) {
    Vec6d out;
    out << v.template cast<double>(), w.template cast<double>();
    return out;
  }

  // x⁺ = x + h v⁺; the orientation by the momentum-conserving free rotation
  // (free_rotation.hpp) of Π = I Rᵀω⁺, which also gives the end ω.
  static bool moveDynamic(Body& body, const SolverBody& solved, S h) {
    const Vec3 v = solved.freeVelocity.head<3>().template cast<S>();
    const Vec3 omega = solved.freeVelocity.tail<3>().template cast<S>();
    const Quat q = body.getCmRotation();
    const Mat3 R = q.toRotationMatrix();
    const Mat3& inertia = body.massProperties_.getInertiaTensor();
    const Mat3 inertiaInverse = inertia.inverse();
    const Vec3 xNext = body.getCmPosition() + h * v;
    const FreeRotation<S> rotation = rotateFreely<S>(inertiaInverse, inertia * (R.transpose() * omega), h);
    const Quat qNext = (q * rotation.increment).normalized();
    const Vec3 omegaNext = qNext * (inertiaInverse * rotation.momentum);
    return commit(body, xNext, qNext, v, omegaNext);
  }

  // Kinematic bodies move with their velocities: x⁺ = x + h v, q⁺ = exp(h ω) q.
  // A moveTo (re-aimed in solverBody) lands on its target at the step
  // boundary nearest to its end time; the half-step margin makes that
  // decision immune to round-off in the remaining time.
  static bool moveKinematic(Body& body, S h) {
    const bool arriving = body.target_ && body.target_->remaining < S(0.5) * h;
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
  // A state that is not finite, or whose model frame would not be (a body
  // near the overflow limit, a quaternion that normalized to zero), freezes
  // the body instead of reaching the Frame, which would refuse it.
  static bool commit(Body& body, const Vec3& x, const Quat& q, const Vec3& v, const Vec3& omega) {
    const Quat modelRotation = (q * body.cmFrame_->getLocalRotate().conjugate()).normalized();
    const Vec3 modelTranslation = x - modelRotation * body.getCmLocalTranslate();
    const bool unitRotation = modelRotation.coeffs().allFinite() && std::abs(modelRotation.norm() - S(1)) < S(0.01);
    if (!(x.allFinite() && unitRotation && modelTranslation.allFinite() && v.allFinite() && omega.allFinite())) {
      freeze(body);
      return false;
    }
    body.frame_->setRotate(modelRotation);
    body.frame_->setTranslate(modelTranslation);
    body.velocity_ = v;
    body.angularVelocity_ = omega;
    return true;
  }
};

}  // namespace spook::detail
