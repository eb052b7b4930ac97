// Wires routed over cylinders (ContactNode, wire/sheave_wrap.hpp) against
// the capstan law: a wire over a fixed cylinder holds a load against a
// counterweight while their ratio is within e^{μθ} and slips beyond (θ = π/2,
// π, and 2π: one whole turn around a capstan); an Atwood machine over a
// frictional (and a frictionless) cylinder accelerates at
// (m₁ − m₂e^{μθ})g/(m₁ + m₂e^{μθ}); a wheel on a hinge that the wire cannot
// slip on turns with it.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <spook/spook.hpp>

#include "error_message.hpp"
#include "tolerance.hpp"

using namespace spook;

namespace {

constexpr double kGravity = 9.80665;  // m/s², the simulation's default

/// Two loads (kg) hung by a light limp wire (radius 5 mm, 100 kg/m³: 8 g/m,
/// 5 nodes/m) over a cylinder of radius 0.5 m on a static body at the
/// origin, its axis along y: the wire wraps it by π over the top, the
/// first load at x = +0.5, the second at x = −0.5, both 5 m below.
template <Scalar S>
struct OverCylinder {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> left = new RigidBodyT<S>(), right = new RigidBodyT<S>();
  ref_ptr<RigidBodyT<S>> holder = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> cylinder = new GeometryT<S>(new CylinderT<S>(S(0.5), S(0.2)));
  ref_ptr<ContactNodeT<S>> contact;
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));

  OverCylinder(double rightMass, double leftMass, double mu) {
    holder->add(cylinder);
    holder->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
    sim->add(holder);
    right->getMassProperties()->setMass(S(rightMass));
    right->setPosition(S(0.5), S(0), S(-5));
    left->getMassProperties()->setMass(S(leftMass));
    left->setPosition(S(-0.5), S(0), S(-5));
    sim->add(right);
    sim->add(left);
    wire->setName("rope");
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(S(mu));
    contact = new ContactNodeT<S>(cylinder.get(), Vec3(S(0), S(0), S(0.5)));
    wire->add(new BodyFixedNodeT<S>(right.get(), Vec3::Zero()));
    wire->add(contact);
    wire->add(new BodyFixedNodeT<S>(left.get(), Vec3::Zero()));
    sim->add(wire);
  }
};

/// A static body holding a cylinder of radius 0.5 m (axis along y) at
/// (x, 0, z) in `sim`; the cylinder.
template <Scalar S>
ref_ptr<GeometryT<S>> fixedCylinder(SimulationT<S>& sim, double x, double z) {
  ref_ptr<RigidBodyT<S>> holder = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> cylinder = new GeometryT<S>(new CylinderT<S>(S(0.5), S(0.2)));
  holder->add(cylinder);
  holder->setMotionControl(RigidBodyT<S>::MotionControl::STATIC);
  holder->setPosition(S(x), S(0), S(z));
  sim.add(holder);
  return cylinder;
}

/// A wheel (a cylinder of `radius` m and `mass` kg, I = M R²/2 about its
/// axle) at (x, 0, 0) in `sim`, on a hinge about the world's y axis; its
/// body and rim.
template <Scalar S>
std::pair<ref_ptr<RigidBodyT<S>>, ref_ptr<GeometryT<S>>> hingedWheel(SimulationT<S>& sim, double x, double radius,
                                                                     double mass) {
  using Vec3 = Vec3T<S>;
  ref_ptr<RigidBodyT<S>> wheel = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> rim = new GeometryT<S>(new CylinderT<S>(S(radius), S(0.1)));
  wheel->add(rim);
  wheel->getMassProperties()->setMass(S(mass));
  wheel->getMassProperties()->setInertiaTensor(SPDMat3T<S>(Vec3(S(1), S(0.5 * mass * radius * radius), S(1))));
  wheel->setPosition(S(x), S(0), S(0));
  sim.add(wheel);
  ref_ptr<FrameT<S>> axle = new FrameT<S>();  // in the wheel's frame
  axle->setLocalRotate(spook::rotate<S>(Vec3::UnitZ(), Vec3::UnitY()));
  sim.add(new HingeT<S>(wheel.get(), axle.get()));
  return {wheel, rim};
}

