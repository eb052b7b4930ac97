// A wire's own contacts with geometries (wire/wire_geometry_contacts.hpp):
// no ContactNode routed, the segments collide as capsules. A wire dropped
// across a box comes to rest on it and over its edges without a segment
// passing through them, the box carrying its weight; a wire over a
// cylinder holds a load against a counterweight below the capstan ratio
// e^{μθ} and slips above it; collisions can be switched off per wire and
// per geometry (they are off by default).

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <spook/spook.hpp>

#include "error_message.hpp"
#include "tolerance.hpp"

using namespace spook;

namespace {

constexpr double kDrapeGravity = 9.80665;  // m/s², the simulation's default

/// Distance (m) from p to the box of half extents `half` centered at the origin (0 inside).
double outsideBox(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  return (p.cwiseAbs() - half).cwiseMax(0.0).norm();
}

/// A 4 m limp wire (radius 1 cm, steel, 10 nodes/m) held level 0.3 m above
/// a static box 1 × 1 × 1 m centered at the origin, free at both ends
/// (colliding with it by default).
template <Scalar S>
struct DropOnBox {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> holder = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> box = new GeometryT<S>(new BoxT<S>(Vec3(S(0.5), S(0.5), S(0.5))));
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.01), S(10));

  DropOnBox() {
    holder->add(box);
    holder->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
    sim->add(holder);
    wire->setName("drape");
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    wire->add(new FreeNodeT<S>(S(-2), S(0.1), S(0.8)));
    wire->add(new FreeNodeT<S>(S(2), S(0.1), S(0.8)));
    sim->add(wire);
  }
};

/// Two loads (kg) on a light limp wire (radius 5 mm, 100 kg/m³, 5 nodes/m)
/// routed with free points over the top of a static cylinder of radius 0.5
/// m (axis along y): the wire wraps it by π through its own contacts, the
/// first load 3 m below x = +0.5, the second below x = −0.5.
template <Scalar S>
struct OverCylinderByContact {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> right = new RigidBodyT<S>(), left = new RigidBodyT<S>(), holder = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> cylinder = new GeometryT<S>(new CylinderT<S>(S(0.5), S(0.2)));
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));

  OverCylinderByContact(double rightMass, double leftMass, double mu) {
    holder->add(cylinder);
    holder->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
    sim->add(holder);
    right->getMassProperties()->setMass(S(rightMass));
    right->setPosition(S(0.5), S(0), S(-3));
    left->getMassProperties()->setMass(S(leftMass));
    left->setPosition(S(-0.5), S(0), S(-3));
    sim->add(right);
    sim->add(left);
    wire->setName("rope");
    wire->setEnableCollisions(true);
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(S(mu));
    wire->add(new BodyFixedNodeT<S>(right.get(), Vec3::Zero()));
    const double radius = 0.5 + 0.005;
    for (int i = 0; i <= 12; ++i) {
      const double angle = std::numbers::pi * i / 12.0;
      wire->add(new FreeNodeT<S>(S(radius * std::cos(angle)), S(0), S(radius * std::sin(angle))));
    }
    wire->add(new BodyFixedNodeT<S>(left.get(), Vec3::Zero()));
    sim->add(wire);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a wire dropped across a box rests on it and over its edges", S, double, float) {
  DropOnBox<S> rig;
  const double mass = double(rig.wire->getMass());
  // What the box carries over the last second (the wire still sways a little).
  double up = 0.0;
  for (int s = 0; s < 300; ++s) {
    rig.sim->stepForward();
    if (s < 240) continue;
    for (const auto& c : rig.wire->getGeometryContacts()) {
      CHECK(c.geometry == rig.box.get());
      up -= double(c.force.z()) / 60.0;
    }
  }
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  // Every point of every straight piece stays outside the box by the radius,
  // less what the contacts' compliance lets in: no segment cuts an edge.
  double deepest = 0.0;
  const auto points = rig.wire->getPoints();
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    for (int i = 0; i <= 20; ++i) {
      const Eigen::Vector3d p = (points[k] + (points[k + 1] - points[k]) * S(i / 20.0)).template cast<double>();
      deepest = std::max(deepest, 0.01 - outsideBox(p, half));
    }
  // The ends hang over the sides: the lowest point below the box's top.
  double lowest = 1e9;
  for (const auto& p : points) lowest = std::min(lowest, double(p.z()));
  MESSAGE("after 5 s: " << rig.wire->getGeometryContacts().size() << " contacts; the box carried " << up
                        << " N over the last second, the wire's weight " << mass * kDrapeGravity << " N, deepest "
                        << deepest * 1e3 << " mm into the box, lowest point " << lowest << " m, "
                        << rig.wire->getNumMassNodes() << " nodes");
  CHECK(deepest < 2e-3);
  CHECK(lowest < 0.0);
  // Resting: the box carries the whole wire.
  CHECK(up == doctest::Approx(mass * kDrapeGravity).epsilon(0.01));
}

