// Winches (wire/wire_winch_controller.hpp): hauling in at the set speed,
// stalling at the force limit, paying out under the brake, the wire's total
// length kept through both, auto-feed, and refusal of bad input.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>

#include <spook/spook.hpp>

#include "error_message.hpp"
#include "tolerance.hpp"

using namespace spook;

namespace {

constexpr double kStandardGravity = 9.80665;  // m/s², the simulation's default

/// A load of `mass` kg hung 10 m below a winch on the world at z = 10 by a
/// wire of radius 1 cm (2 nodes/m, E = 6e10 Pa) of `density` kg/m³, with
/// `pulledIn` m on the drum; the load starts where the stretched wire holds
/// it.
template <Scalar S>
struct HungLoad {
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>();
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3T<S>(S(0), S(0), S(10)), Vec3T<S>(S(0), S(0), S(-1)));
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(2));

  double linearDensity;

  HungLoad(double mass, double pulledIn, double density, bool staticLoad = false)
      : linearDensity(density * std::numbers::pi * 1e-4) {
    load->getMassProperties()->setMass(S(mass));
    if (staticLoad) load->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
    sim->add(load);
    wire->setName("hoist");
    wire->getMaterial()->getBulkMaterial()->setDensity(S(density));
    wire->add(winch, S(pulledIn));
    wire->add(new BodyFixedNodeT<S>(load.get(), Vec3T<S>::Zero()));
    sim->add(wire);
    const double EA = 6e10 * std::numbers::pi * 1e-4;
    if (!staticLoad) load->setPosition(S(0), S(0), S(-mass * kStandardGravity * 10.0 / EA));
  }
  [[nodiscard]] double totalLength() const {
    return double(winch->getPulledInLength()) + double(wire->getRestLength());
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a winch hauls a load in at its speed and pays it out, adding and removing nodes", S, double,
                   float) {
  HungLoad<S> hoist(100.0, 20.0, 7800.0);  // steel: its nodes are resolved at this tension
  hoist.winch->setForceRange(S(1e5));
  const std::size_t nodes = hoist.wire->getNumMassNodes();
  for (const double speed : {-0.5, 0.5}) {
    CAPTURE(speed);
    hoist.winch->setSpeed(S(speed));
    for (int s = 0; s < 60; ++s) hoist.sim->stepForward();  // the load's start transient
    const double from = double(hoist.load->getPosition().z()), pulledIn = double(hoist.winch->getPulledInLength());
    const int steps = 180;
    for (int s = 0; s < steps; ++s) hoist.sim->stepForward();
    const double time = steps * double(hoist.sim->getTimeStep());
    const double rise = double(hoist.load->getPosition().z()) - from;
    MESSAGE("speed " << speed << " m/s: load moves " << rise / time << " m/s, " << hoist.wire->getNumMassNodes()
                     << " nodes, motor force " << hoist.winch->getCurrentForce() << " N, tension "
                     << hoist.wire->getTension(S(0)) << " N");
    CHECK(rise / time == doctest::Approx(-speed).epsilon(0.01));
    CHECK(double(hoist.winch->getPulledInLength()) - pulledIn == doctest::Approx(-speed * time).epsilon(0.01));
    CHECK(double(hoist.winch->getCurrentSpeed()) == doctest::Approx(speed).epsilon(0.01));
    // The motor holds the load and the wire below it.
    const double weight = (100.0 + hoist.linearDensity * double(hoist.wire->getRestLength())) * kStandardGravity;
    CHECK(-double(hoist.winch->getCurrentForce()) == doctest::Approx(weight).epsilon(0.02));
    if (speed < 0) CHECK(hoist.wire->getNumMassNodes() < nodes);
  }
  CHECK(hoist.wire->getNumMassNodes() == doctest::Approx(double(nodes)).epsilon(0.2));
}