/// A load (kg) hung 5 m below the right of a fixed cylinder at the origin,
/// its 5 mm wire (5 nodes/m, `density` kg/m³) over the top to a winch on the
/// world 5 m below the left (pointing up, 3 m on its drum, force range
/// ±`force` N); the sheave's friction coefficient `mu`. The brake holds.
template <Scalar S>
struct HaulOverCylinder {
  using Vec3 = Vec3T<S>;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>();
  ref_ptr<WireWinchControllerT<S>> winch =
      new WireWinchControllerT<S>(nullptr, Vec3(S(-0.5), S(0), S(-5)), Vec3(S(0), S(0), S(1)));
  ref_ptr<ContactNodeT<S>> contact;
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));

  HaulOverCylinder(double mass, double density, double force, double mu) {
    contact = new ContactNodeT<S>(fixedCylinder(*sim, 0.0, 0.0).get(), Vec3(S(0), S(0), S(0.5)));
    contact->setFrictionCoefficient(S(mu));
    load->getMassProperties()->setMass(S(mass));
    load->setPosition(S(0.5), S(0), S(-5));
    sim->add(load);
    winch->setForceRange(S(-force), S(force));
    wire->getMaterial()->getBulkMaterial()->setDensity(S(density));
    wire->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
    wire->add(contact);
    wire->add(winch, S(3));
    sim->add(wire);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a wire over a cylinder holds within the capstan ratio and slips beyond it", S, double, float) {
  const double mu = 0.3, counterweight = 10.0;
  const double ratio = std::exp(mu * std::numbers::pi);
  for (const double share : {0.98, 1.02}) {
    CAPTURE(share);
    OverCylinder<S> rig(share * ratio * counterweight, counterweight, mu);
    CHECK(double(rig.contact->getWrapAngle()) == doctest::Approx(std::numbers::pi).epsilon(1e-6));
    const double length = double(rig.wire->getRestLength());
    const int steps = 60;
    for (int s = 0; s < steps; ++s) rig.sim->stepForward();
    const double time = steps * double(rig.sim->getTimeStep());
    const double drop = -5.0 - double(rig.right->getPosition().z());
    const double tensionRight = double(rig.wire->getTension(S(0.1)));
    const double tensionLeft = double(rig.wire->getTension(S(length - 0.1)));
    MESSAGE("load " << share << " e^(mu pi) x the counterweight: drop " << drop << " m in " << time
                    << " s, tensions " << tensionRight << " N and " << tensionLeft << " N (ratio "
                    << tensionRight / tensionLeft << " against " << ratio << "), friction "
                    << rig.contact->getFrictionForce() << " N");
    // On the wire along it: the tension before the sheave less the one after.
    CHECK(double(rig.contact->getFrictionForce()) == doctest::Approx(tensionRight - tensionLeft).epsilon(0.02));
    if (share < 1.0) {
      // Held: only the wire's stretch lets the load move.
      CHECK(std::abs(drop) < 1e-3);
      CHECK(tensionRight == doctest::Approx(share * ratio * counterweight * kGravity).epsilon(0.01));
      CHECK(tensionLeft == doctest::Approx(counterweight * kGravity).epsilon(0.01));
    } else {
      const double m1 = share * ratio * counterweight, m2 = counterweight;
      const double a = (m1 - m2 * ratio) * kGravity / (m1 + m2 * ratio);
      CHECK(drop > 0.25 * a * time * time);
      CHECK(tensionRight / tensionLeft == doctest::Approx(ratio).epsilon(0.01));
    }
  }
}

TEST_CASE_TEMPLATE("a quarter wrap holds within e^(mu pi/2), the wire turned down by a frictionless guide", S, double,
                   float) {
  using Vec3 = Vec3T<S>;
  const double mu = 0.3, counterweight = 10.0, ratio = std::exp(mu * std::numbers::pi / 2.0);
  for (const double share : {0.98, 1.02}) {
    CAPTURE(share);
    // The load hangs from the right of a sheave at the origin; the wire
    // leaves its top to the left, 3 m over to a frictionless guide, and
    // down its left side to the counterweight.
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<GeometryT<S>> sheave = fixedCylinder(*sim, 0.0, 0.0), guide = fixedCylinder(*sim, -3.0, 0.0);
    ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>(), weight = new RigidBodyT<S>();
    load->getMassProperties()->setMass(S(share * ratio * counterweight));
    load->setPosition(S(0.5), S(0), S(-4));
    weight->getMassProperties()->setMass(S(counterweight));
    weight->setPosition(S(-3.5), S(0), S(-4));
    sim->add(load);
    sim->add(weight);
    ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    ref_ptr<ContactNodeT<S>> onSheave = new ContactNodeT<S>(sheave.get(), Vec3(S(0.35), S(0), S(0.35)));
    ref_ptr<ContactNodeT<S>> onGuide = new ContactNodeT<S>(guide.get(), Vec3(S(-0.35), S(0), S(0.35)));
    onSheave->setFrictionCoefficient(S(mu));
    onGuide->setFrictionCoefficient(S(0));
    wire->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
    wire->add(onSheave);
    wire->add(onGuide);
    wire->add(new BodyFixedNodeT<S>(weight.get(), Vec3::Zero()));
    sim->add(wire);
    for (int s = 0; s < 60; ++s) sim->stepForward();
    // The span between the sheaves sags a little: the wraps grow by its slope.
    CHECK(double(onSheave->getWrapAngle()) == doctest::Approx(std::numbers::pi / 2.0).epsilon(0.005));
    CHECK(double(onGuide->getWrapAngle()) == doctest::Approx(std::numbers::pi / 2.0).epsilon(0.005));
    const double drop = -4.0 - double(load->getPosition().z()), speed = -double(load->getVelocity().z());
    const double high = double(wire->getTension(S(0.1)));
    const double low = double(wire->getTension(wire->getRestLength() - S(0.1)));
    MESSAGE("load " << share << " e^(mu pi/2) x the counterweight: drop " << drop << " m in 1 s, at " << speed
                    << " m/s, tensions " << high << " N and " << low << " N (ratio " << high / low << " against "
                    << ratio << "), wraps " << onSheave->getWrapAngle() << " and " << onGuide->getWrapAngle());
    if (share < 1.0) {
      CHECK(std::abs(drop) < 5e-3);
      CHECK(std::abs(speed) < 1e-3);
      CHECK(low == doctest::Approx(counterweight * kGravity).epsilon(0.01));
    } else {
      CHECK(drop > 0.01);
      CHECK(speed > 0.05);
      CHECK(high / low == doctest::Approx(ratio).epsilon(0.01));
    }
  }
}

