#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <spook/constraints/virtual_constraint_inertia.hpp>
#include <spook/spook.hpp>

#include "policies.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::kPolicies;
using spook::test::makeSolver;
using spook::test::pick;
using spook::test::Policy;
using spook::test::policyName;

// Jointed bodies whose geometries overlap, as every machine is drawn: the
// links overlap at their pins. By default a constraint's two bodies do not
// collide; when collisions between them are switched on, contact and joint
// rows disagree and the step must settle at a compromise set by their
// compliances, never diverge.

namespace {

#ifdef NDEBUG
constexpr double kSlow = 1.0;  // Release: the stated durations
#else
constexpr double kSlow = 0.2;  // Debug and sanitizers: a fifth of them
#endif

template <class S>
ref_ptr<SimulationT<S>> simulationFor(Policy policy) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setSolver(makeSolver(policy));
  return sim;
}

/// A solid link of 1 kg from pin a to pin b: a box of square section
/// `thickness` reaching thickness/2 past each pin, so that links meeting at
/// a pin overlap there.
template <class S>
ref_ptr<RigidBodyT<S>> addLink(SimulationT<S>& sim, const Vec3T<S>& a, const Vec3T<S>& b, S thickness,
                               const char* name) {
  const Vec3T<S> d = b - a;
  const S length = d.norm();
  ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>(
      new GeometryT<S>(new BoxT<S>(Vec3T<S>((length + thickness) / 2, thickness / 2, thickness / 2))), name);
  body->getMassProperties()->setMass(S(1));
  body->updateMassProperties();
  body->setPosition((a + b) / 2);
  body->setRotation(spook::rotate<S>(Vec3T<S>::UnitX(), d));
  sim.add(body);
  return body;
}

/// A pin (hinge about y) at a world point; body2 nullptr pins to the ground.
template <class S>
ref_ptr<HingeT<S>> addPin(SimulationT<S>& sim, const Vec3T<S>& point, RigidBodyT<S>* body1,
                          RigidBodyT<S>* body2 = nullptr) {
  ref_ptr<HingeT<S>> hinge = ConstraintT<S>::template createFromWorld<HingeT<S>>(point, Vec3T<S>::UnitY(), body1, body2);
  sim.add(ref_ptr<ConstraintT<S>>(hinge.get()));
  return hinge;
}

template <class S>
double pinGap(const ConstraintT<S>& pin) {
  return double((pin.getAttachmentFrame(0)->getTranslate() - pin.getAttachmentFrame(1)->getTranslate()).norm());
}

template <class S>
bool finiteState(const SimulationT<S>& sim) {
  return std::all_of(sim.getRigidBodies().begin(), sim.getRigidBodies().end(), [](const auto& b) {
    return b->getPosition().allFinite() && b->getVelocity().allFinite() && b->getAngularVelocity().allFinite() &&
           b->getRotation().coeffs().allFinite();
  });
}

/// A linkage driven at its crank: crank 0.2 m from the ground pin at the
/// origin, straight up, its hinge motor at 2 rad/s; coupler 1 m; with a
/// rocker (0.8 m, ground pin at 0.9 m) it is the crank–rocker four-bar,
/// without one an open chain whose coupler swings freely.
template <class S>
struct Linkage {
  static constexpr double kSpeed = 2.0;  // rad/s
  ref_ptr<SimulationT<S>> sim;
  std::vector<ref_ptr<HingeT<S>>> pins;
  ref_ptr<RigidBodyT<S>> crank;

