// Wire operations on a wire in a simulation (wire/wire_operations.hpp): cut,
// merge, detach and attach, to bodies, the world and winches.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "error_message.hpp"

using namespace spook;

namespace {

constexpr double kFallAcceleration = 9.80665;

/// A steel wire of radius 1 cm at 2 nodes per meter hanging from the world
/// at (0, 0, 10) down to `load` at the origin.
template <Scalar S>
ref_ptr<WireT<S>> hangingWire(SimulationT<S>& sim, RigidBodyT<S>* load) {
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(2));
  wire->setName("hoist");
  wire->getMaterial()->getBulkMaterial()->setDensity(S(7800));
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3T<S>(S(0), S(0), S(10))));
  wire->add(new BodyFixedNodeT<S>(load, Vec3T<S>::Zero()));
  sim.add(wire);
  return wire;
}

template <Scalar S>
ref_ptr<RigidBodyT<S>> addLoad(SimulationT<S>& sim, double mass, const Vec3T<S>& position) {
  ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>("load");
  load->getMassProperties()->setMass(S(mass));
  load->setPosition(position);
  sim.add(load);
  return load;
}

/// How far a body at rest falls in n steps of h under semi-implicit Euler.
double freeFallDrop(int n, double h) { return kFallAcceleration * h * h * n * (n + 1) / 2.0; }

}  // namespace

// Cut at half its length, the wire's lower half and its load fall freely
// (the cut released the tension: nothing holds them) while the upper half
// hangs on; the two halves' rest lengths and masses add up to the wire's.
TEST_CASE_TEMPLATE("a cut wire's lower half falls freely with its load and the upper half hangs on", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = addLoad<S>(*sim, 50.0, Vec3::Zero());
  ref_ptr<WireT<S>> wire = hangingWire<S>(*sim, load.get());
  for (int s = 0; s < 60; ++s) sim->stepForward();
  const double length = double(wire->getRestLength()), mass = double(wire->getMass());
  const std::size_t nodes = wire->getNumMassNodes();
  ref_ptr<WireT<S>> lower = wire->cut(S(length / 2));
  CHECK(lower->getName() == "hoist cut");
  CHECK(double(wire->getRestLength()) + double(lower->getRestLength()) == doctest::Approx(length).epsilon(1e-12));
  CHECK(double(wire->getMass()) + double(lower->getMass()) == doctest::Approx(mass).epsilon(1e-12));
  CHECK(double(wire->getRestLength()) == doctest::Approx(length / 2).epsilon(1e-12));
  CHECK(wire->getNumMassNodes() + lower->getNumMassNodes() == nodes + 2);  // a free end each
  const Vec3 cutEnd = wire->getPoints().back();
  CHECK((lower->getPoints().front() - cutEnd).norm() < S(1e-9));
  CHECK(cutEnd.z() == doctest::Approx(5.0).epsilon(1e-3));
  sim->add(lower);

  const double h = double(sim->getTimeStep()), z0 = double(load->getPosition().z());
  constexpr int kSteps = 30;
  for (int s = 0; s < kSteps; ++s) sim->stepForward();
  const double drop = z0 - double(load->getPosition().z()), expected = freeFallDrop(kSteps, h);
  const double gap = double((wire->getPoints().back() - lower->getPoints().front()).norm());
  const double upperTension = double(wire->getTension(S(0))), upperWeight = double(wire->getMass()) * kFallAcceleration;
  MESSAGE("load fell " << drop << " m in 0.5 s (free fall " << expected << " m); the halves " << gap
                       << " m apart; the upper half's tension at the top " << upperTension << " N (its weight "
                       << upperWeight << " N)");
  CHECK(drop == doctest::Approx(expected).epsilon(0.01));
  CHECK(gap > 1.0);
  CHECK(double(lower->getTension(S(0))) < 1e-3 * 50.0 * kFallAcceleration);
  // The upper half hangs where it was, its own weight at the top.
  CHECK(double(wire->getPoints().back().z()) == doctest::Approx(5.0).epsilon(1e-2));
  CHECK(upperTension == doctest::Approx(upperWeight).epsilon(0.05));
}

