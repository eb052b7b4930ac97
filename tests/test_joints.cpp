#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <spook/constraints/joints/cylindrical_joint.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::makeBody;
using spook::test::pick;

// A hinge pendulum released at 90° swings with the exact large-amplitude
// period T = 4√(I_p/(m g L)) K(sin 45°) (PHYSICS.md §7.5). Symplectic Euler
// with SPOOK rows at h = 1/240 s keeps the period within 0.5%; measured by
// the times the bob crosses the bottom, linearly interpolated.
TEST_CASE_TEMPLATE("a hinge pendulum released at 90 degrees has the exact large-amplitude period", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  sim->setTimeStep(S(1) / S(240));
  const S L = S(1), m = S(2), Icm = S(0.01);
  auto bob = makeBody<S>(*sim, "bob", m, Vec3T<S>(L, 0, 0), Icm);
  // Pivot at the origin, axis along world y: frame 1 sits at the pivot, in bob coordinates.
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(bob.get(), frameAt<S>(Vec3T<S>(-L, 0, 0), Vec3T<S>::UnitY()).get());
  sim->add(hinge);

  std::vector<double> crossings;
  double prevX = double(bob->getPosition().x());
  double prevT = 0.0;
  while (crossings.size() < 5 && sim->getTimeStamp() < S(20)) {
    sim->stepForward();
    const double x = double(bob->getPosition().x());
    const double t = double(sim->getTimeStamp());
    if ((prevX > 0) != (x > 0)) crossings.push_back(prevT + (t - prevT) * prevX / (prevX - x));
    prevX = x;
    prevT = t;
  }
  REQUIRE(crossings.size() == 5);
  const double period = (crossings[4] - crossings[0]) / 2.0;
  const double expected = spook::test::pendulumPeriod(double(Icm + m * L * L), double(m), double(L), spook::test::kG, std::numbers::pi / 2);
  MESSAGE("pendulum period " << period << " s, exact " << expected << " s");
  CHECK(std::abs(period / expected - 1.0) < 0.005);
  // The bob stays on its circle up to SPOOK's drift: each step moves the
  // attachment off by ½h²ω²L (the centripetal term the velocity-level row
  // does not see) and the stabilization removes 4/(1+4τ/h) of the violation,
  // so it settles at (1+4τ/h)h²ω²L/8 ≈ 1.4e-3 m with ω² ≈ 2g/L at the bottom.
  const double h = 1.0 / 240.0, d = (2.0 / 60.0) / h;
  const double drift = (1.0 + 4.0 * d) * h * h * (2.0 * spook::test::kG) * double(L) / 8.0;
  CHECK(std::abs(double(bob->getPosition().norm()) - double(L)) < 1.2 * drift);
}

// A body on a prismatic whose axis is tilted 30° from horizontal slides down
// it at g·sin 30° (x = ½ a t²), whatever the constraint's stiffness.
TEST_CASE_TEMPLATE("a prismatic on a 30 degree axis accelerates at g sin 30", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S angle = S(std::numbers::pi / 6);
  const Vec3T<S> axis(std::cos(angle), S(0), std::sin(angle));
  auto slider = makeBody<S>(*sim, "slider", S(3), Vec3T<S>::Zero());
  ref_ptr<PrismaticT<S>> prismatic = new PrismaticT<S>(slider.get(), frameAt<S>(Vec3T<S>::Zero(), axis).get());
  sim->add(prismatic);
  sim->stepTo(S(2));
  const double t = double(sim->getTimeStamp());
  const double a = spook::test::kG * 0.5;
  const double expected = -0.5 * a * t * t;
  MESSAGE("prismatic position " << double(prismatic->getAngle()) << " m, exact " << expected << " m");
  // Symplectic Euler: x_n = −a h² n(n+1)/2, off by a·h·t/2 from ½at².
  const double h = double(sim->getTimeStep());
  CHECK(std::abs(double(prismatic->getAngle()) - (expected - 0.5 * a * h * t)) < pick<S>(1e-7, 1e-4));
  CHECK(std::abs(double(prismatic->getCurrentSpeed()) + a * t) / (a * t) < 1e-2);
  // The free DOF moved only along the axis.
  CHECK((slider->getPosition() - axis * prismatic->getAngle()).norm() < pick<S>(1e-6, 1e-4));
}