TEST_CASE_TEMPLATE("a wire turned once around a capstan holds within e^(2 mu pi) and slips beyond", S, double, float) {
  using Vec3 = Vec3T<S>;
  const double mu = 0.2, counterweight = 10.0, ratio = std::exp(2.0 * mu * std::numbers::pi);
  for (const double share : {0.98, 1.02}) {
    CAPTURE(share);
    // The load hangs from the right of a capstan at the origin, the wire
    // rises along its right side, turned once around it, to the left of a
    // frictionless guide 3 m above, over its top and down its right side to
    // the counterweight: the capstan's wrap is one whole turn.
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<GeometryT<S>> capstan = fixedCylinder(*sim, 0.0, 0.0), guide = fixedCylinder(*sim, 1.0, 3.0);
    ref_ptr<RigidBodyT<S>> load = new RigidBodyT<S>(), weight = new RigidBodyT<S>();
    load->getMassProperties()->setMass(S(share * ratio * counterweight));
    load->setPosition(S(0.5), S(0), S(-4));
    weight->getMassProperties()->setMass(S(counterweight));
    weight->setPosition(S(1.5), S(0), S(-4));
    sim->add(load);
    sim->add(weight);
    ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
    wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    ref_ptr<ContactNodeT<S>> onCapstan = new ContactNodeT<S>(capstan.get(), Vec3(S(0.5), S(0), S(0)));
    ref_ptr<ContactNodeT<S>> onGuide = new ContactNodeT<S>(guide.get(), Vec3(S(-0.5), S(0), S(0)));
    onCapstan->setTurns(1);
    onCapstan->setFrictionCoefficient(S(mu));
    onGuide->setFrictionCoefficient(S(0));
    wire->add(new BodyFixedNodeT<S>(load.get(), Vec3::Zero()));
    wire->add(onCapstan);
    wire->add(onGuide);
    wire->add(new BodyFixedNodeT<S>(weight.get(), Vec3::Zero()));
    const double free = 4.0 + 3.0 + 0.5 * std::numbers::pi + 7.0;
    sim->add(wire);
    CHECK(double(onCapstan->getWrapAngle()) == doctest::Approx(2.0 * std::numbers::pi).epsilon(1e-6));
    // The turn's wire is on the capstan: 2πr more than the route's spans.
    CHECK(double(wire->getRestLength()) == doctest::Approx(free + std::numbers::pi).epsilon(1e-4));
    for (int s = 0; s < 60; ++s) sim->stepForward();
    CHECK(double(onCapstan->getWrapAngle()) == doctest::Approx(2.0 * std::numbers::pi).epsilon(0.005));
    const double drop = -4.0 - double(load->getPosition().z()), speed = -double(load->getVelocity().z());
    const double high = double(wire->getTension(S(0.1)));
    const double low = double(wire->getTension(wire->getRestLength() - S(0.1)));
    MESSAGE("load " << share << " e^(2 mu pi) x the counterweight: drop " << drop << " m in 1 s, at " << speed
                    << " m/s, tensions " << high << " N and " << low << " N (ratio " << high / low << " against "
                    << ratio << "), wrap " << onCapstan->getWrapAngle());
    if (share < 1.0) {
      CHECK(std::abs(drop) < 5e-3);
      CHECK(std::abs(speed) < 1e-3);
      CHECK(high == doctest::Approx(share * ratio * counterweight * kGravity).epsilon(0.01));
      CHECK(low == doctest::Approx(counterweight * kGravity).epsilon(0.01));
    } else {
      CHECK(drop > 0.01);
      CHECK(speed > 0.05);
      CHECK(high / low == doctest::Approx(ratio).epsilon(0.02));
    }
  }
}