TEST_CASE_TEMPLATE("a winch stalls at its force limit", S, double, float) {
  HungLoad<S> hoist(1.0, 20.0, 7800.0, true);  // the wire's end is held
  const double limit = 5000.0;
  hoist.winch->setForceRange(S(-limit), S(0));
  hoist.winch->setSpeed(S(-0.5));
  for (int s = 0; s < 120; ++s) hoist.sim->stepForward();
  MESSAGE("stalled: tension " << hoist.wire->getTension(S(0)) << " N at the winch, motor "
                              << hoist.winch->getCurrentForce() << " N, drum " << hoist.winch->getCurrentSpeed()
                              << " m/s");
  CHECK(double(hoist.wire->getTension(S(0))) == doctest::Approx(limit).epsilon(0.01));
  // Below, the tension falls by the weight of the wire above.
  CHECK(double(hoist.wire->getTension(S(5))) ==
        doctest::Approx(limit - 5.0 * hoist.linearDensity * kStandardGravity).epsilon(0.01));
  CHECK(double(hoist.winch->getCurrentForce()) == doctest::Approx(-limit).epsilon(1e-3));
  CHECK(std::abs(double(hoist.winch->getCurrentSpeed())) < 1e-3);
}

TEST_CASE_TEMPLATE("a winch's brake holds within its range and pays out beyond it", S, double, float) {
  const double mass = 100.0, weight = mass * kStandardGravity;
  for (const double brake : {2.0 * weight, 0.5 * weight}) {
    CAPTURE(brake);
    HungLoad<S> hoist(mass, 20.0, 100.0);  // a light wire: 0.3 % of the load
    hoist.winch->setBrakeForceRange(S(brake));
    const int steps = 120;
    for (int s = 0; s < steps; ++s) hoist.sim->stepForward();
    const double time = steps * double(hoist.sim->getTimeStep());
    const double drop = -double(hoist.load->getPosition().z()), speed = -double(hoist.load->getVelocity().z());
    MESSAGE("brake " << brake << " N: the load fell " << drop << " m, at " << speed << " m/s; brake force "
                     << hoist.winch->getCurrentBrakeForce() << " N");
    if (brake > weight) {
      CHECK(std::abs(speed) < 1e-3);
      CHECK(double(hoist.winch->getPulledInLength()) == doctest::Approx(20.0).epsilon(1e-5));
    } else {
      // The load falls against the brake: a = (m g − B)/m.
      const double a = (weight - brake) / mass;
      CHECK(speed == doctest::Approx(a * time).epsilon(0.02));
      CHECK(-double(hoist.winch->getCurrentBrakeForce()) == doctest::Approx(brake).epsilon(1e-3));
      CHECK(double(hoist.winch->getPulledInLength()) == doctest::Approx(20.0 - drop).epsilon(1e-3));
    }
  }
}

TEST_CASE_TEMPLATE("a winch keeps the wire's total length through paying out and hauling in", S, double, float) {
  HungLoad<S> hoist(50.0, 10.0, 7800.0);
  hoist.winch->setForceRange(S(1e5));
  const double total = hoist.totalLength();
  double worst = 0.0;
  for (int s = 0; s < 1000; ++s) {
    hoist.winch->setSpeed(S((s / 100) % 2 == 0 ? 1.0 : -1.0));
    hoist.sim->stepForward();
    worst = std::max(worst, std::abs(hoist.totalLength() - total));
  }
  // Float rounds the getters to 24 bits.
  const double tolerance = std::is_same_v<S, double> ? 1e-9 : 4e-6 * total;
  MESSAGE("total length " << total << " m, worst change " << worst << " m");
  CHECK(worst < tolerance);
}

