// Links (WireLink, agxWire's Link): a body connecting the ends of wires
// through ConnectingNodes whose bend and twist stiffness are the
// connection's properties. The tension through a hook block, a torsion
// pendulum against the wire's G·J/L, the bend across a link between a pin
// and a clamp, operations and bad input.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

#include <spook/spook.hpp>

#include "error_message.hpp"

using namespace spook;

namespace {

constexpr double kLinkGravity = 9.80665;  // m/s², the simulation's default

/// A wire from the world down to a link body (a 0.4 × 0.4 × 0.2 m block of
/// `linkMass`, its connection 0.1 m above its center of mass), and, with a
/// load, a second wire from 0.1 m below it down to a load body.
template <Scalar S>
struct HookBlock {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> block = new RigidBodyT<S>(), load = new RigidBodyT<S>();
  ref_ptr<WireLinkT<S>> link = new WireLinkT<S>(block.get());
  ref_ptr<WireT<S>> upper = new WireT<S>(S(0.005), S(2)), lower = new WireT<S>(S(0.005), S(2));
  double inertiaAboutWire = 0.0;

  HookBlock(double linkMass, double loadMass) {
    block->getMassProperties()->setMass(S(linkMass));
    inertiaAboutWire = linkMass * (0.4 * 0.4 + 0.4 * 0.4) / 12.0;
    const double across = linkMass * (0.4 * 0.4 + 0.2 * 0.2) / 12.0;
    block->getMassProperties()->setInertiaTensor(
        Vec3(S(across), S(across), S(inertiaAboutWire)).asDiagonal().toDenseMatrix());
    sim->add(block);
    upper->setName("upper");
    upper->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(0), S(0), S(10.1))));
    upper->add(link, Vec3(S(0), S(0), S(0.1)));
    sim->add(upper);
    if (loadMass > 0.0) {
      load->getMassProperties()->setMass(S(loadMass));
      load->setPosition(S(0), S(0), S(-5.1));
      sim->add(load);
      lower->setName("lower");
      lower->add(link, Vec3(S(0), S(0), S(-0.1)));
      lower->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
      sim->add(lower);
    }
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a hook block (link) carries the tension from one wire to the next", S, double, float) {
  // 200 kg load under a 20 kg link, both on 5 mm steel wire: the lower
  // wire's tension at the link is the load's weight and its own, the upper
  // wire's at the link that and the link's.
  HookBlock<S> rig(20.0, 200.0);
  for (int s = 0; s < 300; ++s) rig.sim->stepForward();
  const double lowerWire = double(rig.lower->getMass()), g = kLinkGravity;
  const double lowerTension = double(rig.lower->getTension(S(0)));
  const double upperTension = double(rig.upper->getTension(rig.upper->getRestLength()));
  MESSAGE("lower wire at the link " << lowerTension << " N (load and wire " << (200.0 + lowerWire) * g
                                    << "), upper " << upperTension << " N (" << (220.0 + lowerWire) * g << ")");
  CHECK(lowerTension == doctest::Approx((200.0 + lowerWire) * g).epsilon(0.005));
  CHECK(upperTension == doctest::Approx((220.0 + lowerWire) * g).epsilon(0.005));
  // The block hangs level under its connection, the load under it.
  CHECK(std::abs(double(rig.block->getPosition().x())) < 1e-4);
  CHECK(std::abs(double(rig.load->getPosition().x())) < 1e-4);
  CHECK(double(rig.load->getPosition().z()) < double(rig.block->getPosition().z()) - 4.9);
}

