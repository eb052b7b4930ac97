// Wires (seed 000, the agxWire pages): the seed's three-node route, a wire
// with free ends that falls keeping its length; and a 500 kg load hung 5 m
// below a crane boom on a steel wire from a winch, which holds it (tension
// m g) and then hauls it up 1 m at 0.5 m/s. Exits non-zero unless the
// length holds to 0.1%, the tension is m g to 1% and the load rises 1 m to 2%.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();

  // The seed's wire: radius 2 cm, two mass elements per meter, routed with
  // three free nodes (both ends free).
  double radius = 0.02;
  double resolution = 2.0;
  spook::WireRef wire = new spook::Wire(radius, resolution);
  wire->add(new spook::FreeNode(-2, 0, 0));
  wire->add(new spook::FreeNode(0, 0, 3));
  wire->add(new spook::FreeNode(2, 0, 0));
  simulation->add(wire);

  // A boom (static) and a load on 5 m of 1 cm steel wire.
  spook::RigidBodyRef boom = new spook::RigidBody("boom");
  boom->add(new spook::Geometry(new spook::Box(spook::Vec3(2.0, 0.2, 0.2))));
  boom->setMotionControl(spook::RigidBody::MotionControl::STATIC);
  boom->setPosition(0, 10, 8);
  simulation->add(boom);
  spook::RigidBodyRef load = new spook::RigidBody("load");
  load->add(new spook::Geometry(new spook::Box(spook::Vec3(0.5, 0.5, 0.5))));
  load->getMassProperties()->setMass(500.0);
  load->setPosition(1.5, 10, 2.5);  // right below the boom's end
  simulation->add(load);
  spook::WireRef hoist = new spook::Wire(0.01, 2.0);
  hoist->setName("hoist");
  hoist->getMaterial()->getBulkMaterial()->setDensity(7800);
  hoist->getMaterial()->getWireMaterial()->setYoungsModulusStretch(6E10);
  // The winch sits at the boom's end (boom frame), the wire leaving it
  // downwards, 20 m on its drum; until its speed is set its brake holds.
  spook::WireWinchControllerRef winch =
      new spook::WireWinchController(boom, spook::Vec3(1.5, 0, -0.2), spook::Vec3(0, 0, -1));
  hoist->add(winch, 20.0);
  hoist->add(new spook::BodyFixedNode(load, spook::Vec3(0, 0, 0.5)));
  simulation->add(hoist);

  const double length = wire->getRestLength();
  simulation->stepTo(simulation->getTimeStamp() + 1.0);

  const double stretch = wire->getCurrentLength() / length - 1.0;
  const double tension = hoist->getTension(hoist->getRestLength());
  const double weight = 500.0 * 9.80665;
  std::printf("seed wire: %zu mass nodes, rest length %.4f m, stretched by %.2e after 1 s of fall, its apex at z = %.3f m\n",
              wire->getNumMassNodes(), length, stretch, wire->getPoints()[wire->getPoints().size() / 2].z());
  std::printf("hoist: tension at the load %.1f N (m g = %.1f N), wire mass %.2f kg\n", tension, weight, hoist->getMass());

  // Haul in at 0.5 m/s with at most 20 kN for 2 s.
  winch->setSpeed(-0.5);
  winch->setForceRange(20E3);
  const double start = load->getPosition().z();
  for (int i = 0; i < 4; ++i) {
    simulation->stepTo(simulation->getTimeStamp() + 0.5);
    std::printf("t = %.1f s: hook at z = %.3f m, winch at %.3f m/s pulling %.1f N, %.3f m on the drum, %zu nodes\n",
                simulation->getTimeStamp(), load->getPosition().z(), winch->getCurrentSpeed(), -winch->getCurrentForce(),
                winch->getPulledInLength(), hoist->getNumMassNodes());
  }
  const double rise = load->getPosition().z() - start;
  return std::abs(stretch) < 1E-3 && std::abs(tension / weight - 1.0) < 0.01 && std::abs(rise - 1.0) < 0.02 ? 0 : 1;
}