TEST_CASE_TEMPLATE("an auto-feeding winch takes in the slack of a wire routed around a point", S, double, float) {
  // A winch on the world at z = 10, routed through a point 3 m aside to a
  // 100 kg load 10 m below: 11.66 m of wire where 10 m hang straight.
  const double mass = 100.0, density = 7800.0, pulledIn = 20.0, straight = 10.0;
  const double routed = 2.0 * std::sqrt(3.0 * 3.0 + 5.0 * 5.0);
  for (const bool autoFeed : {false, true}) {
    CAPTURE(autoFeed);
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>();
    load->getMassProperties()->setMass(S(mass));
    sim->add(load);
    ref_ptr<WireWinchControllerT<S>> winch =
        new WireWinchControllerT<S>(nullptr, Vec3T<S>(S(0), S(0), S(10)), Vec3T<S>(S(0), S(0), S(-1)));
    winch->setEnableAutoFeed(autoFeed);
    ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(2));
    wire->getMaterial()->getBulkMaterial()->setDensity(S(density));
    wire->add(winch, S(pulledIn));
    wire->add(new FreeNodeT<S>(S(3), S(0), S(5)));
    wire->add(new BodyFixedNodeT<S>(load.get(), Vec3T<S>::Zero()));
    sim->add(wire);
    // Where the straight wire holds it (as HungLoad).
    load->setPosition(S(0), S(0), S(-mass * kStandardGravity * straight / (6e10 * std::numbers::pi * 1e-4)));
    const double total = double(winch->getPulledInLength()) + double(wire->getRestLength());
    CHECK(total == doctest::Approx(pulledIn + routed).epsilon(1e-6));
    double lowest = 0.0;
    for (int s = 0; s < 120; ++s) {
      sim->stepForward();
      lowest = std::min(lowest, double(load->getPosition().z()));
    }
    MESSAGE("auto-feed " << autoFeed << ": rest length " << wire->getRestLength() << " m, on the drum "
                         << winch->getPulledInLength() << " m, lowest load " << lowest << " m, tension "
                         << wire->getTension(S(0)) << " N");
    if (!autoFeed) {
      CHECK(wire->getRoute().size() == 3);
      CHECK(lowest < -1.0);  // the load falls through the slack
      continue;
    }
    // Taut from the start: the slack is on the drum, the load holds within
    // the stretch under the wire's own weight (~0.1 mm), and the wire's top
    // segment carries the load and the wire below it (measured: 0.5% under
    // the weight of all but its top half segment, which hangs on the winch).
    CHECK(wire->getRoute().size() == 2);
    CHECK(double(winch->getPulledInLength()) == doctest::Approx(pulledIn + routed - straight).epsilon(1e-6));
    CHECK(double(winch->getPulledInLength()) + double(wire->getRestLength()) ==
          doctest::Approx(total).epsilon(std::is_same_v<S, double> ? 1e-12 : 1e-6));
    CHECK(lowest > -0.5e-3 - mass * kStandardGravity * straight / (6e10 * std::numbers::pi * 1e-4));
    const double weight = (mass + density * std::numbers::pi * 1e-4 * (straight - 0.25)) * kStandardGravity;
    CHECK(double(wire->getTension(S(0))) == doctest::Approx(weight).epsilon(0.01));
    for (const auto& p : wire->getPoints()) CHECK(std::abs(double(p.x())) < 1e-3);
  }
}

TEST_CASE("auto-feeding winches share the slack, leave a free end alone and refuse what they cannot feed") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  // Two auto-feeding winches 10 m apart on the world, routed 2 m above the
  // line between them: each takes in half of the slack.
  ref_ptr<Simulation> sim = new Simulation();
  sim->setUniformGravity(Vec3::Zero());
  ref_ptr<WireWinchController> left = new WireWinchController(nullptr, Vec3(0, 0, 0), Vec3(1, 0, 0));
  ref_ptr<WireWinchController> right = new WireWinchController(nullptr, Vec3(10, 0, 0), Vec3(-1, 0, 0));
  left->setEnableAutoFeed(true);
  right->setEnableAutoFeed(true);
  ref_ptr<Wire> span = new Wire(0.01, 2.0);
  span->add(left, 5.0);
  span->add(new FreeNode(5, 0, 2));
  span->add(right, 5.0);
  sim->add(span);
  const double slack = 2.0 * std::sqrt(29.0) - 10.0;
  CHECK(left->getPulledInLength() == doctest::Approx(5.0 + slack / 2).epsilon(1e-12));
  CHECK(right->getPulledInLength() == doctest::Approx(5.0 + slack / 2).epsilon(1e-12));
  CHECK(span->getRestLength() == doctest::Approx(10.0).epsilon(1e-12));
  CHECK(message([&] { left->setEnableAutoFeed(false); }).find("in one already") != std::string::npos);

  // A free end: nothing pulls against the winch; the route stays.
  ref_ptr<WireWinchController> hoist = new WireWinchController(nullptr, Vec3(0, 5, 10), Vec3(0, 0, -1));
  hoist->setEnableAutoFeed(true);
  ref_ptr<Wire> hanging = new Wire(0.01, 2.0);
  hanging->add(hoist, 5.0);
  hanging->add(new FreeNode(2, 5, 6));
  hanging->add(new FreeNode(0, 5, 2));
  sim->add(hanging);
  CHECK(hanging->getRoute().size() == 3);
  CHECK(hoist->getPulledInLength() == 5.0);

  // Routed out and back to the winch's own point: the taut route would
  // have its two ends coincide. Refused, the wire as routed, nothing added.
  ref_ptr<WireWinchController> loop = new WireWinchController(nullptr, Vec3(0, -5, 0), Vec3(1, 0, 0));
  loop->setEnableAutoFeed(true);
  ref_ptr<Wire> back = new Wire(0.01, 2.0);
  back->setName("loop");
  back->add(loop, 5.0);
  back->add(new FreeNode(3, -5, 0));
  back->add(new BodyFixedNode(nullptr, Vec3(0, -5, 0)));
  const std::size_t producers = sim->getRowProducers().size();
  CHECK(message([&] { sim->add(back); }).find("'loop': consecutive route nodes coincide") != std::string::npos);
  CHECK(sim->getRowProducers().size() == producers);
  CHECK(back->getRoute().size() == 3);
  CHECK(loop->getPulledInLength() == 5.0);
  loop->setEnableAutoFeed(false);
  sim->add(back);
  CHECK(back->getRestLength() == doctest::Approx(6.0).epsilon(1e-12));
}