TEST_CASE_TEMPLATE("an Atwood machine over a cylinder accelerates as the capstan law says", S, double, float) {
  const double heavy = 20.0, light = 5.0;
  for (const double mu : {0.0, 0.2}) {
    CAPTURE(mu);
    OverCylinder<S> rig(heavy, light, mu);
    const double e = std::exp(mu * std::numbers::pi);
    const double a = (heavy - light * e) * kGravity / (heavy + light * e);
    const double length = double(rig.wire->getRestLength());
    // The accelerations over the second half of a second (the loads start
    // at rest: the first steps' wave along the wire settles).
    for (int s = 0; s < 30; ++s) rig.sim->stepForward();
    const double heavyFrom = double(rig.right->getVelocity().z()), lightFrom = double(rig.left->getVelocity().z());
    for (int s = 0; s < 30; ++s) rig.sim->stepForward();
    const double time = 30 * double(rig.sim->getTimeStep());
    const double heavyAcceleration = (heavyFrom - double(rig.right->getVelocity().z())) / time;
    const double lightAcceleration = (double(rig.left->getVelocity().z()) - lightFrom) / time;
    MESSAGE("mu " << mu << ": the heavy load falls at " << heavyAcceleration << " m/s^2, the light rises at "
                  << lightAcceleration << " m/s^2, against " << a << "; " << rig.wire->getNumMassNodes()
                  << " nodes, rest length " << rig.wire->getRestLength() << " m (was " << length << ")");
    CHECK(heavyAcceleration == doctest::Approx(a).epsilon(0.02));
    CHECK(lightAcceleration == doctest::Approx(a).epsilon(0.02));
    CHECK(double(rig.wire->getRestLength()) == doctest::Approx(length).epsilon(1e-9));
  }
}

TEST_CASE_TEMPLATE("a load pulled up to a fixed sheave stops at it, held by the wire", S, double, float) {
  // The frictionless Atwood machine over the cylinder run on: the light load
  // rises 5 m on the left to where the wire meets the cylinder (z = 0) and
  // stops there, the heavy one hanging still. A wire cannot push: the load
  // passes that point by up to one step's travel v h, and the wire then
  // holds it there (it was dragged over the top and the wire left the
  // sheave, both loads falling; on a wheel that turns, it still is, as a
  // point load would be). The light load at the wire's end, and (reversed)
  // at its start.
  const double rise = 5.0;
  for (const bool reversed : {false, true})
    for (const auto& loads : {std::pair(5.0, 20.0), std::pair(1.0, 100.0)}) {
      const double light = loads.first, heavy = loads.second;
      CAPTURE(reversed);
      CAPTURE(heavy / light);
      const double a = (heavy - light) * kGravity / (heavy + light), arrival = std::sqrt(2.0 * a * rise);
      OverCylinder<S> rig(heavy, light, 0.0);
      if (reversed) rig.wire->reverse();
      const double h = double(rig.sim->getTimeStep());
      double highest = -1e9, worstSpeed = 0.0;  // relative error of the speed on the way up
      for (int s = 1; s <= 180; ++s) {
        rig.sim->stepForward();
        highest = std::max(highest, double(rig.left->getPosition().z()));
        if (s >= 6 && highest < -0.1)
          worstSpeed = std::max(worstSpeed, std::abs(double(rig.left->getVelocity().z()) / (a * s * h) - 1.0));
      }
      const double top = double(rig.left->getPosition().z()), x = double(rig.left->getPosition().x());
      const double speed = double(rig.right->getVelocity().norm());
      const S atHeavy = reversed ? rig.wire->getRestLength() - S(0.1) : S(0.1);
      const double tension = double(rig.wire->getTension(atHeavy));
      MESSAGE(light << " kg against " << heavy << ": on the way up the light load's speed within " << worstSpeed
                    << " of the Atwood machine's; after 3 s it is at (" << x << ", " << top << ") (highest " << highest
                    << ", a step's travel at arrival " << arrival * h << "), the heavy one moves at " << speed
                    << " m/s, the wire pulls it with " << tension << " N (its weight " << heavy * kGravity << ")");
      REQUIRE(std::isfinite(top));
      CHECK(worstSpeed < 0.01);
      CHECK(highest < arrival * h);
      CHECK(std::abs(top) < arrival * h);
      CHECK(std::abs(x + 0.5) < 0.01);
      CHECK(speed < 0.01);
      CHECK(tension == doctest::Approx(heavy * kGravity).epsilon(0.02));
    }
}

