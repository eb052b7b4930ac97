// Wire operations (wire/wire.hpp): reverse, findPoint and findDistance,
// setResolutionPerUnitLength at run time.

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "error_message.hpp"

using namespace spook;

TEST_CASE_TEMPLATE("a wire reversed in a simulation keeps its state, its tension and its load", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>();
  load->getMassProperties()->setMass(S(50));
  sim->add(load);
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3(S(0), S(0), S(10)), Vec3(S(0), S(0), S(-1)));
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(2));
  wire->getMaterial()->getBulkMaterial()->setDensity(S(7800));
  wire->add(winch, S(5));
  wire->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
  sim->add(wire);
  for (int s = 0; s < 60; ++s) sim->stepForward();
  const std::vector<Vec3> points = wire->getPoints();
  const double rest = double(wire->getRestLength()), top = double(wire->getTension(S(0)));
  const double bottom = double(wire->getTension(S(rest))), z = double(load->getPosition().z());
  wire->reverse();
  CHECK(wire->getWinch(false) == winch.get());
  CHECK(wire->getWinch(true) == nullptr);
  const std::vector<Vec3> reversed = wire->getPoints();
  REQUIRE(reversed.size() == points.size());
  for (std::size_t k = 0; k < points.size(); ++k) CHECK((reversed[k] - points[points.size() - 1 - k]).norm() == S(0));
  CHECK(double(wire->getTension(S(0))) == doctest::Approx(bottom));
  CHECK(double(wire->getTension(S(rest))) == doctest::Approx(top));
  // It goes on as before: the winch hauls in from its new end.
  winch->setForceRange(S(1e4));
  winch->setSpeed(S(-0.5));
  for (int s = 0; s < 60; ++s) sim->stepForward();
  const double rise = double(load->getPosition().z()) - z;
  MESSAGE("reversed: tensions " << top << " and " << bottom << " N at the winch and load; hauled " << rise
                                << " m in 1 s");
  CHECK(rise == doctest::Approx(0.5).epsilon(0.05));
  CHECK(double(wire->getRestLength()) + double(winch->getPulledInLength()) == doctest::Approx(rest + 5.0).epsilon(1e-6));
}

TEST_CASE_TEMPLATE("findPoint and findDistance walk a taut wire", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setUniformGravity(Vec3::Zero());
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(2));
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3::Zero()));
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(10), S(0), S(0))));
  CHECK_THROWS_AS(static_cast<void>(wire->findPoint(S(1))), Error);
  sim->add(wire);
  sim->stepForward();
  for (const double d : {0.0, 0.3, 2.5, 7.75, 10.0}) {
    CAPTURE(d);
    CHECK((wire->findPoint(S(d)) - Vec3(S(d), S(0), S(0))).norm() < S(1e-5));
    CHECK(double(wire->findDistance(Vec3(S(d), S(1), S(-2)))) == doctest::Approx(d).epsilon(1e-5).scale(1));
    // The seeds' findPoint(any 3D point): the closest point on the wire.
    CHECK((wire->findPoint(Vec3(S(d), S(1), S(-2))) - Vec3(S(d), S(0), S(0))).norm() < S(1e-5));
  }
  CHECK((wire->findPoint(S(-3)) - Vec3::Zero()).norm() < S(1e-6));
  CHECK(double(wire->findDistance(Vec3(S(20), S(0), S(0)))) == doctest::Approx(10.0).epsilon(1e-5));
}

TEST_CASE_TEMPLATE("a wire takes a finer resolution in a simulation", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setUniformGravity(Vec3::Zero());
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(1));
  wire->setName("w");
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3::Zero()));
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(10), S(0), S(0))));
  sim->add(wire);
  sim->stepForward();
  CHECK(wire->getNumMassNodes() == 9);
  wire->setResolutionPerUnitLength(S(4));
  for (int s = 0; s < 3; ++s) sim->stepForward();
  MESSAGE("4 nodes per m: " << wire->getNumMassNodes() << " nodes");
  CHECK(wire->getNumMassNodes() >= 30);
  CHECK(wire->getNumMassNodes() <= 39);
  CHECK(double(wire->getRestLength()) == doctest::Approx(10.0).epsilon(1e-9));
  CHECK(spook::test::errorMessage([&] { wire->setResolutionPerUnitLength(S(0)); }).find("'w': resolution") !=
        std::string::npos);
  CHECK(spook::test::errorMessage([&] { wire->setResolutionPerUnitLength(S(1e9)); }).find("1e6") != std::string::npos);
  CHECK(double(wire->getResolutionPerUnitLength()) == doctest::Approx(4.0));
}
