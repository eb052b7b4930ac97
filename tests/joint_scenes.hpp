#pragma once

// Small scenes shared by the constraint tests.

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