TEST_CASE_TEMPLATE("a wheel on a hinge turns with a wire that cannot slip on it", S, double, float) {
  using Vec3 = Vec3T<S>;
  // An Atwood machine whose pulley is a wheel of 10 kg (I = M R²/2 about
  // its axle): a = (m₁ − m₂) g/(m₁ + m₂ + I/R²).
  const double heavy = 20.0, light = 5.0, wheelMass = 10.0, radius = 0.5;
  const double inertia = 0.5 * wheelMass * radius * radius;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  const auto wheelAndRim = hingedWheel(*sim, 0.0, radius, wheelMass);
  const ref_ptr<RigidBodyT<S>>& wheel = wheelAndRim.first;
  const ref_ptr<GeometryT<S>>& rim = wheelAndRim.second;
  ref_ptr<RigidBodyT<S>> left = new RigidBodyT<S>(), right = new RigidBodyT<S>();
  right->getMassProperties()->setMass(S(heavy));
  right->setPosition(S(radius), S(0), S(-5));
  left->getMassProperties()->setMass(S(light));
  left->setPosition(S(-radius), S(0), S(-5));
  sim->add(right);
  sim->add(left);
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
  wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
  wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
  wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(S(10));
  wire->add(new BodyFixedNodeT<S>(right.get(), Vec3::Zero()));
  wire->add(new ContactNodeT<S>(rim.get(), Vec3(S(0), S(0), S(radius))));
  wire->add(new BodyFixedNodeT<S>(left.get(), Vec3::Zero()));
  sim->add(wire);
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double from = double(right->getVelocity().z());
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double acceleration = (from - double(right->getVelocity().z())) / (30 * double(sim->getTimeStep()));
  const double expected = (heavy - light) * kGravity / (heavy + light + inertia / (radius * radius));
  const double spin = double(wheel->getAngularVelocity().y()), speed = -double(right->getVelocity().z());
  MESSAGE("the heavy load falls at " << acceleration << " m/s^2 against " << expected << "; the wheel turns at "
                                     << spin << " rad/s, the rope moves at " << speed << " m/s");
  CHECK(acceleration == doctest::Approx(expected).epsilon(0.02));
  // The heavy side, at +x, goes down: the wheel turns about +y, its rim
  // with the rope.
  CHECK(spin * radius == doctest::Approx(speed).epsilon(0.02));
  CHECK(wheel->getPosition().norm() < S(1e-3));
}

TEST_CASE_TEMPLATE("a wire over two wheels on hinges runs as an Atwood machine whose pulleys turn", S, double, float) {
  using Vec3 = Vec3T<S>;
  // Two wheels of 10 kg and radius 0.5 m, 2 m apart, each on a hinge about
  // y; the wire over both (a quarter turn on each), the loads under their
  // outer sides: a = (m₁ − m₂) g/(m₁ + m₂ + 2I/R²). It runs at 4 m/s after
  // a second: the node left between the wheels closes on the second one, and
  // may not leave there (the segment between the wheels' contacts would
  // couple both wheels and both slips, four bodies in one row: it threw).
  const double heavy = 20.0, light = 5.0, wheelMass = 10.0, radius = 0.5;
  const double inertia = 0.5 * wheelMass * radius * radius;
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  std::vector<ref_ptr<RigidBodyT<S>>> wheels;
  std::vector<ref_ptr<GeometryT<S>>> rims;
  for (const double x : {-1.0, 1.0}) {
    const auto wheelAndRim = hingedWheel(*sim, x, radius, wheelMass);
    wheels.push_back(wheelAndRim.first);
    rims.push_back(wheelAndRim.second);
  }
  ref_ptr<RigidBodyT<S>> left = new RigidBodyT<S>(), right = new RigidBodyT<S>();
  right->getMassProperties()->setMass(S(heavy));
  right->setPosition(S(1.5), S(0), S(-3));
  left->getMassProperties()->setMass(S(light));
  left->setPosition(S(-1.5), S(0), S(-3));
  sim->add(right);
  sim->add(left);
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
  wire->getMaterial()->getBulkMaterial()->setDensity(S(100));
  wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
  wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(S(10));
  wire->add(new BodyFixedNodeT<S>(right.get(), Vec3::Zero()));
  wire->add(new ContactNodeT<S>(rims[1].get(), Vec3(S(0), S(0), S(radius))));
  wire->add(new ContactNodeT<S>(rims[0].get(), Vec3(S(0), S(0), S(radius))));
  wire->add(new BodyFixedNodeT<S>(left.get(), Vec3::Zero()));
  sim->add(wire);
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double from = double(right->getVelocity().z());
  for (int s = 0; s < 30; ++s) sim->stepForward();
  const double acceleration = (from - double(right->getVelocity().z())) / (30 * double(sim->getTimeStep()));
  const double expected = (heavy - light) * kGravity / (heavy + light + 2.0 * inertia / (radius * radius));
  const double speed = -double(right->getVelocity().z());
  MESSAGE("the heavy load falls at " << acceleration << " m/s^2 against " << expected << ", at " << speed
                                     << " m/s after 1 s; the wheels turn at "
                                     << double(wheels[0]->getAngularVelocity().y()) << " and "
                                     << double(wheels[1]->getAngularVelocity().y()) << " rad/s");
  CHECK(acceleration == doctest::Approx(expected).epsilon(0.02));
  for (const auto& wheel : wheels)
    CHECK(double(wheel->getAngularVelocity().y()) * radius == doctest::Approx(speed).epsilon(0.02));
}