TEST_CASE("a winch refuses bad input by name and leaves the simulation unchanged") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  ref_ptr<WireWinchController> winch = new WireWinchController(nullptr, Vec3(0, 0, 1), Vec3(0, 0, -1));
  winch->setName("drum");
  CHECK(message([&] { winch->setSpeed(std::nan("")); }).find("'drum': speed must be finite") != std::string::npos);
  CHECK(message([&] { winch->setSpeed(INFINITY); }).find("inf") != std::string::npos);
  CHECK(message([&] { winch->setForceRange(-INFINITY, 10.0); }).find("lower must be finite") != std::string::npos);
  CHECK(message([&] { winch->setForceRange(-10.0, std::nan("")); }).find("upper must be finite") != std::string::npos);
  CHECK(message([&] { winch->setForceRange(5.0, 10.0); }).find("got 5") != std::string::npos);
  CHECK(message([&] { winch->setBrakeForceRange(-1.0); }).find("brake force range") != std::string::npos);
  CHECK(winch->getSpeed() == 0.0);
  CHECK(winch->getForceRangeLower() == 0.0);
  CHECK(message([] { ref_ptr<WireWinchController> w = new WireWinchController(nullptr, Vec3::Zero(), Vec3::Zero()); })
            .find("direction") != std::string::npos);

  ref_ptr<Wire> wire = new Wire(0.01, 2.0);
  wire->setName("w");
  CHECK(message([&] { wire->add(winch, -1.0); }).find("'w': pulled-in length must be finite and >= 0 m, got -1") !=
        std::string::npos);
  CHECK(message([&] { wire->add(ref_ptr<WireWinchController>(), 1.0); }).find("null winch") != std::string::npos);
  CHECK(wire->getRoute().empty());
  wire->add(winch, 5.0);
  CHECK(wire->getWinch(true) == winch.get());
  ref_ptr<Wire> other = new Wire(0.01, 2.0);
  CHECK(message([&] { other->add(winch, 1.0); }).find("already routed") != std::string::npos);
  wire->add(new FreeNode(0, 0, -1));
  ref_ptr<WireWinchController> end = new WireWinchController(nullptr, Vec3(0, 0, -2), Vec3(0, 0, 1));
  wire->add(end, 1.0);
  CHECK(message([&] { wire->add(new FreeNode(0, 0, -3)); }).find("ends at a winch") != std::string::npos);

  // A winch on a body that is not in the simulation: refused, nothing added.
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> crane = new RigidBody();
  crane->setName("crane");
  ref_ptr<Wire> away = new Wire(0.01, 2.0);
  away->setName("w");
  away->add(new WireWinchController(crane.get(), Vec3::Zero(), Vec3(0, 0, -1)), 1.0);
  away->add(new FreeNode(0, 0, -1));
  CHECK(message([&] { sim->add(away); }).find("crane") != std::string::npos);
  CHECK(sim->getRowProducers().empty());
  CHECK(sim->getBodyStores().empty());
  // Two winches and one segment between them.
  ref_ptr<Wire> bare = new Wire(0.01, 2.0);
  bare->setName("w");
  bare->add(new WireWinchController(nullptr, Vec3::Zero(), Vec3(0, 0, -1)), 1.0);
  bare->add(new WireWinchController(nullptr, Vec3(0, 0, -0.4), Vec3(0, 0, 1)), 1.0);
  CHECK(message([&] { sim->add(bare); }).find("two segments between its two winches") != std::string::npos);
  CHECK(sim->getRowProducers().empty());
}
