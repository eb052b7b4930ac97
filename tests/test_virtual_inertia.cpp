#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include <spook/constraints/virtual_constraint_inertia.hpp>

#include "joint_scenes.hpp"
#include "tolerance.hpp"

using namespace spook;
using spook::test::frameAt;
using spook::test::makeBody;
using spook::test::pick;

// Virtual inertia m_v along a free axis under a constant force F: the
// implicit step gives v(t) = F t/(m + m_v) exactly (PHYSICS.md §1.3), so the
// tolerances are the scalar's rounding over 60 steps.

namespace {
template <class S>
ref_ptr<SimulationT<S>> weightless(Solver* solver = nullptr) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setUniformGravity(Vec3T<S>::Zero());
  if (solver) sim->setSolver(solver);
  return sim;
}

template <class S>
void stepWithForce(SimulationT<S>& sim, RigidBodyT<S>& body, const Vec3T<S>& force, const Vec3T<S>& torque,
                   int steps) {
  for (int i = 0; i < steps; ++i) {
    body.addForce(force);
    body.addTorque(torque);
    sim.stepForward();
  }
}
}  // namespace

TEST_CASE_TEMPLATE("virtual mass along a prismatic axis: a = F/(m + m_v) under each solver", S, float, double) {
  const double tolerance = pick<S>(1e-11, 1e-5);
  for (Solver* solver : {static_cast<Solver*>(new DirectSolver()), static_cast<Solver*>(new IterativeSolver()),
                         static_cast<Solver*>(new HybridSolver())}) {
    ref_ptr<Solver> keep = solver;
    auto sim = weightless<S>(solver);
    auto slider = makeBody<S>(*sim, "slider", S(2), Vec3T<S>::Zero());
    ref_ptr<PrismaticT<S>> prismatic = new PrismaticT<S>(slider.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get());
    sim->add(prismatic);
    ref_ptr<VirtualConstraintInertiaT<S>> inertia = new VirtualConstraintInertiaT<S>(prismatic.get(), S(3), 0, 0, 0);
    sim->add(inertia);
    CHECK(inertia->getNumDOF() == 1);
    stepWithForce<S>(*sim, *slider, Vec3T<S>(S(10), 0, 0), Vec3T<S>::Zero(), 60);
    CHECK(double(slider->getVelocity().x()) == doctest::Approx(10.0 / 5.0).epsilon(tolerance));

    // Removed, the body accelerates at F/m again.
    sim->remove(inertia.get());
    const double before = double(slider->getVelocity().x());
    stepWithForce<S>(*sim, *slider, Vec3T<S>(S(10), 0, 0), Vec3T<S>::Zero(), 60);
    CHECK(double(slider->getVelocity().x()) - before == doctest::Approx(10.0 / 2.0).epsilon(tolerance));
  }
}