TEST_CASE_TEMPLATE("a wire leaves a sheave that moves away from it and runs straight", S, double, float) {
  using Vec3 = Vec3T<S>;
  // A wire between two fixed points 4 m apart, pushed 0.3 m up by a
  // cylinder on a kinematic body that then sinks at 1 m/s (no gravity).
  ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
  sim->setUniformGravity(Vec3::Zero());
  ref_ptr<RigidBodyT<S>> lift = new RigidBodyT<S>();
  ref_ptr<GeometryT<S>> roller = new GeometryT<S>(new CylinderT<S>(S(0.5), S(0.2)));
  lift->add(roller);
  lift->setMotionControl(RigidBodyT<S>::MotionControl::KINEMATICS);
  lift->setPosition(S(0), S(0), S(-0.2));
  sim->add(lift);
  ref_ptr<WireT<S>> wire = new WireT<S>(S(0.005), S(5));
  ref_ptr<ContactNodeT<S>> contact = new ContactNodeT<S>(roller.get(), Vec3(S(0), S(0), S(0.5)));
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(-2), S(0), S(0))));
  wire->add(contact);
  wire->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(2), S(0), S(0))));
  sim->add(wire);
  const double wrapped = double(contact->getWrapAngle()), length = double(wire->getRestLength());
  CHECK(wrapped > 0.2);
  lift->setVelocity(Vec3(S(0), S(0), S(-1)));
  for (int s = 0; s < 60; ++s) sim->stepForward();
  MESSAGE("wrap " << wrapped << " rad at first, " << contact->getWrapAngle() << " after; "
                  << wire->getPoints().size() << " points");
  CHECK(contact->getWrapAngle() == S(0));
  CHECK(double(wire->getRestLength()) == doctest::Approx(length).epsilon(1e-9));
  // Free of the roller, the wire hangs slack between its ends (no gravity):
  // no longer than its rest length, no shorter than the span, nowhere the
  // roller has gone.
  CHECK(double(wire->getCurrentLength()) >= 4.0);
  CHECK(double(wire->getCurrentLength()) <= length + 1e-3);
  for (const Vec3& p : wire->getPoints()) {
    CHECK(p.allFinite());
    CHECK(std::abs(double(p.z())) < 0.5);
  }
}

TEST_CASE("a contact node refuses bad input by name and leaves the simulation unchanged") {
  const auto message = [](auto&& make) { return spook::test::errorMessage(make); };
  CHECK(message([] { ref_ptr<ContactNode> c = new ContactNode(nullptr, Vec3::Zero()); }).find("geometry") !=
        std::string::npos);
  ref_ptr<Geometry> box = new Geometry(new Box(Vec3(0.5, 0.5, 0.5)));
  ref_ptr<ContactNode> onBox = new ContactNode(box.get(), Vec3(0, 0, 0.5));
  CHECK(message([&] { onBox->setFrictionCoefficient(-0.1); }).find("friction") != std::string::npos);
  CHECK(message([&] { onBox->setFrictionCoefficient(std::nan("")); }).find("nan") != std::string::npos);

  ref_ptr<Simulation> sim = new Simulation();
  const auto refused = [&](Wire* wire, const char* expected) {
    const std::string what = message([&] { sim->add(ref_ptr<Wire>(wire)); });
    CAPTURE(what);
    CHECK(what.find("'w'") != std::string::npos);
    CHECK(what.find(expected) != std::string::npos);
    CHECK(sim->getRowProducers().empty());
    CHECK(sim->getBodyStores().empty());
  };
  ref_ptr<Geometry> ball = new Geometry(new Sphere(0.5));
  ref_ptr<Wire> overBall = new Wire(0.01, 2.0);
  overBall->setName("w");
  overBall->add(new FreeNode(2, 0, -2));
  overBall->add(new ContactNode(ball.get(), Vec3(0, 0, 0.5)));
  overBall->add(new FreeNode(-2, 0, -2));
  refused(overBall.get(), "one cylinder, box, convex, trimesh or height field");
  onBox->setTurns(1);
  ref_ptr<Wire> turnsOnBox = new Wire(0.01, 2.0);
  turnsOnBox->setName("w");
  turnsOnBox->add(new FreeNode(2, 0, -2));
  turnsOnBox->add(onBox);
  turnsOnBox->add(new FreeNode(-2, 0, -2));
  refused(turnsOnBox.get(), "a ContactNode on an edge cannot take turns");

  ref_ptr<Geometry> drum = new Geometry(new Cylinder(0.5, 0.2));
  ref_ptr<Wire> atEnd = new Wire(0.01, 2.0);
  atEnd->setName("w");
  atEnd->add(new FreeNode(2, 0, -2));
  atEnd->add(new ContactNode(drum.get(), Vec3(0, 0, 0.5)));
  refused(atEnd.get(), "may not be the first or last");

  ref_ptr<RigidBody> away = new RigidBody();
  away->setName("away");
  ref_ptr<Geometry> carried = new Geometry(new Cylinder(0.5, 0.2));
  away->add(carried);
  ref_ptr<Wire> notThere = new Wire(0.01, 2.0);
  notThere->setName("w");
  notThere->add(new FreeNode(2, 0, -2));
  notThere->add(new ContactNode(carried.get(), Vec3(0, 0, 0.5)));
  notThere->add(new FreeNode(-2, 0, -2));
  refused(notThere.get(), "away");
}