// Two wires merged end to end: the load on the lower one hangs on the upper
// one's anchor through the joint, with the tension of a single wire (the
// load's weight at the bottom, and the wire's weight more at the top).
TEST_CASE_TEMPLATE("two merged wires carry their load through the joint", S, double, float) {
  using Vec3 = Vec3T<S>;
  {
    // Before a simulation: the routes join (at the point both ends share).
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<WireT<S>> upper = new WireT<S>(S(0.01), S(2)), lower = new WireT<S>(S(0.01), S(2), upper->getMaterial());
    upper->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(0), S(0), S(10))));
    upper->add(new FreeNodeT<S>(Vec3(S(0), S(0), S(5))));
    lower->add(new FreeNodeT<S>(Vec3(S(0), S(0), S(5))));
    lower->add(new FreeNodeT<S>(Vec3(S(1), S(0), S(5))));
    upper->merge(lower.get());
    CHECK(upper->getRoute().size() == 3);
    CHECK(lower->getRoute().empty());
    sim->add(upper);
    CHECK(double(upper->getRestLength()) == doctest::Approx(6.0).epsilon(1e-6));
  }
  for (const double offset : {0.0, 0.5}) {
    CAPTURE(offset);
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<RigidBodyT<S>> load = addLoad<S>(*sim, 100.0, Vec3(S(offset), S(0), S(0)));
    ref_ptr<WireT<S>> upper = new WireT<S>(S(0.01), S(2)), lower = new WireT<S>(S(0.01), S(2), upper->getMaterial());
    upper->getMaterial()->getBulkMaterial()->setDensity(S(7800));
    upper->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(0), S(0), S(10))));
    upper->add(new FreeNodeT<S>(Vec3(S(0), S(0), S(5))));
    lower->add(new FreeNodeT<S>(Vec3(S(offset), S(0), S(5))));
    lower->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
    sim->add(upper);
    sim->add(lower);
    const double mass = double(upper->getMass()) + double(lower->getMass());
    upper->merge(lower.get());
    // Ends within a quarter of the node spacing become one node; else a
    // piece of wire as long as the gap joins them.
    const double rest = 10.0 + offset;
    CHECK(double(upper->getRestLength()) == doctest::Approx(rest).epsilon(1e-6));
    CHECK(double(upper->getMass()) == doctest::Approx(mass * rest / 10.0).epsilon(1e-6));
    CHECK(lower->getNumMassNodes() == 0);
    CHECK(lower->getPoints().empty());
    sim->remove(lower.get());
    CHECK_THROWS_AS(sim->add(lower), Error);
    CHECK(sim->getRowProducers().size() == 1);
    if (offset > 0.0) continue;  // the offset load swings
    for (int s = 0; s < 180; ++s) sim->stepForward();
    const double weight = 100.0 * kFallAcceleration, wireWeight = double(upper->getMass()) * kFallAcceleration;
    const double top = double(upper->getTension(S(0))), bottom = double(upper->getTension(upper->getRestLength()));
    MESSAGE("merged: tension " << top << " N at the anchor (load and wire " << weight + wireWeight << " N), " << bottom
                               << " N at the load (" << weight << " N); load at z = " << load->getPosition().z());
    // The lumped wire's half segments at its two ends hang on the anchor
    // and the load directly: the segment at the top carries one segment's
    // weight (0.5 m, 1 %) less than the whole wire's.
    CHECK(top == doctest::Approx(weight + wireWeight).epsilon(0.015));
    CHECK(bottom == doctest::Approx(weight).epsilon(0.01));
    CHECK(std::abs(double(load->getPosition().z())) < 0.01);
    CHECK(double(load->getVelocity().norm()) < 0.01);
  }
}