TEST_CASE_TEMPLATE("virtual mass has no weight: a vertical slider falls at g m/(m + m_v)", S, float, double) {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  auto slider = makeBody<S>(*sim, "slider", S(1), Vec3T<S>::Zero());
  ref_ptr<PrismaticT<S>> prismatic = new PrismaticT<S>(slider.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  sim->add(prismatic);
  sim->add(ref_ptr<VirtualConstraintInertiaT<S>>(new VirtualConstraintInertiaT<S>(prismatic.get(), S(3), 0, 0, 0)));
  for (int i = 0; i < 60; ++i) sim->stepForward();
  CHECK(double(slider->getVelocity().z()) == doctest::Approx(-spook::test::kG / 4.0).epsilon(pick<S>(1e-11, 1e-5)));
}

TEST_CASE_TEMPLATE("virtual moment of inertia about a hinge axis: alpha = T/(I + I_v)", S, float, double) {
  auto sim = weightless<S>(new DirectSolver());
  auto wheel = makeBody<S>(*sim, "wheel", S(4), Vec3T<S>::Zero(), S(0.5));
  ref_ptr<HingeT<S>> hinge = new HingeT<S>(wheel.get(), frameAt<S>(Vec3T<S>::Zero()).get());
  sim->add(hinge);
  ref_ptr<VirtualConstraintInertiaT<S>> inertia = new VirtualConstraintInertiaT<S>(hinge.get(), S(100), S(1.5), 0, 0);
  sim->add(inertia);
  stepWithForce<S>(*sim, *wheel, Vec3T<S>::Zero(), Vec3T<S>(0, 0, S(2)), 60);
  CHECK(double(wheel->getAngularVelocity().z()) == doctest::Approx(2.0 / 2.0).epsilon(pick<S>(1e-9, 1e-5)));
  CHECK(double(hinge->getAngle()) == doctest::Approx(61.0 / 120.0).epsilon(pick<S>(1e-6, 1e-4)));  // h²α N(N+1)/2
  // The virtual mass along the axis acts on a DOF the hinge already locks.
  CHECK(std::abs(double(wheel->getPosition().z())) < 1e-9);
}

TEST_CASE_TEMPLATE("virtual inertia split between two bodies acts on each body alone", S, float, double) {
  // Seed 001 §12.19.2: half of the virtual mass on each body of a prismatic.
  auto sim = weightless<S>(new DirectSolver());
  auto first = makeBody<S>(*sim, "first", S(1), Vec3T<S>::Zero());
  auto second = makeBody<S>(*sim, "second", S(3), Vec3T<S>(S(1), 0, 0));
  ref_ptr<PrismaticT<S>> prismatic = new PrismaticT<S>(first.get(), frameAt<S>(Vec3T<S>::Zero(), Vec3T<S>::UnitX()).get(),
                                                       second.get(), nullptr);
  sim->add(prismatic);
  ref_ptr<VirtualConstraintInertiaT<S>> inertia =
      new VirtualConstraintInertiaT<S>(prismatic.get(), S(0.5), 0, S(0.5), 0);
  sim->add(inertia);
  CHECK(inertia->getNumDOF() == 2);
  for (int i = 0; i < 60; ++i) {
    first->addForce(S(4), 0, 0);
    second->addForce(S(2), 0, 0);
    sim->stepForward();
  }
  const double tolerance = pick<S>(1e-9, 1e-5);
  CHECK(double(first->getVelocity().x()) == doctest::Approx(4.0 / 1.5).epsilon(tolerance));
  CHECK(double(second->getVelocity().x()) == doctest::Approx(2.0 / 3.5).epsilon(tolerance));
}

TEST_CASE("bad virtual inertia input throws spook::Error naming it and the value, and changes nothing") {
  ref_ptr<Simulation> sim = new Simulation();
  auto body = makeBody<double>(*sim, "slider", 1.0, Vec3T<double>::Zero());
  ref_ptr<Prismatic> prismatic = new Prismatic(body.get(), frameAt<double>(Vec3T<double>::Zero()).get());
  sim->add(prismatic);
  const auto message = [](auto&& f) -> std::string {
    try {
      f();
    } catch (const spook::Error& e) {
      return e.what();
    }
    return "";
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(message([&] { VirtualConstraintInertiaRef v = new VirtualConstraintInertia(nullptr, 1, 0, 0, 0); })
            .find("needs a constraint") != std::string::npos);
  CHECK(message([&] { VirtualConstraintInertiaRef v = new VirtualConstraintInertia(prismatic.get(), -1, 0, 0, 0); })
            .find("-1") != std::string::npos);
  CHECK(message([&] { VirtualConstraintInertiaRef v = new VirtualConstraintInertia(prismatic.get(), 0, nan, 0, 0); })
            .find("rotational inertia") != std::string::npos);
  // The prismatic's second body is the world.
  CHECK(message([&] { VirtualConstraintInertiaRef v = new VirtualConstraintInertia(prismatic.get(), 0, 0, 2, 0); })
            .find("world") != std::string::npos);

  VirtualConstraintInertiaRef inertia = new VirtualConstraintInertia(prismatic.get(), 1, 0, 0, 0);
  CHECK(message([&] { inertia->setInertia(2, 1, 1); }).find("VirtualConstraintInertia") != std::string::npos);
  CHECK(message([&] { inertia->setInertia(0, 2, -3); }).find("-3") != std::string::npos);
  CHECK(inertia->getTranslationalInertia(0) == 1.0);  // the failed set kept both values
  CHECK(inertia->getRotationalInertia(0) == 0.0);
  CHECK(sim->getConstraints().size() == 1);
}