// Hooke's law (seed 001 §12.1.3): at rest a row deflects load × compliance.
TEST_CASE_TEMPLATE("a lock joint deflects load times compliance, in meters", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(10), c = S(1e-4);
  auto body = makeBody<S>(*sim, "weight", m, Vec3T<S>::Zero());
  ref_ptr<LockJointT<S>> lock = new LockJointT<S>(body.get());
  lock->setCompliance(c, LockJointT<S>::TRANSLATIONAL_3);
  sim->add(lock);
  sim->stepTo(S(3));
  const double expected = -double(m) * spook::test::kG * double(c);
  MESSAGE("deflection " << double(body->getPosition().z()) << " m, Hooke " << expected << " m");
  CHECK(std::abs(double(body->getPosition().z()) / expected - 1.0) < 0.01);
}

// A torque τ on a body held by a LockJoint whose rotational compliance is c:
// without linearization the QuatLock rows hold sin θ/c, so θ = asin(τ c);
// with it, θ = τ c (Hooke's law in radians).
TEST_CASE_TEMPLATE("a lock joint twists load times compliance in radians with linearization", S, float, double) {
  for (bool linearize : {false, true}) {
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    sim->setSolver(new DirectSolver());
    sim->setUniformGravity(Vec3T<S>::Zero());
    const S c = S(1e-2), torque = S(80);  // τc = 0.8 rad
    auto body = makeBody<S>(*sim, "wheel", S(1), Vec3T<S>::Zero(), S(0.1));
    ref_ptr<LockJointT<S>> lock = new LockJointT<S>(body.get());
    for (int dof : {3, 4, 5}) lock->setCompliance(c, dof);
    lock->setEnableLinearization(linearize);
    sim->add(lock);
    for (int i = 0; i < 600; ++i) {
      body->addTorque(Vec3T<S>(0, 0, torque));
      sim->stepForward();
    }
    const double angle = double(toEulerAngles<S>(body->getRotation()).z);
    const double hooke = double(torque * c);
    MESSAGE(std::string(linearize ? "linearized" : "plain") << " twist " << angle << " rad, Hooke " << hooke << " rad");
    if (linearize)
      CHECK(std::abs(angle / hooke - 1.0) < 0.01);
    else
      CHECK(std::abs(angle - std::asin(hooke)) < 0.01 * hooke);
  }
}

// The lock's force on a hanging body equals its weight (direct solver).
TEST_CASE_TEMPLATE("getLastForce of a hanging body equals its weight", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(7.5);
  auto body = makeBody<S>(*sim, "hanging", m, Vec3T<S>(0, 0, -1));
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(body.get(), frameAt<S>(Vec3T<S>(0, 0, 1)).get());
  hinge->setEnableComputeForces(true);
  sim->add(hinge);
  sim->stepTo(S(5));
  Vec3T<S> force = Vec3T<S>::Zero(), torque = Vec3T<S>::Zero();
  REQUIRE(hinge->getLastForce(body.get(), force, torque));
  const double weight = double(m) * spook::test::kG;
  MESSAGE("lock force " << force.transpose() << " N, weight " << weight << " N");
  CHECK(std::abs(double(force.z()) / weight - 1.0) < pick<S>(1e-6, 1e-5));
  CHECK(std::hypot(double(force.x()), double(force.y())) < pick<S>(1e-9, 1e-4) * weight);
  CHECK(double(torque.norm()) < pick<S>(1e-8, 1e-4) * weight);
  // About the attachment origin, 2 m above the center: the same, as the force is vertical.
  Vec3T<S> forceAtFrame = Vec3T<S>::Zero(), torqueAtFrame = Vec3T<S>::Zero();
  REQUIRE(hinge->getLastForce(0, forceAtFrame, torqueAtFrame, false));
  CHECK(double(torqueAtFrame.norm()) < pick<S>(1e-7, 1e-3) * weight);
  // Off: nothing kept.
  hinge->setEnableComputeForces(false);
  CHECK_FALSE(hinge->getLastForce(body.get(), force, torque));
}