TEST_CASE_TEMPLATE("a link twisted about its wire swings as a torsion pendulum against G J / L", S, double, float) {
  // The block spun about the wire at 0.5 rad/s: with twist stiffness G the
  // wire resists by k = G J/L (J = πr⁴/2, L = 10 m) and the wire's bend
  // damping τ (SPOOK: a viscous b = k τ, ζ = ωτ/2), so the block turns as a
  // damped torsion pendulum, ω = √(k/I), ω_d = ω√(1 − ζ²), its first swing
  // reaching (0.5/ω) e^{−ζ ω t₁} at ω_d t₁ = atan(√(1 − ζ²)/ζ). Without it,
  // the block spins on.
  const double shear = 8e10, radius = 0.005, length = 10.0, tau = 0.02;
  const double torsion = shear * std::numbers::pi * std::pow(radius, 4) / 2.0 / length;
  for (const bool held : {true, false}) {
    CAPTURE(held);
    HookBlock<S> rig(20.0, 0.0);
    rig.upper->getMaterial()->getWireMaterial()->setDampingBend(S(tau));
    ConnectingNodeT<S>* connection = rig.link->getConnectionProperties(*rig.upper);
    REQUIRE(connection != nullptr);
    CHECK(connection->getLink() == rig.link.get());
    CHECK(connection->getBendStiffness() == S(0));
    if (held) connection->setTwistStiffness(S(shear));
    const double omega = std::sqrt(torsion / rig.inertiaAboutWire), zeta = omega * tau / 2.0;
    const double damped = omega * std::sqrt(1.0 - zeta * zeta);
    const double firstPeak = std::atan(std::sqrt(1.0 - zeta * zeta) / zeta) / damped;
    const double reach = 0.5 / omega * std::exp(-zeta * omega * firstPeak);
    const double h = double(rig.sim->getTimeStep());
    rig.block->setAngularVelocity(S(0), S(0), S(0.5));
    // Upward crossings of the twist (rad) after the start: the period.
    double previous = 0.0, first = -1.0, last = -1.0, amplitude = 0.0;
    int crossings = 0;
    const int steps = int(std::ceil(4.0 * 2.0 * std::numbers::pi / omega / h));
    for (int s = 1; s <= steps; ++s) {
      rig.sim->stepForward();
      const double twist = double(connection->getTwistAngle());
      amplitude = std::max(amplitude, std::abs(twist));
      if (s > 1 && previous < 0.0 && twist >= 0.0) {
        const double at = (s - 1 + previous / (previous - twist)) * h;
        if (first < 0.0) first = at;
        last = at;
        ++crossings;
      }
      previous = twist;
    }
    const double spin = double(rig.block->getAngularVelocity().z());
    MESSAGE("twist held: " << held << "; " << crossings << " upward crossings, period "
                           << (crossings > 1 ? (last - first) / (crossings - 1) : 0.0) << " s against "
                           << 2.0 * std::numbers::pi / damped << ", first swing " << amplitude << " rad against "
                           << reach << ", spin at the end " << spin << " rad/s");
    if (held) {
      REQUIRE(crossings >= 3);
      CHECK((last - first) / (crossings - 1) == doctest::Approx(2.0 * std::numbers::pi / damped).epsilon(0.005));
      CHECK(amplitude == doctest::Approx(reach).epsilon(0.01));
    } else {
      CHECK(crossings == 0);
      CHECK(spin == doctest::Approx(0.5).epsilon(0.01));
      CHECK(double(connection->getTwistAngle()) == doctest::Approx(0.5 * steps * h).epsilon(0.01));
    }
  }
}

TEST_CASE_TEMPLATE("a link's bend stiffness takes a pipe from a pin to the cantilever's clamp", S, double, float) {
  // 5 m of solid steel rod (radius 5 cm, E = 2e11 Pa, 4 nodes per meter)
  // clamped level through a link on a static block. At the wire's modulus
  // (or above it: capped) the tip sinks by w L⁴/(8 E I). At a share s of
  // it the connection's bend compliance (l/2)/(s E I) (l = 0.25 m, the
  // segment) exceeds the clamp's by (l/2)(1/s − 1)/(E I), which turns the
  // root under the moment w L²/2 and adds w L³ l (1/s − 1)/(4 E I) at the
  // tip; at 0 the link is a pin and the rod hangs down.
  using Vec3 = Vec3T<S>;
  const double radius = 0.05, length = 5.0, density = 7800.0, modulus = 2e11, segment = 0.25;
  const double w = density * std::numbers::pi * radius * radius * kLinkGravity;
  const double EI = modulus * std::numbers::pi * std::pow(radius, 4) / 4.0;
  const double clamped = w * std::pow(length, 4) / (8.0 * EI);
  for (const double share : {1.0, 2.0, 0.5, 0.0}) {
    CAPTURE(share);
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<RigidBodyT<S>> block = new RigidBodyT<S>();
    block->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
    sim->add(block);
    ref_ptr<WireLinkT<S>> link = new WireLinkT<S>(block.get());
    ref_ptr<WireT<S>> pipe = new WireT<S>(S(radius), S(4));
    pipe->getMaterial()->getBulkMaterial()->setDensity(S(density));
    pipe->getMaterial()->getWireMaterial()->setYoungsModulusStretch(S(modulus));
    pipe->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(modulus));
    pipe->add(link, Vec3(S(0.5), S(0), S(0)));
    pipe->add(new FreeNodeT<S>(Vec3(S(0.5 + length), S(0), S(0))));
    link->getConnectionProperties(*pipe)->setBendStiffness(S(share * modulus));
    sim->add(pipe);
    double sum = 0.0, lowest = 0.0;
    int samples = 0;
    for (int s = 0; s < 240; ++s) {
      sim->stepForward();
      const double tip = double(pipe->getPoints().back().z());
      lowest = std::min(lowest, tip);
      if (s >= 180) {
        sum += tip;
        ++samples;
      }
    }
    const double mean = -sum / samples;
    const double expected =
        share >= 1.0 ? clamped : clamped + w * std::pow(length, 3) * segment * (1.0 / share - 1.0) / (4.0 * EI);
    MESSAGE("bend stiffness " << share << " of the wire's: the tip sinks " << mean << " m on average ("
                              << -lowest << " at most); expected " << (share > 0.0 ? expected : 1.0));
    if (share > 0.0)
      CHECK(mean == doctest::Approx(expected).epsilon(0.01));
    else
      CHECK(-lowest > 1.0);
  }
}

