#include <doctest/doctest.h>

#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

// Relative distance |a − b| / max(1, |b|).
template <class S>
S relativeError(const spook::Vec3T<S>& a, const spook::Vec3T<S>& b) {
  return (a - b).norm() / std::max(S(1), b.norm());
}

}  // namespace

// The stepper is symplectic Euler: v⁺ = v + h g, x⁺ = x + h v⁺. After n steps
// vₙ = v₀ + n h g and xₙ = x₀ + n h v₀ + h² g n(n+1)/2 exactly.
TEST_CASE_TEMPLATE("free fall follows the exact discrete solution of the stepper", S, float, double) {
  const S tol = pick<S>(1e-12, 2e-6);
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  const S h = S(1) / S(60);
  sim->setTimeStep(h);
  spook::ref_ptr<spook::RigidBodyT<S>> ball = new spook::RigidBodyT<S>("ball");
  ball->getMassProperties()->setMass(S(2.5));
  const spook::Vec3T<S> x0(S(0.5), S(1), S(10)), v0(S(1), S(-2), S(3));
  ball->setPosition(x0);
  ball->setVelocity(v0);
  sim->add(ball);
  const spook::Vec3T<S> g(S(0), S(0), S(-9.80665));
  for (int n = 1; n <= 120; ++n) {
    sim->stepForward();
    const S k = S(n);
    CHECK(relativeError<S>(ball->getVelocity(), v0 + k * h * g) < tol);
    CHECK(relativeError<S>(ball->getPosition(), x0 + k * h * v0 + h * h * g * (k * (k + S(1)) / S(2))) < tol);
  }
}

// Against the parabola x(t) = x₀ + v₀t + g t²/2 the stepper is first order:
// xₙ − x(tₙ) = g h tₙ / 2 exactly, so the error halves with h.
TEST_CASE_TEMPLATE("a projectile deviates from the parabola by g h t / 2", S, float, double) {
  const S tol = pick<S>(1e-10, 1e-3);
  const spook::Vec3T<S> x0(S(0), S(0), S(0)), v0(S(12), S(0), S(9)), g(S(0), S(0), S(-9.80665));
  const S t = S(1.5);
  S previousError = S(0);
  for (int steps : {90, 180, 360}) {
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    const S h = t / S(steps);
    sim->setTimeStep(h);
    spook::ref_ptr<spook::RigidBodyT<S>> shot = new spook::RigidBodyT<S>("shot");
    shot->setVelocity(v0);
    sim->add(shot);
    sim->stepTo(t);
    CHECK(sim->getStatistics().numSteps == std::uint64_t(steps));
    const spook::Vec3T<S> exact = x0 + v0 * t + g * (t * t / S(2));
    const spook::Vec3T<S> error = shot->getPosition() - exact;
    CHECK(relativeError<S>(error, g * (h * t / S(2))) < tol);
    if (previousError > S(0)) CHECK(error.norm() / previousError == doctest::Approx(0.5).epsilon(pick<S>(1e-9, 1e-2)));
    previousError = error.norm();
  }
}

TEST_CASE_TEMPLATE("the center of mass of a spinning off-center body follows the parabola", S, float, double) {
  // float: the CM is rebuilt from the model frame each step (ε per step).
  const S tol = pick<S>(1e-12, 3e-5);
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  const S h = S(0.01);
  sim->setTimeStep(h);
  spook::ref_ptr<spook::RigidBodyT<S>> club = new spook::RigidBodyT<S>("club");
  club->getMassProperties()->setInertiaTensor(spook::Vec3T<S>(S(0.1), S(0.4), S(0.45)));
  club->setCmLocalTranslate(spook::Vec3T<S>(S(0.3), S(0), S(0)));
  const spook::Vec3T<S> c0 = club->getCmPosition(), v0(S(2), S(1), S(6));
  club->setVelocity(v0);
  club->setAngularVelocity(spook::Vec3T<S>(S(1), S(8), S(0.5)));
  sim->add(club);
  const spook::Vec3T<S> g(S(0), S(0), S(-9.80665));
  const int n = 100;
  for (int i = 0; i < n; ++i) sim->stepForward();
  const S k = S(n);
  CHECK(relativeError<S>(club->getCmPosition(), c0 + k * h * v0 + h * h * g * (k * (k + S(1)) / S(2))) < tol);
  // The model frame stays rigidly attached: the CM is 0.3 m from its origin.
  CHECK(std::abs((club->getCmPosition() - club->getPosition()).norm() - S(0.3)) < tol);
}

TEST_CASE_TEMPLATE("a constant force accelerates a body at F/m", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-6);
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setUniformGravity(spook::Vec3T<S>::Zero());
  const S h = sim->getTimeStep();
  spook::ref_ptr<spook::RigidBodyT<S>> cart = new spook::RigidBodyT<S>("cart");
  cart->getMassProperties()->setMass(S(4));
  sim->add(cart);
  const spook::Vec3T<S> force(S(8), S(-2), S(1));
  for (int i = 0; i < 60; ++i) {
    cart->addForce(force);
    sim->stepForward();
  }
  CHECK(relativeError<S>(cart->getVelocity(), force / S(4) * (S(60) * h)) < tol);
}