// A horizontal beam of mass m and length L locked to the world at its left
// end (seed 000: getLastForce(rb, force, torque, giveForceAtCm = false)). At
// rest the lock carries the weight, F = (0, 0, m g); about the attachment
// point, the body's end at c − (L/2) x, the torque that balances gravity's
// lever is (L/2 x) × F = (0, −m g L/2, 0): the default. About the center of
// mass (giveForceAtCm true) the lock's wrench balances a force through the
// center: zero torque.
TEST_CASE_TEMPLATE("getLastForce reports the torque about the attachment point unless asked for the center of mass", S,
                   float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(4), L = S(2);
  auto beam = makeBody<S>(*sim, "beam", m, Vec3T<S>(S(3), S(0), S(1)), S(m * L * L / 12));
  ref_ptr<LockJointT<S>> lock = new LockJointT<S>(beam.get(), frameAt<S>(Vec3T<S>(-L / 2, 0, 0)).get());
  lock->setEnableComputeForces(true);
  sim->add(lock);
  sim->stepTo(S(2));
  const double weight = double(m) * spook::test::kG, moment = weight * double(L) / 2;
  Vec3T<S> force = Vec3T<S>::Zero(), torque = Vec3T<S>::Zero();
  REQUIRE(lock->getLastForce(beam.get(), force, torque));
  MESSAGE("force " << force.transpose() << " N, torque " << torque.transpose() << " N m; m g = " << weight
                   << " N, m g L/2 = " << moment << " N m");
  CHECK(std::abs(double(force.z()) / weight - 1.0) < pick<S>(1e-6, 1e-4));
  CHECK(std::hypot(double(force.x()), double(force.y())) < pick<S>(1e-9, 1e-4) * weight);
  CHECK(std::abs(double(torque.y()) / -moment - 1.0) < pick<S>(1e-6, 1e-4));
  CHECK(std::hypot(double(torque.x()), double(torque.z())) < pick<S>(1e-9, 1e-4) * moment);
  // The same by index; about the center of mass on request.
  Vec3T<S> byIndex = Vec3T<S>::Zero(), torqueByIndex = Vec3T<S>::Zero();
  REQUIRE(lock->getLastForce(0, byIndex, torqueByIndex));
  CHECK(double((torqueByIndex - torque).norm()) <= pick<S>(1e-12, 1e-6) * moment);
  Vec3T<S> atCm = Vec3T<S>::Zero(), torqueAtCm = Vec3T<S>::Zero();
  REQUIRE(lock->getLastForce(beam.get(), atCm, torqueAtCm, true));
  MESSAGE("torque about the center of mass " << torqueAtCm.transpose() << " N m");
  CHECK(double((atCm - force).norm()) <= pick<S>(1e-12, 1e-6) * weight);
  CHECK(double(torqueAtCm.norm()) < pick<S>(1e-6, 1e-4) * moment);
}

