#include <doctest/doctest.h>

#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

template <class S>
struct TumblingBody {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("tumbler");

  TumblingBody(const spook::Vec3T<S>& inertia, const spook::Vec3T<S>& omega, S h) {
    sim->setTimeStep(h);
    sim->setUniformGravity(spook::Vec3T<S>::Zero());
    body->getMassProperties()->setInertiaTensor(inertia);
    body->setAngularVelocity(omega);
    sim->add(body);
  }
};

}  // namespace

// A torque-free body spun near its intermediate principal axis flips over
// periodically (the Dzhanibekov effect) while angular momentum and kinetic
// energy stay constant.
TEST_CASE_TEMPLATE("a body spinning near its intermediate axis flips and conserves L and E", S, float, double) {
  // float: round-off of about ε per step over 1200 steps, ×10 margin.
  const S momentumTol = pick<S>(1e-9, 1e-3);
  const S energyTol = pick<S>(1e-6, 1e-3);
  TumblingBody<S> scene({S(1), S(2), S(3)}, {S(0.01), S(3), S(0.01)}, S(1) / S(60));
  spook::RigidBodyT<S>& body = *scene.body;
  const spook::Vec3T<S> L0 = body.getAngularMomentum();
  const S E0 = body.getKineticEnergy();
  S worstMomentum = 0, worstEnergyGain = 0;
  int flips = 0;
  S previous = (body.getRotation() * spook::Vec3T<S>::UnitY()).dot(L0);
  for (int i = 0; i < 20 * 60; ++i) {
    scene.sim->stepForward();
    worstMomentum = std::max(worstMomentum, (body.getAngularMomentum() - L0).norm() / L0.norm());
    worstEnergyGain = std::max(worstEnergyGain, (body.getKineticEnergy() - E0) / E0);
    const S alongL = (body.getRotation() * spook::Vec3T<S>::UnitY()).dot(L0);
    if (alongL * previous < S(0)) ++flips;
    previous = alongL;
  }
  MESSAGE("max |ΔL|/|L| = " << worstMomentum << ", max ΔE/E = " << worstEnergyGain << ", flips: " << flips);
  CHECK(worstMomentum < momentumTol);
  CHECK(worstEnergyGain < energyTol);
  CHECK(flips >= 2);
}

TEST_CASE_TEMPLATE("a spin about a principal axis turns by ω t exactly", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  const S h = S(0.02);
  TumblingBody<S> scene({S(1), S(2), S(3)}, {S(0), S(0), S(1.3)}, h);
  for (int i = 0; i < 100; ++i) scene.sim->stepForward();
  const spook::QuatT<S> expected(Eigen::AngleAxis<S>(S(1.3) * S(100) * h, spook::Vec3T<S>::UnitZ()));
  CHECK(std::abs(std::abs(scene.body->getRotation().dot(expected)) - S(1)) < tol);
  CHECK((scene.body->getAngularVelocity() - spook::Vec3T<S>(S(0), S(0), S(1.3))).norm() < tol);
}

TEST_CASE_TEMPLATE("a fast spin at a large step keeps L and does not gain energy", S, float, double) {
  const S tol = pick<S>(1e-9, 1e-3);
  // One radian per step about a skewed axis: the free-rotation solve substeps.
  TumblingBody<S> scene({S(0.5), S(2), S(6)}, {S(20), S(25), S(-15)}, S(1) / S(30));
  const spook::Vec3T<S> L0 = scene.body->getAngularMomentum();
  const S E0 = scene.body->getKineticEnergy();
  for (int i = 0; i < 300; ++i) {
    scene.sim->stepForward();
    CHECK((scene.body->getAngularMomentum() - L0).norm() / L0.norm() < tol);
    CHECK(scene.body->getKineticEnergy() <= E0 * (S(1) + tol));
  }
}

TEST_CASE_TEMPLATE("a constant torque changes the angular momentum by τ t", S, float, double) {
  const S tol = pick<S>(1e-12, 2e-5);
  TumblingBody<S> scene({S(1), S(2), S(3)}, {S(0.5), S(0), S(0)}, S(0.01));
  const spook::Vec3T<S> L0 = scene.body->getAngularMomentum();
  const spook::Vec3T<S> torque(S(0.2), S(-0.1), S(0.3));
  for (int i = 0; i < 200; ++i) {
    scene.body->addTorque(torque);
    scene.sim->stepForward();
  }
  const spook::Vec3T<S> expected = L0 + torque * S(2);
  CHECK((scene.body->getAngularMomentum() - expected).norm() / expected.norm() < tol);
}