// A winch hauls 10 kg up over a frictionless guide (a 5 mm steel wire at 5
// nodes per meter, 100 N: its nodes at the edge of the adaptive resolution's
// removal). The nodes arriving at the guide leave there, and no node is
// split into a wrap's arc: before, each step split the straight part beside
// the wrap in half, the nodes piled up at the tangent point, the wire
// pushed (-330 N) and the load jumped between 0.1 and 3 m/s.
TEST_CASE_TEMPLATE("a winch hauls a light load over a guide at its speed, nodes leaving at the guide", S, double,
                   float) {
  HaulOverCylinder<S> rig(10.0, 7800.0, 1e3, 0.0);
  auto& sim = rig.sim;
  auto& load = rig.load;
  auto& winch = rig.winch;
  auto& contact = rig.contact;
  auto& wire = rig.wire;
  for (int s = 0; s < 30; ++s) sim->stepForward();
  winch->setSpeed(S(-0.5));
  const std::size_t nodes = wire->getNumMassNodes();
  std::size_t most = nodes;
  double slowest = 1e9, fastest = 0, lowest = 1e9, highest = 0;
  for (int s = 0; s < 120; ++s) {
    sim->stepForward();
    most = std::max(most, wire->getNumMassNodes());
    if (s < 10) continue;  // the winch's start
    const double v = double(load->getVelocity().z()), t = double(wire->getTension(S(0)));
    slowest = std::min(slowest, v);
    fastest = std::max(fastest, v);
    lowest = std::min(lowest, t);
    highest = std::max(highest, t);
  }
  const double weight = 10.0 * kGravity;
  MESSAGE("hauled over a guide: load at " << slowest << ".." << fastest << " m/s, tension at it " << lowest << ".."
                                          << highest << " N (" << weight << "), " << nodes << " nodes, at most "
                                          << most << "; wrap " << contact->getWrapAngle() << " rad");
  CHECK(slowest == doctest::Approx(0.5).epsilon(0.01));
  CHECK(fastest == doctest::Approx(0.5).epsilon(0.01));
  CHECK(lowest == doctest::Approx(weight).epsilon(0.01));
  CHECK(highest == doctest::Approx(weight).epsilon(0.01));
  CHECK(most <= nodes + 2);
  CHECK(double(contact->getWrapAngle()) == doctest::Approx(std::numbers::pi).epsilon(1e-3));
}