// A mass m hanging 1 m below a world point on a DistanceJoint of compliance
// c set on the joint (seed 001 §12.1.2, §12.7: one translational DOF) stretches
// by Hooke's law d = m g c (§12.1.3); the joint's damping is that DOF's too.
TEST_CASE_TEMPLATE("a DistanceJoint has one DOF, and its compliance stretches a hanging mass by m g c", S, float,
                   double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(10), c = S(1e-4), damping = S(0.05);
  auto body = makeBody<S>(*sim, "hanging", m, Vec3T<S>(0, 0, -1));
  ref_ptr<DistanceJointT<S>> rope = new DistanceJointT<S>(body.get(), new FrameT<S>(), Vec3T<S>::Zero());
  CHECK(rope->getNumDOF() == 1);
  for (int dof = 0; dof < rope->getNumDOF(); ++dof) rope->getRegularizationParameters(dof)->setDamping(damping);
  rope->setCompliance(c);
  sim->add(rope);
  sim->stepTo(S(4));
  const double stretch = double(rope->getAngle()) - 1.0, hooke = double(m * c) * spook::test::kG;
  MESSAGE("DistanceJoint stretch " << stretch << " m, m g c = " << hooke << " m");
  CHECK(std::abs(stretch / hooke - 1.0) < 0.01);
  CHECK(rope->getCompliance(0) == c);
  CHECK(rope->getDamping(0) == damping);
}

// Without gravity, a 390 kg body (inertia 32.7, 35.8, 40.4 kg m^2) moving at
// 7.5 m/s and spinning at 22 or 66 rad/s about its center, tied 0.36 m from
// a world point by a DistanceJoint at 0.5 m off its center: nothing does
// work on it, so its kinetic energy never rises above its start (1% for
// round-off) over 2 s. The row's second-order term |d'_perp|^2/L, unbounded
// where the tie turns by radians in a step, reached 2.8 and 3.9 times the
// start at 1/30 and 1/60 s and 1e64 at 1/30 s and 66 rad/s.
TEST_CASE_TEMPLATE("a body spinning on a short DistanceJoint gains no energy", S, float, double) {
  using Vec3 = Vec3T<S>;
  for (const double spin : {1.0, 3.0}) {
    for (const double h : {1.0 / 60, 1.0 / 30}) {
      CAPTURE(spin);
      CAPTURE(h);
      ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
      sim->setTimeStep(S(h));
      sim->setUniformGravity(Vec3::Zero());
      ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>("spinner");
      const Vec3 inertia(S(32.7), S(35.8), S(40.4));
      body->getMassProperties()->setMass(S(390));
      body->getMassProperties()->setInertiaTensor(inertia);
      body->setVelocity(Vec3(S(-2.29), S(0.224), S(-7.13)));
      body->setAngularVelocity(Vec3(S(1.17), S(16.4), S(15.2)) * S(spin));
      sim->add(body);
      ref_ptr<FrameT<S>> tie = new FrameT<S>();
      tie->setLocalTranslate(Vec3(S(0.5), S(0), S(0)));
      sim->add(new DistanceJointT<S>(body.get(), tie.get(), Vec3(S(0.8), S(0.2), S(0))));
      const auto energy = [&] {
        const Vec3 w = body->getAngularVelocity();
        return 0.5 * 390.0 * double(body->getVelocity().squaredNorm()) + 0.5 * double(w.cwiseProduct(w).dot(inertia));
      };
      const double start = energy();
      double most = 0.0;
      for (int s = 0; s < int(std::lround(2.0 / h)); ++s) {
        sim->stepForward();
        most = std::max(most, energy() / start);
      }
      MESSAGE("spin " << spin << ", h " << h << ": most energy " << most << " of the start");
      CHECK(most <= 1.01);
    }
  }
}

