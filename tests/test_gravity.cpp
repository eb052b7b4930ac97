#include <doctest/doctest.h>

#include <numbers>

#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

using spook::test::pick;

TEST_CASE_TEMPLATE("a point field attracts with the inverse square of the distance", S, float, double) {
  const S tol = pick<S>(1e-15, 1e-6);
  spook::ref_ptr<spook::PointGravityFieldT<S>> field =
      new spook::PointGravityFieldT<S>(spook::Vec3T<S>(S(1), S(0), S(0)), S(4));
  const spook::Vec3T<S> near = field->calculateGravity(spook::Vec3T<S>(S(3), S(0), S(0)));
  const spook::Vec3T<S> far = field->calculateGravity(spook::Vec3T<S>(S(1), S(4), S(0)));
  CHECK((near - spook::Vec3T<S>(S(-1), S(0), S(0))).norm() < tol);
  CHECK((far - spook::Vec3T<S>(S(0), S(-0.25), S(0))).norm() < tol);
  CHECK(field->calculateGravity(field->getCenter()) == spook::Vec3T<S>::Zero());
}

// Symplectic Euler keeps r × v exactly under a central force
// (x⁺ × v⁺ = x × v⁺ = x × (v + h a(x)) = x × v), and keeps a circular orbit
// bounded with a first-order error in radius and period.
TEST_CASE_TEMPLATE("a body in a point field orbits with constant angular momentum", S, float, double) {
  const S momentumTol = pick<S>(1e-12, 2e-5);
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  const S mu = S(1), radius = S(1), h = S(0.001);
  sim->setTimeStep(h);
  sim->setGravityField(new spook::PointGravityFieldT<S>(spook::Vec3T<S>::Zero(), mu));
  spook::ref_ptr<spook::RigidBodyT<S>> moon = new spook::RigidBodyT<S>("moon");
  moon->setPosition(spook::Vec3T<S>(radius, S(0), S(0)));
  moon->setVelocity(spook::Vec3T<S>(S(0), std::sqrt(mu / radius), S(0)));
  sim->add(moon);
  const spook::Vec3T<S> L0 = moon->getPosition().cross(moon->getVelocity());
  const S period = S(2 * std::numbers::pi) * std::sqrt(radius * radius * radius / mu);
  S rMin = radius, rMax = radius;
  const auto steps = static_cast<int>(std::lround(period / h));
  for (int i = 0; i < steps; ++i) {
    sim->stepForward();
    const S r = moon->getPosition().norm();
    rMin = std::min(rMin, r);
    rMax = std::max(rMax, r);
    CHECK((moon->getPosition().cross(moon->getVelocity()) - L0).norm() < momentumTol);
  }
  CHECK(rMax - rMin < S(4) * h * radius);
  // Back where it started after one period, to first order in h.
  CHECK((moon->getPosition() - spook::Vec3T<S>(radius, S(0), S(0))).norm() < S(10) * h * radius);
}

TEST_CASE_TEMPLATE("a uniform field can point anywhere", S, float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  const spook::Vec3T<S> g(S(1.5), S(0), S(-3.7));
  sim->setUniformGravity(g);
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("b");
  sim->add(body);
  sim->stepForward();
  CHECK((body->getVelocity() - g * sim->getTimeStep()).norm() < pick<S>(1e-15, 1e-7));
}