TEST_CASE("a link's connections follow the wire through reverse, detach and attach") {
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> block = new RigidBody();
  sim->add(block);
  ref_ptr<WireLink> link = new WireLink(block.get());
  ref_ptr<Wire> wire = new Wire(0.01, 2.0);
  wire->add(link, Vec3(0, 0, 0.1));
  wire->add(new FreeNode(0, 0, 3));
  sim->add(wire);
  ConnectingNode* connection = link->getConnectionProperties(*wire);
  REQUIRE(connection != nullptr);
  connection->setTwistStiffness(1e9);
  wire->reverse();
  CHECK(link->getConnectionProperties(*wire) == connection);
  wire->detach(false);
  CHECK(link->getConnectionProperties(*wire) == nullptr);
  wire->attach(link, Vec3(0, 0, 0.1), false);
  REQUIRE(link->getConnectionProperties(*wire) != nullptr);
  CHECK(link->getConnectionProperties(*wire)->getTwistStiffness() == 0.0);
  for (int s = 0; s < 10; ++s) sim->stepForward();
  CHECK(block->getPosition().allFinite());
}

TEST_CASE("links and connection properties refuse bad input by name, leaving the simulation unchanged") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  CHECK(message([] { ref_ptr<WireLink> l = new WireLink(nullptr); }).find("WireLink") != std::string::npos);
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> block = new RigidBody();
  sim->add(block);
  ref_ptr<WireLink> link = new WireLink(block.get());
  ref_ptr<Wire> wire = new Wire(0.01, 2.0);
  wire->setName("sling");
  CHECK(message([&] { wire->add(ref_ptr<WireLink>(), Vec3(0, 0, 0)); }).find("'sling'") != std::string::npos);
  CHECK(wire->getRoute().empty());
  CHECK(message([&] { wire->add(link, Vec3(0, std::nan(""), 0)); }).find("ConnectingNode") != std::string::npos);
  CHECK(wire->getRoute().empty());
  CHECK(link->getConnectionProperties(*wire) == nullptr);
  wire->add(link, Vec3(0, 0, 0));  // at the center of mass: a pin is fine
  wire->add(new FreeNode(0, 0, 2));
  ConnectingNode* connection = link->getConnectionProperties(*wire);
  REQUIRE(connection != nullptr);
  CHECK(message([&] { connection->setBendStiffness(-1.0); }).find("bend stiffness must be finite and >= 0 Pa, got -1") !=
        std::string::npos);
  CHECK(message([&] { connection->setTwistStiffness(INFINITY); }).find("twist stiffness") != std::string::npos);
  CHECK(connection->getTwistStiffness() == 0.0);
  // Holding the bend needs the socket off the center of mass.
  connection->setBendStiffness(1e9);
  const std::string what = message([&] { sim->add(wire); });
  CHECK(what.find("'sling'") != std::string::npos);
  CHECK(what.find("away from its body's center of mass") != std::string::npos);
  CHECK(sim->getRowProducers().empty());
  connection->setBendStiffness(0.0);
  sim->add(wire);
  CHECK(sim->getRowProducers().size() == 1);
  CHECK(message([&] { wire->attach(ref_ptr<WireLink>(), Vec3(0, 0, 0), false); }).find("null link") !=
        std::string::npos);
}