// Detached, the load falls freely and the wire's end becomes a free node;
// attached again to another body there, the wire holds that one.
TEST_CASE_TEMPLATE("a load detached from its wire falls, and the wire holds the body it is attached to next", S, double,
                   float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = addLoad<S>(*sim, 50.0, Vec3::Zero());
  ref_ptr<WireT<S>> wire = hangingWire<S>(*sim, load.get());
  for (int s = 0; s < 60; ++s) sim->stepForward();
  const double rest = double(wire->getRestLength());
  const std::size_t nodes = wire->getNumMassNodes();
  wire->detach(false);
  CHECK(wire->getNumMassNodes() == nodes + 1);
  CHECK(double(wire->getRestLength()) == doctest::Approx(rest).epsilon(1e-12));
  CHECK_THROWS_AS(wire->detach(false), Error);
  const double h = double(sim->getTimeStep()), z0 = double(load->getPosition().z());
  constexpr int kSteps = 30;
  for (int s = 0; s < kSteps; ++s) sim->stepForward();
  const double drop = z0 - double(load->getPosition().z());
  CHECK(drop == doctest::Approx(freeFallDrop(kSteps, h)).epsilon(0.01));

  // A 20 kg body where the wire's end hangs now.
  const Vec3 end = wire->getPoints().back();
  ref_ptr<RigidBodyT<S>> next = addLoad<S>(*sim, 20.0, end);
  wire->attach(new BodyFixedNodeT<S>(next.get(), Vec3::Zero()), false);
  CHECK(wire->getNumMassNodes() == nodes + 1);  // the end node stays until the step merges it
  for (int s = 0; s < 240; ++s) sim->stepForward();
  const double weight = 20.0 * kFallAcceleration, bottom = double(wire->getTension(wire->getRestLength()));
  MESSAGE("detached load fell " << drop << " m in 0.5 s; the wire then holds 20 kg at " << bottom << " N ("
                                << weight << " N), " << wire->getNumMassNodes() << " nodes");
  CHECK(bottom == doctest::Approx(weight).epsilon(0.01));
  CHECK(wire->getNumMassNodes() == nodes);
  CHECK(double(next->getVelocity().norm()) < 0.01);
}

// The wire's top taken from the world and given to a winch there: it hauls
// the load in at its speed, and the wire on its drum and off it add up to
// the wire's length. Detached from the winch, the wire and load fall and
// the winch keeps what it hauled in.
TEST_CASE_TEMPLATE("a wire attached to a winch is hauled in; detached, the winch keeps its drum", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = addLoad<S>(*sim, 50.0, Vec3::Zero());
  ref_ptr<WireT<S>> wire = hangingWire<S>(*sim, load.get());
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double rest = double(wire->getRestLength());
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3(S(0), S(0), S(10)), Vec3(S(0), S(0), S(-1)));
  winch->setForceRange(S(1e4));
  winch->setSpeed(S(-0.5));
  wire->detach(true);
  wire->attach(winch, S(2), true);
  CHECK(wire->getWinch(true) == winch.get());
  CHECK(double(wire->getRestLength()) == doctest::Approx(rest).epsilon(1e-9));
  const double z0 = double(load->getPosition().z());
  for (int s = 0; s < 60; ++s) sim->stepForward();
  const double rise = double(load->getPosition().z()) - z0, speed = double(load->getVelocity().z());
  const double total = double(wire->getRestLength()) + double(winch->getPulledInLength());
  MESSAGE("attached to a winch: the load rose " << rise << " m in 1 s at " << speed << " m/s; on the drum "
                                                << winch->getPulledInLength() << " m");
  CHECK(speed == doctest::Approx(0.5).epsilon(0.01));
  CHECK(rise == doctest::Approx(0.5).epsilon(0.05));
  CHECK(total == doctest::Approx(rest + 2.0).epsilon(1e-9));

  const double drum = double(winch->getPulledInLength());
  wire->detach(true);
  CHECK(wire->getWinch(true) == nullptr);
  CHECK(double(winch->getPulledInLength()) == drum);
  CHECK(double(winch->getCurrentSpeed()) == 0.0);
  CHECK(double(wire->getRestLength()) + drum == doctest::Approx(total).epsilon(1e-9));
  const double v0 = double(load->getVelocity().z());
  for (int s = 0; s < 30; ++s) sim->stepForward();
  // Wire and load fall together: g on the load within 1%.
  const double dv = double(load->getVelocity().z()) - v0;
  CHECK(-dv == doctest::Approx(kFallAcceleration * 30 * double(sim->getTimeStep())).epsilon(0.01));
  // The winch can take another wire.
  ref_ptr<Wire> spare = new Wire(0.01, 2.0);
  spare->add(new FreeNode(0, 0, 1));
  spare->add(new FreeNode(0, 0, 2));
  spare->attach(ref_ptr<WireWinchController>(new WireWinchController(nullptr, Vec3T<double>(0, 0, 3), Vec3T<double>(0, 0, -1))), 1.0,
                false);
  CHECK(spare->getRoute().size() == 3);
}

