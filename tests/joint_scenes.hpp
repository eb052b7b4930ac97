#pragma once

// Small scenes shared by the constraint tests.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <spook/constraints/joints/ball_joint.hpp>
#include <spook/constraints/joints/distance_joint.hpp>
#include <spook/constraints/joints/hinge.hpp>
#include <spook/constraints/joints/lock_joint.hpp>
#include <spook/constraints/joints/prismatic.hpp>
#include <spook/sim/simulation.hpp>

#include "policies.hpp"

namespace spook::test {

inline constexpr double kG = 9.80665;  // m/s², standard gravity (the simulation's default)

template <class S>
ref_ptr<RigidBodyT<S>> makeBody(SimulationT<S>& sim, const char* name, S mass, const Vec3T<S>& position,
                                S inertia = S(0)) {
  ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>(name);
  body->getMassProperties()->setMass(mass);
  const S I = inertia > S(0) ? inertia : S(0.4) * mass * S(0.01);
  body->getMassProperties()->setInertiaTensor(SPDMat3T<S>(Vec3T<S>(I, I, I)));
  body->setPosition(position);
  sim.add(body);
  return body;
}

/// A frame at `point` (in its parent) with z along `axis`.
template <class S>
ref_ptr<FrameT<S>> frameAt(const Vec3T<S>& point, const Vec3T<S>& axis = Vec3T<S>::UnitZ()) {
  ref_ptr<FrameT<S>> f = new FrameT<S>();
  f->setLocalTranslate(point);
  f->setLocalRotate(spook::rotate<S>(Vec3T<S>::UnitZ(), axis));
  return f;
}

/// A light body (1 kg, inertia 1) beside a heavy one (17 kg, inertia
/// diag(7.18, 0.225, 5.7)), the two spinning about different axes at about
/// 25·spin rad/s, no gravity, stepped at h: where a joint between them
/// turns by radians a step. `energy()` is their kinetic energy (J).
template <class S>
struct SpinningPair {
  using Vec3 = Vec3T<S>;
  const Vec3 inertia{S(7.18), S(0.225), S(5.7)};
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> heavy = new RigidBodyT<S>("heavy"), light = new RigidBodyT<S>("light");

  SpinningPair(double spin, double h) {
    sim->setTimeStep(S(h));
    sim->setUniformGravity(Vec3::Zero());
    heavy->getMassProperties()->setMass(S(17));
    heavy->getMassProperties()->setInertiaTensor(inertia);
    light->getMassProperties()->setMass(S(1));
    light->getMassProperties()->setInertiaTensor(Vec3(1, 1, 1));
    heavy->setPosition(Vec3(S(-1.26), S(0.314), S(-0.937)));
    light->setPosition(Vec3(S(-1.37), S(-0.511), S(-0.354)));
    heavy->setVelocity(Vec3(S(2.47), S(2.2), S(5.07)));
    heavy->setAngularVelocity(Vec3(S(1.88), S(-19.1), S(15.7)) * S(spin));
    light->setVelocity(Vec3(S(-4.71), S(-6.23), S(8.83)));
    light->setAngularVelocity(Vec3(S(-3.86), S(18.9), S(0.448)) * S(spin));
    sim->add(heavy);
    sim->add(light);
  }
  [[nodiscard]] double energy() const {
    const Vec3 w = heavy->getRotation().conjugate() * heavy->getAngularVelocity();
    return 0.5 * 17.0 * double(heavy->getVelocity().squaredNorm()) + 0.5 * double(w.cwiseProduct(w).dot(inertia)) +
           0.5 * double(light->getVelocity().squaredNorm()) + 0.5 * double(light->getAngularVelocity().squaredNorm());
  }
  /// The most kinetic energy over `steps` steps, as a share of the start's.
  double mostEnergyShare(int steps) {
    const double start = energy();
    double most = 0.0;
    for (int s = 0; s < steps; ++s) {
      sim->stepForward();
      most = std::max(most, energy() / start);
    }
    return most;
  }
};

/// Period of a compound pendulum released from rest at amplitude θ₀:
/// T = 4 √(I_p/(m g d)) K(sin(θ₀/2)) with K by the arithmetic–geometric mean
/// (PHYSICS.md §7.5).
inline double pendulumPeriod(double pivotInertia, double mass, double distance, double g, double theta0) {
  const double k = std::sin(theta0 / 2.0);
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = next;
  }
  return 4.0 * std::sqrt(pivotInertia / (mass * g * distance)) * std::numbers::pi / (2.0 * a);
}

}  // namespace spook::test