TEST_CASE_TEMPLATE("a wire over a cylinder by its own contacts holds below the capstan ratio and slips above",
                   S, double, float) {
  const double mu = 0.3, counterweight = 10.0, ratio = std::exp(mu * std::numbers::pi);
  for (const double share : {0.9, 1.1}) {
    CAPTURE(share);
    OverCylinderByContact<S> rig(share * ratio * counterweight, counterweight, mu);
    const double length = double(rig.wire->getRestLength());
    for (int s = 0; s < 120; ++s) rig.sim->stepForward();
    const double drop = -3.0 - double(rig.right->getPosition().z());
    const double high = double(rig.wire->getTension(S(0.05))), low = double(rig.wire->getTension(S(length - 0.05)));
    MESSAGE("load " << share << " e^(mu pi) x the counterweight: drop " << drop << " m in 2 s, tensions " << high
                    << " N and " << low << " N (ratio " << high / low << ", e^(mu pi) " << ratio << ")");
    if (share < 1.0) {
      CHECK(std::abs(drop) < 2e-3);
      CHECK(high == doctest::Approx(share * ratio * counterweight * kDrapeGravity).epsilon(0.01));
      CHECK(low == doctest::Approx(counterweight * kDrapeGravity).epsilon(0.01));
    } else {
      // Slipping: the capstan Atwood machine's acceleration
      // (m₁ − m₂e^{μθ})g/(m₁ + m₂e^{μθ}) over 2 s would drop it
      // 2·a m (0.93 m); the wire's polygon over the cylinder slips more
      // slowly, by stick-slip over its nodes' corners, and how far depends
      // on round-off: 0.72 m (float); 0.72 m (double) with the segments'
      // capsules placed by Eigen's FromTwoVectors, 0.47 m with
      // detail::shortestArc, whose rotations differ from it by at most
      // 4e-10. A quarter of the capstan's drop still tells slip from hold
      // (< 2 mm) by 100x.
      const double m1 = share * ratio * counterweight, m2 = counterweight;
      const double a = (m1 - m2 * ratio) * kDrapeGravity / (m1 + m2 * ratio);
      CHECK(drop > 0.25 * 0.5 * a * 4.0);
    }
  }
}

TEST_CASE("a wire's collisions switch off for the wire and for one geometry") {
  CHECK(ref_ptr<Wire>(new Wire(0.01, 10.0))->getEnableCollisions());  // on by default, as agxWire's
  DropOnBox<double> rig;
  CHECK(rig.wire->getEnableCollisions());
  CHECK(rig.wire->getEnableCollisions(rig.box.get()));
  rig.wire->setEnableCollisions(rig.box.get(), false);
  CHECK_FALSE(rig.wire->getEnableCollisions(rig.box.get()));
  for (int s = 0; s < 60; ++s) rig.sim->stepForward();
  CHECK(rig.wire->getGeometryContacts().empty());
  for (const auto& p : rig.wire->getPoints()) CHECK(p.z() < 0.0);  // fell through the box

  DropOnBox<double> off;
  off.wire->setEnableCollisions(false);
  for (int s = 0; s < 60; ++s) off.sim->stepForward();
  CHECK(off.wire->getGeometryContacts().empty());
  for (const auto& p : off.wire->getPoints()) CHECK(p.z() < 0.0);

  // A cut's second half keeps the settings.
  DropOnBox<double> halves;
  halves.wire->setEnableCollisions(halves.box.get(), false);
  halves.sim->stepForward();
  const ref_ptr<Wire> second = halves.wire->cut(2.0);
  CHECK(second->getEnableCollisions());
  CHECK_FALSE(second->getEnableCollisions(halves.box.get()));

  const std::string message = test::errorMessage([&] { rig.wire->setEnableCollisions(nullptr, false); });
  CHECK(message.find("drape") != std::string::npos);
  CHECK(message.find("null geometry") != std::string::npos);
}