TEST_CASE("cut, merge, attach and detach refuse bad input by name and leave the wire unchanged") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> load = addLoad<double>(*sim, 50.0, Vec3::Zero());
  ref_ptr<Wire> unrouted = new Wire(0.01, 2.0);
  unrouted->setName("w");
  CHECK(message([&] { static_cast<void>(unrouted->cut(1.0)); }).find("'w': is not in a simulation") !=
        std::string::npos);
  ref_ptr<Wire> wire = hangingWire<double>(*sim, load.get());
  sim->stepForward();
  const double rest = wire->getRestLength();
  const std::size_t nodes = wire->getNumMassNodes();
  const auto unchanged = [&] {
    CHECK(wire->getRestLength() == rest);
    CHECK(wire->getNumMassNodes() == nodes);
    CHECK(sim->getRowProducers().size() == 1);
  };
  for (const double at : {std::nan(""), 0.0, 0.1, 9.9, 10.0, 12.0, -1.0, double(INFINITY)}) {
    CAPTURE(at);
    CHECK(message([&] { static_cast<void>(wire->cut(at)); }).find("'hoist': can only be cut at least a quarter") !=
          std::string::npos);
  }
  unchanged();

  CHECK(message([&] { wire->merge(nullptr); }).find("null wire") != std::string::npos);
  CHECK(message([&] { wire->merge(wire.get()); }).find("with itself") != std::string::npos);
  CHECK(message([&] { wire->merge(unrouted.get()); }).find("of its own simulation") != std::string::npos);
  ref_ptr<Wire> thick = new Wire(0.02, 2.0, wire->getMaterial());
  thick->add(new FreeNode(1, 0, 0));
  thick->add(new FreeNode(2, 0, 0));
  sim->add(thick);
  CHECK(message([&] { wire->merge(thick.get()); }).find("another radius (m), got 0.02") != std::string::npos);
  ref_ptr<Wire> other = new Wire(0.01, 2.0);
  other->add(new FreeNode(1, 0, 0));
  other->add(new FreeNode(2, 0, 0));
  sim->add(other);
  CHECK(message([&] { wire->merge(other.get()); }).find("another material") != std::string::npos);
  ref_ptr<Wire> same = new Wire(0.01, 2.0, wire->getMaterial());
  same->add(new FreeNode(1, 0, 0));
  same->add(new FreeNode(2, 0, 0));
  sim->add(same);
  CHECK(message([&] { wire->merge(same.get()); }).find("'hoist': is attached at its end: detach it first, got load") !=
        std::string::npos);
  CHECK(message([&] { same->merge(wire.get()); }).find("is attached at its begin: detach it first, got world") !=
        std::string::npos);
  CHECK(same->getRestLength() == doctest::Approx(1.0));

  CHECK(message([&] { wire->detach(true); wire->detach(true); }).find("'hoist': is not attached at its begin") !=
        std::string::npos);
  CHECK(message([&] { wire->attach(new FreeNode(0, 0, 11), true); }).find("only to a BodyFixedNode") !=
        std::string::npos);
  ref_ptr<RigidBody> away = new RigidBody("away");
  CHECK(message([&] { wire->attach(new BodyFixedNode(away.get(), Vec3::Zero()), true); })
            .find("can only attach to a body of its simulation; not, got away") != std::string::npos);
  CHECK(message([&] { wire->attach(new BodyFixedNode(load.get(), Vec3::Zero()), false); })
            .find("is attached at its end") != std::string::npos);
  const double detached = wire->getRestLength();
  CHECK(message([&] {
          wire->attach(new BodyFixedNode(nullptr, Vec3(0, 0, 1e7)), true);
        }).find("'hoist': would have more than 1e6 lumped nodes (length x resolution) once attached there, got 2") !=
        std::string::npos);
  CHECK(message([&] {
          wire->attach(new BodyFixedNode(nullptr, Vec3(1e200, 1e200, 0)), true);
        }).find("'hoist': would have more than 1e6 lumped nodes (length x resolution) once attached there, got 2.8") !=
        std::string::npos);  // the gap's norm does not overflow
  CHECK(wire->getRestLength() == detached);
  CHECK(message([&] { wire->detach(true); }).find("is not attached at its begin") != std::string::npos);
  ref_ptr<WireWinchController> winch = new WireWinchController(nullptr, Vec3(0, 0, 10), Vec3(0, 0, -1));
  CHECK(message([&] { wire->attach(winch, -1.0, true); }).find("pulled-in length must be finite") != std::string::npos);
  CHECK(message([&] { same->detach(true); }).find("is not attached at its begin, got a free end") != std::string::npos);
  CHECK(winch->getPulledInLength() == 0.0);
}

