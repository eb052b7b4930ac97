// Wires through eyes (EyeNode): the capstan law over the angle the wire is
// deflected by, with a coefficient for each direction it slides in, and a
// ring on a taut wire that slides to where both sides make one angle with
// the vertical (the clothesline problem); bad input to eye and connecting
// nodes and a capstan's turns.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "error_message.hpp"

using namespace spook;

namespace {

constexpr double kEyeGravity = 9.80665;  // m/s², the simulation's default

/// A light limp wire (radius 5 mm, 100 kg/m³, 5 nodes/m) from a first load
/// up through an eye fixed to the world at the origin and down to a second
/// load, both 5 m below and 1 cm to either side.
template <Scalar S>
struct ThroughEye {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> first = new RigidBodyT<S>(), second = new RigidBodyT<S>();
  ref_ptr<EyeNodeT<S>> eye = new EyeNodeT<S>(nullptr, Vec3::Zero());
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));

  ThroughEye(double firstMass, double secondMass) {
    first->getMassProperties()->setMass(S(firstMass));
    first->setPosition(S(-0.01), S(0), S(-5));
    second->getMassProperties()->setMass(S(secondMass));
    second->setPosition(S(0.01), S(0), S(-5));
    sim->add(first);
    sim->add(second);
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    wire->add(new BodyFixedNodeT<S>(first.get(), Vec3::Zero()));
    wire->add(eye);
    wire->add(new BodyFixedNodeT<S>(second.get(), Vec3::Zero()));
  }
};

}  // namespace

TEST_CASE_TEMPLATE("an eye holds the wire within e^(mu theta) in each direction and lets it slide beyond", S, double,
                   float) {
  using Direction = typename SlidingNodeT<S>::Direction;
  const double forward = 0.2, backward = 0.4;
  const double theta = std::numbers::pi - 2.0 * std::atan(0.01 / 5.0);
  // Forward: the second load, at the wire's end, is the heavier one.
  for (const bool heavyAtEnd : {true, false}) {
    const double mu = heavyAtEnd ? forward : backward, ratio = std::exp(mu * theta), light = 10.0;
    for (const double share : {0.98, 1.02}) {
      CAPTURE(heavyAtEnd);
      CAPTURE(share);
      const double heavy = share * ratio * light;
      ThroughEye<S> rig(heavyAtEnd ? light : heavy, heavyAtEnd ? heavy : light);
      rig.eye->setFrictionCoefficient(S(forward), Direction::FORWARD);
      rig.eye->setFrictionCoefficient(S(backward), Direction::BACKWARD);
      rig.sim->add(rig.wire);
      CHECK(double(rig.eye->getWrapAngle()) == doctest::Approx(theta).epsilon(1e-6));
      for (int s = 0; s < 60; ++s) rig.sim->stepForward();
      RigidBodyT<S>& load = heavyAtEnd ? *rig.second : *rig.first;
      const double drop = -5.0 - double(load.getPosition().z()), speed = -double(load.getVelocity().z());
      const double length = double(rig.wire->getRestLength());
      const double before = double(rig.wire->getTension(S(0.1)));
      const double after = double(rig.wire->getTension(S(length - 0.1)));
      const double high = heavyAtEnd ? after : before, low = heavyAtEnd ? before : after;
      MESSAGE("sliding " << std::string(heavyAtEnd ? "forward" : "backward") << ", load " << share
                         << " e^(mu theta) x the light one: drop " << drop << " m in 1 s at " << speed
                         << " m/s, tensions " << high << " N and " << low << " N (ratio " << high / low
                         << " against " << ratio << "), friction " << rig.eye->getFrictionForce() << " N");
      if (share < 1.0) {
        CHECK(std::abs(drop) < 5e-3);
        CHECK(std::abs(speed) < 1e-3);
        CHECK(high == doctest::Approx(heavy * kEyeGravity).epsilon(0.01));
        CHECK(low == doctest::Approx(light * kEyeGravity).epsilon(0.01));
      } else {
        CHECK(drop > 0.01);
        CHECK(speed > 0.05);
        CHECK(high / low == doctest::Approx(ratio).epsilon(0.02));
      }
      // The friction force is the tension before the eye less the one after.
      CHECK(double(rig.eye->getFrictionForce()) == doctest::Approx(before - after).epsilon(0.02));
    }
  }
}

