#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::makeBody;
using spook::test::pick;

namespace {

// A wheel on a horizontal hinge to the world (no gravity torque: the center
// of mass is on the axis).
template <class S>
struct Wheel {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> body;
  ref_ptr<HingeT<S>> hinge;
  explicit Wheel(S inertia = S(0.5)) {
    sim->setSolver(new DirectSolver());
    body = makeBody<S>(*sim, "wheel", S(4), Vec3T<S>::Zero(), inertia);
    hinge = new HingeT<S>(body.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
    hinge->setEnableComputeForces(true);
    sim->add(hinge);
  }
};
}  // namespace

TEST_CASE_TEMPLATE("a motor reaches its speed and a saturated motor delivers exactly its force range", S, float, double) {
  Wheel<S> w;
  auto* motor = w.hinge->getMotor1D();
  motor->setEnable(true);
  motor->setSpeed(S(3));
  motor->setForceRange(S(-2), S(2));
  // Saturated: I ω̇ = 2 N·m, so ω = 4 t until the speed is reached at 0.75 s.
  w.sim->stepTo(S(0.5));
  CHECK(std::abs(double(motor->getCurrentForce()) - 2.0) < pick<S>(1e-9, 1e-5));
  CHECK(std::abs(double(w.hinge->getCurrentSpeed()) - 4.0 * 0.5) < pick<S>(1e-9, 1e-4));
  w.sim->stepTo(S(2));
  MESSAGE("motor speed " << double(w.hinge->getCurrentSpeed()) << " rad/s, torque " << double(motor->getCurrentForce()));
  CHECK(std::abs(double(w.hinge->getCurrentSpeed()) - 3.0) < pick<S>(1e-6, 1e-4));
  CHECK(std::abs(double(motor->getCurrentForce())) < pick<S>(1e-6, 1e-3));
  // Winding: 2 s at up to 3 rad/s is more than a turn; the angle keeps counting.
  CHECK(double(w.hinge->getAngle()) > 2 * std::numbers::pi * 0.6);
}

TEST_CASE_TEMPLATE("a motor locked at zero speed holds its position against a load", S, float, double) {
  Wheel<S> w;
  auto* motor = w.hinge->getMotor1D();
  motor->setEnable(true);
  motor->setLockedAtZeroSpeed(true);
  motor->setSpeed(S(0));
  const S start = w.hinge->getAngle();
  for (int i = 0; i < 120; ++i) {
    w.body->addTorque(Vec3T<S>(S(5), 0, 0));
    w.sim->stepForward();
  }
  CHECK(std::abs(double(w.hinge->getAngle() - start)) < pick<S>(1e-6, 1e-5));
  CHECK(std::abs(double(motor->getCurrentForce()) + 5.0) < pick<S>(1e-4, 1e-3));
}

TEST_CASE_TEMPLATE("Lock1D holds a position, winding included", S, float, double) {
  Wheel<S> w;
  auto* lock = w.hinge->getLock1D();
  lock->setEnable(true);
  const S target = S(2.5 * std::numbers::pi);  // more than a turn: reached through winding
  lock->setPosition(target);
  lock->setCompliance(S(1e-6));
  // A slow relaxation (τ = 0.5 s): the angle must change by less than π per
  // step for the winding to follow it.
  lock->setDamping(S(0.5));
  w.sim->stepTo(S(10));
  MESSAGE("locked angle " << double(w.hinge->getAngle()) << " rad, target " << double(target));
  CHECK(std::abs(double(w.hinge->getAngle() - target)) < pick<S>(1e-6, 1e-4));
  CHECK(std::abs(double(w.hinge->getCurrentSpeed())) < pick<S>(1e-6, 1e-4));
}

TEST_CASE_TEMPLATE("Range1D stops a hinge pendulum at its limits", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  auto bob = makeBody<S>(*sim, "bob", S(1), Vec3T<S>(1, 0, 0));
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(bob.get(), frameAt<S>(Vec3T<S>(-1, 0, 0), Vec3T<S>::UnitY()).get());
  auto* range = hinge->getRange1D();
  range->setEnable(true);
  // Angle about +y: the bob falling from +x toward −z turns positively.
  range->setRange(S(-0.2), S(0.5));
  sim->add(hinge);
  double lowest = 0.0, highest = 0.0;
  for (int i = 0; i < 600; ++i) {
    sim->stepForward();
    lowest = std::min(lowest, double(hinge->getAngle()));
    highest = std::max(highest, double(hinge->getAngle()));
  }
  MESSAGE("hinge angle stayed in [" << lowest << ", " << highest << "] rad");
  CHECK(highest < 0.5 + pick<S>(1e-3, 2e-3));
  CHECK(highest > 0.5 - 1e-3);  // it did reach the stop
  CHECK(lowest > -0.2 - 1e-3);
  // At rest on the stop: the range holds the gravity torque m g L cos 0.5.
  CHECK(std::abs(double(range->getCurrentForce()) + spook::test::kG * std::cos(0.5)) < 1e-3 * spook::test::kG);
}

TEST_CASE_TEMPLATE("a prismatic motor lifts a load at its speed; getCurrentForce is the load", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(50);
  auto load = makeBody<S>(*sim, "load", m, Vec3T<S>::Zero());
  ref_ptr<PrismaticT<S>> prismatic = new PrismaticT<S>(load.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  auto* motor = prismatic->getMotor1D();
  motor->setEnable(true);
  motor->setSpeed(S(0.25));
  sim->add(prismatic);
  sim->stepTo(S(2));
  // The motor's compliance γ acts as a viscosity: it runs slow by γ·F (PHYSICS.md §1.3).
  const double slip = double(motor->getCompliance()) * double(m) * spook::test::kG;
  CHECK(std::abs(double(prismatic->getCurrentSpeed()) - (0.25 - slip)) < pick<S>(1e-9, 1e-5));
  CHECK(std::abs(double(motor->getCurrentForce()) / (double(m) * spook::test::kG) - 1.0) < pick<S>(1e-6, 1e-4));
}
