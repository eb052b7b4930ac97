// A crane hoist (seed 000, the agxWire pages): a winch at the root of a
// boom hauls a 2 t load up over a sheave at the boom's tip. The boom is
// static, the sheave a 50 kg wheel on a hinge at its tip; the steel wire
// (radius 1 cm) runs from the winch along the boom, over the sheave (which
// it turns: it would have to slip over a fixed one, which the capstan law
// makes cost e^{μθ} times the load) and down to the hook. The brake holds the load for a
// second, then the winch hauls in at 0.5 m/s with at most 30 kN for 3 s.
// Prints tension, hook height and winch state; exits non-zero unless the
// hook rises 1.5 m within 2% with the tension at the hook m·g within 2%.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();

  // The boom: 8 m along x at 10 m height; at its tip the sheave, a wheel
  // of radius 0.3 m turning about y on a hinge.
  spook::RigidBodyRef boom = new spook::RigidBody("boom");
  boom->add(new spook::Geometry(new spook::Box(spook::Vec3(4.0, 0.2, 0.2))));
  boom->setMotionControl(spook::RigidBody::MotionControl::STATIC);
  boom->setPosition(4.0, 0.0, 10.0);
  simulation->add(boom);
  spook::RigidBodyRef wheel = new spook::RigidBody("sheave");
  spook::GeometryRef sheave = new spook::Geometry(new spook::Cylinder(0.3, 0.1));
  wheel->add(sheave);
  wheel->getMassProperties()->setMass(50.0);
  wheel->setPosition(8.5, 0.0, 10.0);  // clear of the boom's end
  simulation->add(wheel);
  spook::FrameRef axle = new spook::Frame();
  axle->setLocalRotate(spook::rotate<double>(spook::Vec3::UnitZ(), spook::Vec3::UnitY()));  // hinge axis: z of its frame
  simulation->add(new spook::Hinge(wheel, axle));

  const double mass = 2000.0, g = 9.80665;
  spook::RigidBodyRef load = new spook::RigidBody("load");
  load->add(new spook::Geometry(new spook::Box(spook::Vec3(0.5, 0.5, 0.5))));
  load->getMassProperties()->setMass(mass);
  load->setPosition(8.8, 0.0, 2.0);  // below the sheave's far side
  simulation->add(load);

  // The winch sits on the boom near its root, 0.3 m above the axis so that
  // the wire runs level onto the top of the sheave; 40 m on its drum.
  spook::WireWinchControllerRef winch =
      new spook::WireWinchController(boom, spook::Vec3(-3.5, 0.0, 0.3), spook::Vec3(1.0, 0.0, 0.0));
  winch->setName("hoist winch");
  spook::WireRef wire = new spook::Wire(0.01, 2.0);
  wire->setName("hoist wire");
  wire->getMaterial()->getBulkMaterial()->setDensity(7800);
  wire->getMaterial()->getWireMaterial()->setYoungsModulusStretch(6E10);
  spook::ref_ptr<spook::ContactNode> overSheave = new spook::ContactNode(sheave, spook::Vec3(0.2, 0.0, 0.2));
  wire->add(winch, 40.0);
  wire->add(overSheave);
  wire->add(new spook::BodyFixedNode(load, spook::Vec3(0.0, 0.0, 0.5)));
  simulation->add(wire);

  const auto report = [&] {
    std::printf("t = %.1f s: hook at z = %.3f m (%+.3f m/s), tension at the hook %.0f N, winch %+.3f m/s pulling "
                "%.0f N, %.2f m on the drum, wrap %.3f rad, %zu mass nodes\n",
                simulation->getTimeStamp(), load->getPosition().z() + 0.5, load->getVelocity().z(),
                wire->getTension(wire->getRestLength()), winch->getCurrentSpeed(), -winch->getCurrentForce(),
                winch->getPulledInLength(), overSheave->getWrapAngle(), wire->getNumMassNodes());
  };
  simulation->stepTo(1.0);  // the brake holds
  report();
  winch->setSpeed(-0.5);
  winch->setForceRange(30E3);
  const double start = load->getPosition().z();
  double tension = 0.0;
  for (int i = 0; i < 6; ++i) {
    simulation->stepTo(simulation->getTimeStamp() + 0.5);
    report();
    tension = wire->getTension(wire->getRestLength());
  }
  const double rise = load->getPosition().z() - start;
  std::printf("hauled %.3f m in 3 s (1.5 m at 0.5 m/s); m g = %.0f N\n", rise, mass * g);
  return std::abs(rise / 1.5 - 1.0) < 0.02 && std::abs(tension / (mass * g) - 1.0) < 0.02 ? 0 : 1;
}