  Linkage(Policy policy, double thickness, bool withRocker, bool collide) : sim(simulationFor<S>(policy)) {
    using V = Vec3T<S>;
    const S t = S(thickness);
    const V a(0, 0, 0), b(0, 0, S(0.2)), d(S(0.9), 0, 0);
    // The coupler's far pin: on the rocker's circle for the four-bar
    // (|c − b| = 1, |c − d| = 0.8, above the ground line), horizontal otherwise.
    V c(S(1), 0, S(0.2));
    if (withRocker) {
      const double bd = std::hypot(0.9, 0.2), along = (1.0 + bd * bd - 0.64) / (2.0 * bd);
      const double across = std::sqrt(1.0 - along * along);
      const double ux = 0.9 / bd, uz = -0.2 / bd;  // unit vector b → d
      c = V(S(along * ux - across * uz), 0, S(0.2 + along * uz + across * ux));
    }
    crank = addLink<S>(*sim, a, b, t, "crank");
    auto coupler = addLink<S>(*sim, b, c, t, "coupler");
    pins.push_back(addPin<S>(*sim, a, crank.get()));
    pins.push_back(addPin<S>(*sim, b, crank.get(), coupler.get()));
    if (withRocker) {
      auto rocker = addLink<S>(*sim, d, c, t, "rocker");
      pins.push_back(addPin<S>(*sim, c, coupler.get(), rocker.get()));
      pins.push_back(addPin<S>(*sim, d, rocker.get()));
    }
    for (auto& pin : pins) pin->setEnableCollisions(collide);
    auto* motor = pins[0]->getMotor1D();
    motor->setEnable(true);
    motor->setSpeed(S(kSpeed));
  }

  [[nodiscard]] double worstGap() const {
    double worst = 0.0;
    for (const auto& pin : pins) worst = std::max(worst, pinGap(*pin));
    return worst;
  }
  [[nodiscard]] double crankSpeed() const { return std::abs(double(crank->getAngularVelocity().y())); }
};

}  // namespace

TEST_CASE_TEMPLATE("jointed bodies do not collide by default; the constraint, the geometries and removal restore the pair",
                   S, float, double) {
  using V = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setUniformGravity(V::Zero());
  ref_ptr<GeometryT<S>> g1 = new GeometryT<S>(new BoxT<S>(V(S(0.5), S(0.1), S(0.1))));
  ref_ptr<GeometryT<S>> g2 = new GeometryT<S>(new BoxT<S>(V(S(0.5), S(0.1), S(0.1))));
  ref_ptr<RigidBodyT<S>> b1 = new RigidBodyT<S>(g1, "one");
  ref_ptr<RigidBodyT<S>> b2 = new RigidBodyT<S>(g2, "two");
  b2->setPosition(V(S(0.9), 0, 0));  // overlapping b1 by 0.1 m
  sim->add(b1);
  sim->add(b2);
  // Static ground under b1 only: a body pinned to the world still collides with it.
  ref_ptr<GeometryT<S>> ground = new GeometryT<S>(new BoxT<S>(V(S(0.3), S(0.3), S(0.1))));
  ground->setPosition(V(S(-0.2), 0, S(-0.15)));
  sim->add(ground);
  // Which pairs touch after one step, as "a-b" with the names in order.
  const auto touching = [&] {
    std::vector<std::string> pairs;
    sim->stepForward();
    for (const auto& c : sim->getGeometryContacts()) {
      const std::string a = c.rigidBody(0) ? c.rigidBody(0)->getName() : "ground";
      const std::string b = c.rigidBody(1) ? c.rigidBody(1)->getName() : "ground";
      pairs.push_back(std::min(a, b) + "-" + std::max(a, b));
    }
    std::sort(pairs.begin(), pairs.end());
    return pairs;
  };
  using Pairs = std::vector<std::string>;
  CHECK(touching() == Pairs{"ground-one", "one-two"});  // no constraint yet

  ref_ptr<HingeT<S>> hinge =
      ConstraintT<S>::template createFromWorld<HingeT<S>>(V(S(0.45), 0, 0), V::UnitY(), b1.get(), b2.get());
  sim->add(ref_ptr<ConstraintT<S>>(hinge.get()));
  ref_ptr<HingeT<S>> pin = ConstraintT<S>::template createFromWorld<HingeT<S>>(V::Zero(), V::UnitY(), b1.get());
  sim->add(ref_ptr<ConstraintT<S>>(pin.get()));
  CHECK_FALSE(hinge->getEnableCollisions());
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  CHECK(touching() == Pairs{"ground-one"});  // the world pin filters nothing

  hinge->setEnableCollisions(true);
  CHECK(sim->getSpace()->canCollide(*g1, *g2));
  CHECK(touching() == Pairs{"ground-one", "one-two"});
  g1->setEnableCollisions(g2.get(), false);  // the geometry filter still applies, both ways
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  CHECK_FALSE(sim->getSpace()->canCollide(*g2, *g1));
  g2->setEnableCollisions(g1.get(), true);
  CHECK(sim->getSpace()->canCollide(*g1, *g2));

  hinge->setEnableCollisions(false);
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  hinge->setEnable(false);  // a disabled constraint filters nothing
  CHECK(sim->getSpace()->canCollide(*g1, *g2));
  hinge->setEnable(true);
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  // A second constraint on the same bodies that allows collisions does not
  // lift the first's filter; a disabled one adds none.
  ref_ptr<LockJointT<S>> lock = new LockJointT<S>(b1.get(), nullptr, b2.get(), nullptr);
  lock->setEnableCollisions(true);
  sim->add(ref_ptr<ConstraintT<S>>(lock.get()));
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  sim->remove(hinge.get());
  CHECK(sim->getSpace()->canCollide(*g1, *g2));
  lock->setEnableCollisions(false);
  CHECK_FALSE(sim->getSpace()->canCollide(*g1, *g2));
  lock->setEnable(false);
  CHECK(sim->getSpace()->canCollide(*g1, *g2));
  lock->setEnable(true);
  sim->remove(lock.get());
  CHECK(sim->getSpace()->canCollide(*g1, *g2));
}