TEST_CASE_TEMPLATE("a ring slides along a taut wire to where both sides make one angle with the vertical", S, double,
                   float) {
  using Vec3 = Vec3T<S>;
  // A wire from the world at A = (0, 0, 0) to B = (4, 0, −1) runs through an
  // eye on a 10 kg ring released at (1, 0, −2): the wire's length L is
  // |AP| + |PB| there. Without friction the ring comes to rest where both
  // sides make the angle α with the vertical, sin α = S/L (S = 4 m the
  // span), on the ellipse with foci A and B: its distance along the wire
  // from A is L₁ = (L + Δz/cos α)/2, Δz = z_A − z_B.
  const Vec3 a(S(0), S(0), S(0)), b(S(4), S(0), S(-1)), start(S(1), S(0), S(-2));
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> ring = new RigidBodyT<S>();
  ring->getMassProperties()->setMass(S(10));
  ring->setPosition(start);
  ring->setLinearVelocityDamping(S(2));  // settles it
  sim->add(ring);
  ref_ptr<EyeNodeT<S>> eye = new EyeNodeT<S>(ring.get(), Vec3::Zero());
  eye->setFrictionCoefficient(S(0));
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
  wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
  wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
  wire->add(new BodyFixedNodeT<S>(nullptr, a));
  wire->add(eye);
  wire->add(new BodyFixedNodeT<S>(nullptr, b));
  sim->add(wire);
  const double length = double(wire->getRestLength());
  CHECK(length == doctest::Approx(std::sqrt(5.0) + std::sqrt(10.0)).epsilon(1e-6));
  for (int s = 0; s < 600; ++s) sim->stepForward();
  const double sine = 4.0 / length, cosine = std::sqrt(1.0 - sine * sine);
  const double along = 0.5 * (length + 1.0 / cosine);
  const double x = along * sine, z = -along * cosine;
  const Vec3 at = ring->getPosition();
  const double tension = 10.0 * kEyeGravity / (2.0 * cosine);
  MESSAGE("ring at (" << at.x() << ", " << at.z() << ") against (" << x << ", " << z << "), speed "
                      << ring->getVelocity().norm() << " m/s, tensions " << wire->getTension(S(0.1)) << " and "
                      << wire->getTension(S(length - 0.1)) << " N against " << tension << " N, wrap "
                      << eye->getWrapAngle() << ", " << wire->getNumMassNodes() << " nodes");
  // The wire's own weight (42 g against the ring's 10 kg) sags it by a few mm.
  CHECK(std::abs(double(at.x()) - x) < 5e-3);
  CHECK(std::abs(double(at.z()) - z) < 5e-3);
  CHECK(double(ring->getVelocity().norm()) < 1e-3);
  CHECK(double(wire->getTension(S(0.1))) == doctest::Approx(tension).epsilon(0.01));
  CHECK(double(wire->getTension(S(length - 0.1))) == doctest::Approx(tension).epsilon(0.01));
  CHECK(double(eye->getWrapAngle()) == doctest::Approx(std::numbers::pi - 2.0 * std::acos(cosine)).epsilon(0.01));
  // 1.2 m of wire went through the eye; none was made or lost.
  CHECK(double(wire->getRestLength()) == doctest::Approx(length).epsilon(1e-9));
  CHECK(wire->getNumMassNodes() < 40);
}

TEST_CASE("eye and connecting nodes and a capstan's turns refuse bad input by name, leaving the simulation unchanged") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  ref_ptr<EyeNode> eye = new EyeNode(nullptr, Vec3(0, 0, 0));
  CHECK(message([&] { eye->setFrictionCoefficient(-0.1); }).find("EyeNode") != std::string::npos);
  CHECK(message([&] { eye->setFrictionCoefficient(std::nan(""), EyeNode::Direction::BACKWARD); }).find("nan") !=
        std::string::npos);
  CHECK_FALSE(eye->hasFrictionCoefficient(EyeNode::Direction::BACKWARD));
  CHECK(message([] { ref_ptr<EyeNode> e = new EyeNode(nullptr, Vec3(0, std::nan(""), 0)); }).find("EyeNode") !=
        std::string::npos);
  ref_ptr<GeometryT<double>> drum = new Geometry(new Cylinder(0.5, 0.2));
  ref_ptr<ContactNode> capstan = new ContactNode(drum.get(), Vec3(0.5, 0, 0));
  CHECK(message([&] { capstan->setTurns(-1); }).find("turns must be within 0 and 1000, got -1") != std::string::npos);
  CHECK(capstan->getTurns() == 0);
  for (const bool first : {true, false}) {
    CAPTURE(first);
    ref_ptr<Simulation> sim = new Simulation();
    ref_ptr<Wire> wire = new Wire(0.01, 2.0);
    wire->setName("line");
    if (first) wire->add(eye);
    wire->add(new BodyFixedNode(nullptr, Vec3(1, 0, 0)));
    wire->add(new FreeNode(2, 0, 0));
    if (!first) wire->add(eye);
    const std::string what = message([&] { sim->add(wire); });
    CAPTURE(what);
    CHECK(what.find("'line'") != std::string::npos);
    CHECK(what.find("an EyeNode may not be the first or last route node") != std::string::npos);
    CHECK(sim->getRowProducers().empty());
    CHECK(wire->getNumMassNodes() == 0);
  }
  // A ConnectingNode needs a body, an end of the route, and a socket away
  // from the body's center of mass.
  CHECK(message([] { ref_ptr<ConnectingNode> c = new ConnectingNode(nullptr, Vec3(1, 0, 0)); })
            .find("ConnectingNode") != std::string::npos);
  ref_ptr<Simulation> sim = new Simulation();
  ref_ptr<RigidBody> block = new RigidBody();
  sim->add(block);
  const auto refused = [&](const std::vector<ref_ptr<WireNode>>& route, const char* expected) {
    ref_ptr<Wire> wire = new Wire(0.01, 2.0);
    wire->setName("pipe");
    for (const auto& node : route) wire->add(node);
    const std::string what = message([&] { sim->add(wire); });
    CAPTURE(what);
    CHECK(what.find("'pipe'") != std::string::npos);
    CHECK(what.find(expected) != std::string::npos);
    CHECK(sim->getRowProducers().empty());
  };
  refused({new FreeNode(-1, 0, 0), new ConnectingNode(block, Vec3(1, 0, 0)), new FreeNode(2, 0, 0)},
          "a ConnectingNode may only be the first or last route node; it is node, got 1");
  refused({new ConnectingNode(block, Vec3(0, 0, 0)), new FreeNode(2, 0, 0)},
          "a ConnectingNode that holds the bend must be away from its body's center of mass");
}
