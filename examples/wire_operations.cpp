// Wire operations (seed 000, the agxWire pages "Wire operations" and
// "agxWire::Node"): a hanging wire cut in two, its load and lower part
// falling freely; two wires, one reversed, merged into one that carries a
// load; and a ring on an eye node sliding along a taut wire to where both
// sides hang at one angle. Exits non-zero unless the cut load falls at g t
// within 1%, the merged wire's tension at the load is m g within 1% and the
// ring rests within 1 cm of the clothesline equilibrium.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

namespace {

constexpr double kG = 9.80665;  // m/s², the simulation's default gravity

spook::RigidBodyRef addLoad(spook::Simulation& simulation, const char* name, double mass, spook::Vec3 at) {
  spook::RigidBodyRef load = new spook::RigidBody(name);
  load->add(new spook::Geometry(new spook::Sphere(0.2)));
  load->getMassProperties()->setMass(mass);
  load->setPosition(at);
  simulation.add(load);
  return load;
}

// Steel wires of one material (merge asks for it), 2 nodes per meter.
spook::WireRef steelWire(const char* name, double radius) {
  static const spook::MaterialRef steel = [] {
    spook::MaterialRef material = new spook::Material("steel wire");
    material->getBulkMaterial()->setDensity(7800);
    material->getWireMaterial()->setYoungsModulusStretch(2E11);
    return material;
  }();
  spook::WireRef wire = new spook::Wire(radius, 2.0, steel);
  wire->setName(name);
  return wire;
}

}  // namespace

int main() {
  spook::SimulationRef simulation = new spook::Simulation();

  // Cut: 10 m of wire from the world holds 50 kg; after 1 s it is cut 5 m
  // from its start. `cut` returns the part after the cut (with the load),
  // which goes on in the simulation once added.
  spook::RigidBodyRef first = addLoad(*simulation, "first load", 50.0, spook::Vec3(0, 0, 0));
  spook::WireRef wire1 = steelWire("wire1", 0.005);
  wire1->add(new spook::BodyFixedNode(nullptr, spook::Vec3(0, 0, 10)));
  wire1->add(new spook::BodyFixedNode(first, spook::Vec3(0, 0, 0.2)));
  simulation->add(wire1);
  simulation->stepTo(1.0);
  std::printf("wire1 holds %.1f N at the load (m g = %.1f N)\n", wire1->getTension(first->getPosition()), 50.0 * kG);
  spook::WireRef wire2 = wire1->cut(5.0);
  simulation->add(wire2);
  const double cutAt = simulation->getTimeStamp();
  simulation->stepTo(1.5);
  const double speed = -first->getVelocity().z(), freeFall = kG * (simulation->getTimeStamp() - cutAt);
  std::printf("cut: wire1 %.3f m and wire2 %.3f m; the load falls at %.4f m/s after %.3f s (g t = %.4f m/s)\n",
              wire1->getRestLength(), wire2->getRestLength(), speed, simulation->getTimeStamp() - cutAt, freeFall);

  // Merge: wire3 hangs from the world and ends free; wire4 was routed from
  // a load up to a free end. Reversed, wire4 starts free where wire3 ends:
  // merged (before either joins the simulation, their routes join), wire3
  // reaches the load and wire4 is left empty (in a simulation, remove it).
  spook::RigidBodyRef second = addLoad(*simulation, "second load", 20.0, spook::Vec3(10, 0, 0));
  spook::WireRef wire3 = steelWire("wire3", 0.005);
  wire3->add(new spook::BodyFixedNode(nullptr, spook::Vec3(10, 0, 10)));
  wire3->add(new spook::FreeNode(10, 0, 5));
  spook::WireRef wire4 = steelWire("wire4", 0.005);
  wire4->add(new spook::BodyFixedNode(second, spook::Vec3(0, 0, 0.2)));
  wire4->add(new spook::FreeNode(10, 0, 4.9));
  wire4->reverse();
  wire3->merge(wire4);
  simulation->add(wire3);
  simulation->stepTo(3.5);
  const double merged = wire3->getTension(second->getPosition() + spook::Vec3(0, 0, 0.2));
  std::printf("merge: one wire of %.3f m, %zu mass nodes; tension %.1f N at the load (m g = %.1f N), %.1f N at "
              "the top (with the wire's %.2f kg)\n",
              wire3->getRestLength(), wire3->getNumMassNodes(), merged, 20.0 * kG, wire3->getTension(0.0),
              wire3->getMass());

  // An eye node: a 100 kg ring threaded on a 2 mm wire (0.5 kg) between
  // two points 4 m apart, released off its equilibrium; it slides (no
  // friction) to where both sides make the angle a with the vertical,
  // sin a = span / length.
  spook::RigidBodyRef ring = addLoad(*simulation, "ring", 100.0, spook::Vec3(21, 0, 8));
  ring->setLinearVelocityDamping(2.0);  // air drag, to settle it
  spook::ref_ptr<spook::EyeNode> eye = new spook::EyeNode(ring, spook::Vec3(0, 0, 0));
  eye->setFrictionCoefficient(0.0);  // both directions; setFrictionCoefficient(mu, EyeNode::Direction::FORWARD)
  spook::WireRef line = steelWire("line", 0.002);
  line->add(new spook::BodyFixedNode(nullptr, spook::Vec3(20, 0, 10)));
  line->add(eye);
  line->add(new spook::BodyFixedNode(nullptr, spook::Vec3(24, 0, 9)));
  simulation->add(line);
  const double length = line->getRestLength();
  simulation->stepTo(simulation->getTimeStamp() + 8.0);
  const double sine = 4.0 / length, cosine = std::sqrt(1.0 - sine * sine);
  const double along = 0.5 * (length + 1.0 / cosine);
  const spook::Vec3 rest(20 + along * sine, 0, 10 - along * cosine);
  const double miss = (ring->getPosition() - rest).norm();
  std::printf("eye: the ring rests at (%.4f, %.4f), %.1f mm from the clothesline's (%.4f, %.4f); wire deflected "
              "%.4f rad, tension %.1f N (m g / (2 cos a) = %.1f N)\n",
              ring->getPosition().x(), ring->getPosition().z(), 1E3 * miss, rest.x(), rest.z(), eye->getWrapAngle(),
              line->getTension(0.0), 100.0 * kG / (2.0 * cosine));

  const bool fell = std::abs(speed / freeFall - 1.0) < 0.01;
  const bool carried = std::abs(merged / (20.0 * kG) - 1.0) < 0.01;
  return fell && carried && miss < 0.01 ? 0 : 1;
}