TEST_CASE_TEMPLATE("RigidBody(geometry) takes the geometry and generates its mass; bad geometries throw", S, float,
                   double) {
  using V = Vec3T<S>;
  ref_ptr<GeometryT<S>> geometry = new GeometryT<S>(new BoxT<S>(V(1, 1, 1)));
  ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>(geometry);
  CHECK(geometry->getRigidBody() == body.get());
  CHECK(body->getGeometries().size() == 1);
  ref_ptr<RigidBodyT<S>> reference = new RigidBodyT<S>();
  reference->add(new GeometryT<S>(new BoxT<S>(V(1, 1, 1))));
  CHECK(body->getMassProperties()->getMass() == reference->getMassProperties()->getMass());
  ref_ptr<RigidBodyT<S>> named = new RigidBodyT<S>(new GeometryT<S>(new SphereT<S>(S(0.5))), "ball");
  CHECK(named->getName() == "ball");

  CHECK_THROWS_WITH_AS(ref_ptr<RigidBodyT<S>>(new RigidBodyT<S>(ref_ptr<GeometryT<S>>(), "empty")),
                       doctest::Contains("null Geometry"), spook::Error);
  CHECK_THROWS_WITH_AS(ref_ptr<RigidBodyT<S>>(new RigidBodyT<S>(geometry, "thief")),
                       doctest::Contains("another body"), spook::Error);
  CHECK(geometry->getRigidBody() == body.get());
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<GeometryT<S>> standing = new GeometryT<S>(new BoxT<S>(V(1, 1, 1)));
  sim->add(standing);
  CHECK_THROWS_AS(ref_ptr<RigidBodyT<S>>(new RigidBodyT<S>(standing)), spook::Error);
  CHECK(standing->getRigidBody() == nullptr);
}

TEST_CASE_TEMPLATE("the seeds' hinge snippet: two boxes made at one place stay together", S, float, double) {
  // Seed 001 §12.19.2: two 2 m boxes created at the same place, hinged with
  // empty frames, virtual inertia on the hinge; they fall together for 2 s.
  for (Policy policy : kPolicies) {
    CAPTURE(std::string(policyName(policy)));
    auto sim = simulationFor<S>(policy);
    ref_ptr<FrameT<S>> frame1 = new FrameT<S>(), frame2 = new FrameT<S>();
    ref_ptr<RigidBodyT<S>> body1 = new RigidBodyT<S>(new GeometryT<S>(new BoxT<S>(Vec3T<S>(1, 1, 1))));
    ref_ptr<RigidBodyT<S>> body2 = new RigidBodyT<S>(new GeometryT<S>(new BoxT<S>(Vec3T<S>(1, 1, 1))));
    sim->add(body1);
    sim->add(body2);
    ref_ptr<HingeT<S>> hinge = new HingeT<S>(body1.get(), frame1.get(), body2.get(), frame2.get());
    sim->add(ref_ptr<ConstraintT<S>>(hinge.get()));
    sim->add(ref_ptr<ConstraintT<S>>(new VirtualConstraintInertiaT<S>(hinge.get(), 0, 0, 0, S(1))));
    double worst = 0.0;
    for (int i = 0; i < 120; ++i) {
      sim->stepForward();
      worst = std::max(worst, double((body1->getPosition() - body2->getPosition()).norm()));
    }
    CHECK(worst < (policy == Policy::DIRECT ? 1e-6 : 1e-4));
  }
}