// A wire from a 20 kg load up over a frictionless guide (radius 0.5 m, its
// axis along y) and down to a winch, cut between the load and the sheave: the load
// falls freely, and the new wire takes the contact and the winch; a 20 kg
// load attached to its free end rises at the winch's speed over the sheave.
TEST_CASE_TEMPLATE("a cut wire's new part takes the contacts and the winch beyond the cut", S, double, float) {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> holder = new RigidBodyT<S>("holder");
  ref_ptr<GeometryT<S>> sheave = new GeometryT<S>(new CylinderT<S>(S(0.5), S(0.2)));
  holder->add(sheave);
  holder->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
  sim->add(holder);
  ref_ptr<RigidBodyT<S>> load = addLoad<S>(*sim, 20.0, Vec3(S(0.5), S(0), S(-5)));
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3(S(-0.5), S(0), S(-5)), Vec3(S(0), S(0), S(1)));
  winch->setForceRange(S(-1e3), S(1e3));
  ref_ptr<ContactNodeT<S>> contact = new ContactNodeT<S>(sheave.get(), Vec3(S(0), S(0), S(0.5)));
  contact->setFrictionCoefficient(S(0));  // a guide: the wire slides freely over it
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
  wire->setName("fall");
  wire->getMaterial()->getBulkMaterial()->setDensity(S(7800));
  wire->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
  wire->add(contact);
  wire->add(winch, S(3));
  sim->add(wire);
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double total = double(wire->getRestLength()) + double(winch->getPulledInLength());

  ref_ptr<WireT<S>> rest = wire->cut(S(2.5));
  CHECK(wire->getWinch(false) == nullptr);
  CHECK(rest->getWinch(false) == winch.get());
  REQUIRE(rest->getRoute().size() == 3);
  CHECK(rest->getRoute()[0]->getType() == WireNodeT<S>::Type::FREE);
  CHECK(rest->getRoute()[1].get() == contact.get());
  CHECK(rest->getRoute()[2]->getType() == WireNodeT<S>::Type::BODY_FIXED);
  REQUIRE(wire->getRoute().size() == 2);
  CHECK(wire->getRoute()[1]->getType() == WireNodeT<S>::Type::FREE);
  sim->add(rest);
  ref_ptr<RigidBodyT<S>> next = addLoad<S>(*sim, 20.0, rest->getPoints().front());
  rest->attach(new BodyFixedNodeT<S>(next.get(), Vec3::Zero()), true);
  winch->setSpeed(S(-0.5));
  const double z0 = double(load->getPosition().z()), next0 = double(next->getPosition().z());
  constexpr int kSteps = 60;
  for (int s = 0; s < kSteps; ++s) sim->stepForward();
  const double h = double(sim->getTimeStep());
  const double drop = z0 - double(load->getPosition().z()), rise = double(next->getPosition().z()) - next0;
  const double length = double(wire->getRestLength()) + double(rest->getRestLength()) + double(winch->getPulledInLength());
  MESSAGE("after the cut: the load fell " << drop << " m in 1 s (free fall " << freeFallDrop(kSteps, h)
                                          << " m); the 20 kg load rose " << rise << " m at " << next->getVelocity().z()
                                          << " m/s, the winch hauling at " << winch->getCurrentSpeed() << " m/s; wrap "
                                          << contact->getWrapAngle() << " rad");
  CHECK(drop == doctest::Approx(freeFallDrop(kSteps, h)).epsilon(0.01));
  CHECK(double(winch->getCurrentSpeed()) == doctest::Approx(-0.5).epsilon(0.01));
  CHECK(double(next->getVelocity().z()) == doctest::Approx(0.5).epsilon(0.02));
  CHECK(rise == doctest::Approx(0.5).epsilon(0.1));
  CHECK(double(contact->getWrapAngle()) == doctest::Approx(std::numbers::pi).epsilon(0.01));
  CHECK(length == doctest::Approx(total).epsilon(1e-9));
}