// A winch hauls 20 kg up over a fixed cylinder with friction (θ = π): the
// wire slips over it steadily, the winch pulling e^{μθ} times the load (the
// capstan law). With the friction bound from the last step's tensions the
// winch alternated between stalled and yanking the load at 2 m/s.
TEST_CASE_TEMPLATE("a winch hauls a load over a fixed sheave against the capstan friction, steadily", S, double,
                   float) {
  for (const double mu : {0.2, 0.41667}) {
    CAPTURE(mu);
    // The wire at 100 kg/m³ (8 g/m): the load's tension throughout.
    HaulOverCylinder<S> rig(20.0, 100.0, 5e3, mu);
    auto& sim = rig.sim;
    auto& load = rig.load;
    auto& winch = rig.winch;
    auto& contact = rig.contact;
    for (int s = 0; s < 30; ++s) sim->stepForward();
    winch->setSpeed(S(-0.5));
    double slowest = 1e9, fastest = 0, lowestPull = 1e9, highestPull = 0, lowestFriction = 1e9, highestFriction = 0;
    for (int s = 0; s < 120; ++s) {
      sim->stepForward();
      if (s < 10) continue;  // the winch's start
      const double v = double(load->getVelocity().z()), pull = -double(winch->getCurrentForce());
      const double friction = double(contact->getFrictionForce());
      slowest = std::min(slowest, v);
      fastest = std::max(fastest, v);
      lowestPull = std::min(lowestPull, pull);
      highestPull = std::max(highestPull, pull);
      lowestFriction = std::min(lowestFriction, std::abs(friction));
      highestFriction = std::max(highestFriction, std::abs(friction));
    }
    const double weight = 20.0 * kGravity, ratio = std::exp(mu * std::numbers::pi);
    MESSAGE("mu " << mu << ": load at " << slowest << ".." << fastest << " m/s; the winch pulls " << lowestPull << ".."
                  << highestPull << " N (e^(mu pi) m g = " << ratio * weight << "), friction " << lowestFriction
                  << ".." << highestFriction << " N (" << (ratio - 1.0) * weight << ")");
    CHECK(slowest == doctest::Approx(0.5).epsilon(0.01));
    CHECK(fastest == doctest::Approx(0.5).epsilon(0.01));
    CHECK(lowestPull == doctest::Approx(ratio * weight).epsilon(0.02));
    CHECK(highestPull == doctest::Approx(ratio * weight).epsilon(0.02));
    CHECK(lowestFriction == doctest::Approx((ratio - 1.0) * weight).epsilon(0.02));
    CHECK(highestFriction == doctest::Approx((ratio - 1.0) * weight).epsilon(0.02));
  }
}

TEST_CASE_TEMPLATE("a stiff wire wrapped on a sheave that a kinematic body spins or drags stays finite", S, double,
                   float) {
  using Vec3 = Vec3T<S>;
  // A steel-like wire (E 4.9e11 Pa, 46 kg/m³, radius 8.2 mm, no bend
  // stiffness) from a point on a kinematic body, over a cylinder of radius
  // 0.53 m on that body, to a fixed point of the world: the body spins at
  // 5 or 20 rad/s about an axis across the cylinder's (the wire wraps 4.9
  // rad of it) or drags the wire away at 3 or 11 m/s, for a second at 60 Hz.
  // The wire cannot hold either; it must stay finite, no node farther from
  // the fixed end than the body's reach plus what a stretch wave runs in a
  // second, √(E/ρ)·1 s.
  const double c = std::sqrt(4.9e11 / 46.0);
  for (const auto& motion : {std::pair{20.0, 0.0}, std::pair{5.0, 3.0}, std::pair{0.0, 11.0}}) {
    const double spin = motion.first, speed = motion.second;  // rad/s, m/s
    CAPTURE(spin);
    CAPTURE(speed);
    ref_ptr<SimulationT<S>> sim = new SimulationT<S>();
    ref_ptr<RigidBodyT<S>> body = new RigidBodyT<S>();
    ref_ptr<GeometryT<S>> sheave = new GeometryT<S>(new CylinderT<S>(S(0.53), S(0.53)));
    body->add(sheave);
    body->setMotionControl(RigidBodyT<S>::MotionControl::KINEMATICS);
    body->setPosition(S(-2), S(-2), S(1.5));
    sim->add(body);
    ref_ptr<WireT<S>> wire = new WireT<S>(S(0.0082), S(0.1));
    wire->getMaterial()->getBulkMaterial()->setDensity(S(46));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusStretch(S(4.9e11));
    wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(S(0));
    wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(S(0.98));
    wire->add(new BodyFixedNodeT<S>(body.get(), Vec3(S(-1), S(-1), S(-0.94))));
    wire->add(new ContactNodeT<S>(sheave.get(), Vec3::Zero()));
    wire->add(new BodyFixedNodeT<S>(nullptr, Vec3(S(-1), S(-1), S(-1))));
    sim->add(wire);
    body->setVelocity(Vec3(S(0.16 * speed), S(-speed), S(0)));
    body->setAngularVelocity(Vec3(S(0), S(0), S(-spin)));
    const Vec3 anchor(S(-1), S(-1), S(-1));
    double farthest = 0.0;
    bool finite = true;
    for (int s = 0; s < 60; ++s) {
      sim->stepForward();
      for (const Vec3& p : wire->getPoints()) {
        finite = finite && p.allFinite();
        farthest = std::max(farthest, double((p - anchor).norm()));
      }
    }
    const double reach = double((body->getPosition() - anchor).norm()) + 2.0;
    MESSAGE("spin " << spin << " rad/s, drag " << speed << " m/s: farthest point " << farthest
                    << " m from the fixed end (body's reach " << reach << " m)");
    CHECK(finite);
    CHECK(farthest <= reach + c * 1.0);
  }
}