// Direct and hybrid hold the motor to 0.5% (measured 0.47%). Gauss-Seidel
// converges on the closed loop at ~0.8 per sweep: with its default 16 sweeps
// the crank lags by 3.5% on the first step (the motor takes the resting
// linkage to speed in one step) and up to 1.3% after it (9.5% row by row
// before the joint blocks); 32 sweeps hold it to 0.14%, 48 to 0.014%.
// Warm starting would hold it to 0.01% after three steps but feeds energy
// into a swinging hinge chain (+47 m g L in 10 s, bench/joint_study), so it
// stays off by default.
TEST_CASE_TEMPLATE("a solid-link four-bar closes and its crank turns at the motor's speed", S, float, double) {
  const int steps = int(600 * kSlow);  // 10 s
  for (Policy policy : kPolicies)
    for (int sweeps : {0, 32}) {
      if (sweeps > 0 && policy != Policy::ITERATIVE) continue;
      CAPTURE(std::string(policyName(policy)));
      CAPTURE(sweeps);
      Linkage<S> fourBar(policy, 0.06, true, false);
      if (sweeps > 0) fourBar.sim->getSolver()->setNumIterations(sweeps);
      double worstGap = 0.0, worstSpeed = 0.0;
      for (int i = 0; i < steps; ++i) {
        fourBar.sim->stepForward();
        worstGap = std::max(worstGap, fourBar.worstGap());
        worstSpeed = std::max(worstSpeed, std::abs(fourBar.crankSpeed() - Linkage<S>::kSpeed) / Linkage<S>::kSpeed);
      }
      CHECK(worstGap < (policy == Policy::DIRECT ? 1e-5 : 1e-3));
      MESSAGE(std::string(policyName(policy)) << ", " << (sweeps > 0 ? std::to_string(sweeps) : "default") << " sweeps: worst crank speed error " << worstSpeed);
      CHECK(worstSpeed < (policy == Policy::ITERATIVE && sweeps == 0 ? 0.05 : 0.005));
    }
}

TEST_CASE_TEMPLATE("a solid-link four-bar with collisions between its links stays finite", S, float, double) {
  const int steps = int(600 * kSlow);
  for (Policy policy : kPolicies) {
    CAPTURE(std::string(policyName(policy)));
    Linkage<S> fourBar(policy, 0.06, true, true);
    bool finite = true;
    for (int i = 0; i < steps && finite; ++i) {
      fourBar.sim->stepForward();
      finite = finiteState(*fourBar.sim) && fourBar.worstGap() < 1.0;
    }
    CHECK(finite);
  }
}

TEST_CASE_TEMPLATE("a driven crank and coupler fighting their contact stay finite, 2 to 10 cm thick", S, float,
                   double) {
  const int steps = int(120 * kSlow);  // 2 s
  for (Policy policy : kPolicies)
    for (double thickness : {0.02, 0.03, 0.05, 0.06, 0.07, 0.1}) {
      CAPTURE(std::string(policyName(policy)));
      CAPTURE(thickness);
      Linkage<S> chain(policy, thickness, false, true);
      double worst = 0.0;
      for (int i = 0; i < steps; ++i) {
        chain.sim->stepForward();
        worst = std::max(worst, finiteState(*chain.sim) ? chain.worstGap() : HUGE_VAL);
      }
      CHECK(worst < 2.0 * thickness);
    }
}