// Without gravity, a 1 kg body (inertia 1 kg m^2) hinged to a 17 kg one
// (inertia 7.18, 0.225, 5.7 kg m^2), both spinning at 12.5, 25 or 50 rad/s
// and moving at 6-11 m/s, their relative spin across the hinge at up to
// 1.6 rad a step at h = 1/30 s and 5 rad at 0.1 s. Nothing does work on
// them: at 1/30 their kinetic energy never rises above its start (1%)
// over 40 steps. At 0.1 s the step's linearization fails and the energy
// is only bounded: measured 0.78-0.92 of the start, once 7.2 (float,
// 25 rad/s). The joint rows' second-order terms, the Taylor terms of the
// turn (growing as its square), reached 1e241 times the start and inf at
// 0.1 s; scaled for each body's turn, 2.5 and 3.6 at 1/30 and 16 at 0.1.
TEST_CASE_TEMPLATE("a hinged pair turning radians a step gains no energy", S, float, double) {
  using Vec3 = Vec3T<S>;
  for (const double h : {1.0 / 30, 0.1})
    for (const double spin : {0.5, 1.0, 2.0}) {
      CAPTURE(h);
      CAPTURE(spin);
      spook::test::SpinningPair<S> pair(spin, h);
      pair.sim->add(ConstraintT<S>::template createFromWorld<HingeT<S>>(
          Vec3(S(-1.3), S(0), S(-0.6)), Vec3(S(0.3), S(0.5), S(0.8)), pair.light.get(), pair.heavy.get()));
      const double most = pair.mostEnergyShare(h < 0.05 ? 40 : 20);
      MESSAGE("h " << h << " s, spin " << 25 * spin << " rad/s: most energy " << most << " of the start");
      CHECK(most <= (h < 0.05 ? 1.01 : 10.0));
    }
}

// A screw jack: a CylindricalJoint along the vertical with a Screw1D of lead
// L. Gravity drives the body down and the screw turns it, so it falls with
// a = g m / (m + I (2π/L)²) (energy: m g x = ½ m v² + ½ I (2π v/L)²).
TEST_CASE_TEMPLATE("a screw jack descends at g m / (m + I (2 pi / lead)^2)", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  const S m = S(3), I = S(0.02), lead = S(0.25);
  auto nut = makeBody<S>(*sim, "nut", m, Vec3T<S>::Zero(), I);
  auto screw = ConstraintT<S>::template createFromWorld<CylindricalJointT<S>>(Vec3T<S>::Zero(), Vec3T<S>::UnitZ(), nut.get());
  screw->getScrew1D()->setEnable(true);
  screw->setLead(lead);
  sim->add(screw);
  sim->stepTo(S(1));
  const double k = 2 * std::numbers::pi / double(lead);
  const double a = spook::test::kG * double(m) / (double(m) + double(I) * k * k);
  const double t = double(sim->getTimeStamp()), h = double(sim->getTimeStep());
  const double x = double(screw->getAngle(CylindricalJointT<S>::FIRST));
  const double theta = double(screw->getAngle(CylindricalJointT<S>::SECOND));
  MESSAGE("screw jack: x " << x << " m, exact " << -0.5 * a * t * t - 0.5 * a * h * t << " m; turns " << theta / (2 * std::numbers::pi));
  CHECK(std::abs(x - (-0.5 * a * t * t - 0.5 * a * h * t)) < pick<S>(1e-6, 1e-4));
  // The screw row is compliant (default ε = 1e-8 m/N) and carries less than m g.
  CHECK(std::abs(x - double(lead) * theta / (2 * std::numbers::pi)) < double(m) * spook::test::kG * 1e-8 + pick<S>(1e-9, 1e-5));
}

// A PlaneJoint keeps a body in the xy plane of its frame while it slides and spins freely.
TEST_CASE_TEMPLATE("a plane joint keeps a body in its plane", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(new DirectSolver());
  auto puck = makeBody<S>(*sim, "puck", S(2), Vec3T<S>(1, 2, 0));
  ref_ptr<PlaneJointT<S>> plane = new PlaneJointT<S>(puck.get(), nullptr);
  sim->add(plane);
  puck->setVelocity(S(1), S(-0.5), S(0));
  puck->setAngularVelocity(S(0.3), S(2), S(1));
  sim->stepTo(S(2));
  // In-plane motion untouched; out of plane only the compliance's m g ε.
  CHECK(std::abs(double(puck->getPosition().x()) - 3.0) < pick<S>(1e-9, 5e-5));
  CHECK(std::abs(double(puck->getPosition().y()) - 1.0) < pick<S>(1e-9, 5e-5));
  CHECK(std::abs(double(puck->getPosition().z())) < 2.0 * spook::test::kG * 1e-8 + pick<S>(1e-12, 1e-6));
}
