// Issue 21's wire scenes at 60 Hz, cost against accuracy:
//
// 1. Pay-out over two sheaves: a 10 t load on a steel wire (radius 1 cm)
//    from a winch on the ground, up over a sheave wheel 20 m up and across
//    to a second 10 m on (both wheels on hinges), down to the load. The
//    brake holds while the load settles on the unstretched wire (6 s) and
//    for 2 s more, the winch pays out at 1 m/s for 4 s and hauls in at
//    1 m/s for 4 s. Per phase: time per step, mass nodes, and over its
//    second half the mean tension at the load against m·g, the load's speed
//    against the winch's, the load's travel, and the change of the total
//    length (drum and wire).
// 2. A 12-fall reeving: one light wire from a winch over 6 crown sheaves
//    (fixed cylinders) and 6 sheaves on a 10 t hook block running in a
//    vertical guide, its dead end at the crown; the winch hauls at 1 m/s. The winch's tension against the
//    capstan chain, W / Σₖ e^{−kμπ} (k = 1…12, each part e^{μπ} below the
//    one before it), for μ = 0 and 0.05; time per step against real time.
//
//   wire_study [csv]

#include <spook/spook.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace {

constexpr double kGravity = 9.80665;

struct Phase {
  std::string name;
  double meanMs = 0.0, maxMs = 0.0;
  std::size_t fewestNodes = 0, mostNodes = 0;
  double tensionError = 0.0;  // relative, the mean over the phase's second half
  double speedError = 0.0;    // relative, the mean over the phase's second half
  double moved = 0.0;         // m, the load over the phase's second half
  double lengthChange = 0.0;  // m
};

spook::WireRef steelWire(double radius, double resolution) {
  spook::WireRef wire = new spook::Wire(radius, resolution);
  wire->getMaterial()->getBulkMaterial()->setDensity(7800);
  wire->getMaterial()->getWireMaterial()->setYoungsModulusStretch(6E10);
  return wire;
}

spook::GeometryRef hingedSheave(spook::Simulation& sim, const spook::Vec3& at, double radius) {
  spook::RigidBodyRef wheel = new spook::RigidBody("sheave");
  spook::GeometryRef rim = new spook::Geometry(new spook::Cylinder(radius, 0.1));
  wheel->add(rim);
  wheel->getMassProperties()->setMass(100.0);
  wheel->setPosition(at);
  sim.add(wheel);
  spook::FrameRef axle = new spook::Frame();
  axle->setLocalRotate(spook::rotate<double>(spook::Vec3::UnitZ(), spook::Vec3::UnitY()));
  sim.add(new spook::Hinge(wheel, axle));
  return rim;
}

std::vector<Phase> payOut() {
  spook::SimulationRef sim = new spook::Simulation();
  const double mass = 1e4, radius = 0.5;
  spook::GeometryRef first = hingedSheave(*sim, spook::Vec3(0, 0, 20), radius);
  spook::GeometryRef second = hingedSheave(*sim, spook::Vec3(10, 0, 20), radius);
  spook::RigidBodyRef load = new spook::RigidBody("load");
  load->getMassProperties()->setMass(mass);
  load->setPosition(10 + radius, 0, 5);
  sim->add(load);
  spook::WireWinchControllerRef winch =
      new spook::WireWinchController(nullptr, spook::Vec3(-10, 0, 0.5), spook::Vec3(10, 0, 19.5));
  spook::WireRef wire = steelWire(0.01, 1.0);
  wire->add(winch, 100.0);
  wire->add(new spook::ContactNode(first, spook::Vec3(0, 0, radius)));
  wire->add(new spook::ContactNode(second, spook::Vec3(radius * 0.7, 0, radius * 0.7)));
  wire->add(new spook::BodyFixedNode(load, spook::Vec3::Zero()));
  sim->add(wire);

  const double h = sim->getTimeStep();
  const auto total = [&] { return wire->getRestLength() + winch->getPulledInLength(); };
  const double length = total();
  std::vector<Phase> phases;
  const auto run = [&](const std::string& name, double speed, double seconds) {
    winch->setSpeed(speed);
    Phase p;
    p.name = name;
    p.fewestNodes = wire->getNumMassNodes();
    const int steps = int(std::lround(seconds / h));
    double spent = 0.0, late = 0.0, tension = 0.0;
    for (int k = 0; k < steps; ++k) {
      if (k == steps / 2) late = load->getPosition().z();
      if (k >= steps / 2) tension += wire->getTension(wire->getRestLength()) / (steps - steps / 2);
      const auto t0 = std::chrono::steady_clock::now();
      sim->stepForward();
      const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
      spent += dt;
      p.maxMs = std::max(p.maxMs, dt);
      p.fewestNodes = std::min(p.fewestNodes, wire->getNumMassNodes());
      p.mostNodes = std::max(p.mostNodes, wire->getNumMassNodes());
    }
    p.meanMs = spent / steps;
    // The load's mean speed over the phase's second half against the winch's.
    p.moved = load->getPosition().z() - late;
    p.speedError = speed != 0.0 ? -p.moved / ((steps - steps / 2) * h) / speed - 1.0 : 0.0;
    p.tensionError = tension / (mass * kGravity) - 1.0;
    p.lengthChange = total() - length;
    phases.push_back(p);
  };
  winch->setForceRange(3e5);
  // The wire starts unstretched: 10 t stretch it by ~0.2 m, and the load
  // bounces on it (SPOOK's damping of 0.05 s) before it hangs still.
  run("settle (brake)", 0.0, 6.0);
  run("hold (brake)", 0.0, 2.0);
  run("pay out 1 m/s", 1.0, 4.0);
  run("haul in 1 m/s", -1.0, 4.0);
  return phases;
}

struct Reeving {
  double mu, meanMs, maxMs, winchTension, expected, blockSpeed;
  std::size_t nodes, contacts;
};

Reeving reeving(double mu) {
  spook::SimulationRef sim = new spook::Simulation();
  const double mass = 1e4, r = 0.25, crown = 20.0, blockAt = 5.0;
  spook::RigidBodyRef top = new spook::RigidBody("crown");
  top->setMotionControl(spook::RigidBody::MotionControl::STATIC);
  spook::RigidBodyRef block = new spook::RigidBody("hook block");
  block->setPosition(2.75, 0, blockAt);
  std::vector<spook::GeometryRef> crownSheaves, blockSheaves;
  for (int i = 0; i < 6; ++i) {
    spook::Transform X = spook::Transform::Identity();
    X.translation() = spook::Vec3(i, 0, crown);
    spook::GeometryRef c = new spook::Geometry(new spook::Cylinder(r, 0.1), X);
    top->add(c);
    crownSheaves.push_back(c);
    X.translation() = spook::Vec3(i + 0.5 - 2.75, 0, 0);  // block frame
    spook::GeometryRef b = new spook::Geometry(new spook::Cylinder(r, 0.1), X);
    block->add(b);
    blockSheaves.push_back(b);
  }
  block->getMassProperties()->setMass(mass);
  block->getMassProperties()->setInertiaTensor(spook::SPDMat3(spook::Vec3(1e4, 1e4, 1e4)));
  sim->add(top);
  sim->add(block);
  // The block runs in a vertical guide (a dolly, as a drilling rig's): its
  // sheaves side by side would otherwise turn it under the tensions' gradient.
  sim->add(new spook::Prismatic(block, new spook::Frame()));
  spook::WireWinchControllerRef winch =
      new spook::WireWinchController(nullptr, spook::Vec3(-r, 0, 0), spook::Vec3(0, 0, 1));
  // Light (100 kg/m³: 7 kg over its 200 m) so that the capstan chain, which
  // leaves the wire's weight out, is the reference.
  spook::WireRef wire = steelWire(0.015, 1.0);
  wire->getMaterial()->getBulkMaterial()->setDensity(100);
  wire->getMaterial()->getWireMaterial()->setFrictionCoefficient(mu);
  wire->getMaterial()->getWireMaterial()->setYoungsModulusBend(0.0);
  wire->add(winch, 200.0);
  // Over the top of each crown sheave, under each block sheave (geometry
  // frames: the cylinders sit off the bodies' origins).
  for (int i = 0; i < 6; ++i) {
    wire->add(new spook::ContactNode(crownSheaves[std::size_t(i)], spook::Vec3(i, 0, crown + r)));
    wire->add(new spook::ContactNode(blockSheaves[std::size_t(i)], spook::Vec3(i + 0.5 - 2.75, 0, -r)));
  }
  wire->add(new spook::BodyFixedNode(nullptr, spook::Vec3(5.75, 0, crown)));
  sim->add(wire);
  winch->setForceRange(2e5);
  // Settle under the brake, then haul.
  for (int k = 0; k < 120; ++k) sim->stepForward();
  winch->setSpeed(-1.0);
  for (int k = 0; k < 60; ++k) sim->stepForward();
  const int steps = 120;
  double spent = 0.0, slowest = 0.0;
  const double from = block->getPosition().z();
  for (int k = 0; k < steps; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    sim->stepForward();
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
    spent += dt;
    slowest = std::max(slowest, dt);
  }
  double chain = 0.0;
  for (int k = 1; k <= 12; ++k) chain += std::exp(-k * mu * std::numbers::pi);
  Reeving out;
  out.mu = mu;
  out.meanMs = spent / steps;
  out.maxMs = slowest;
  out.winchTension = -winch->getCurrentForce();
  out.expected = mass * kGravity / chain;
  out.blockSpeed = (block->getPosition().z() - from) / (steps * sim->getTimeStep());
  out.nodes = wire->getNumMassNodes();
  out.contacts = 12;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::FILE* csv = argc > 1 ? std::fopen(argv[1], "w") : nullptr;
  if (csv) std::fprintf(csv, "scene,phase,mean_ms,max_ms,nodes_min,nodes_max,error\n");
  std::printf("1. 10 t paid out and hauled in over two hinged sheaves (100 m on the drum, 60 Hz)\n\n");
  std::printf("| phase | ms/step (mean, max) | mass nodes | tension at the load vs m g | load speed vs winch | "
              "load moved (m) | total length change (m) |\n|---|---|---|---|---|---|---|\n");
  for (const Phase& p : payOut()) {
    std::printf("| %s | %.3f, %.3f | %zu-%zu | %+.3f%% | %+.3f%% | %+.4f | %.1e |\n", p.name.c_str(), p.meanMs,
                p.maxMs, p.fewestNodes, p.mostNodes, 100 * p.tensionError, 100 * p.speedError, p.moved,
                p.lengthChange);
    if (csv)
      std::fprintf(csv, "payout,%s,%g,%g,%zu,%zu,%g\n", p.name.c_str(), p.meanMs, p.maxMs, p.fewestNodes, p.mostNodes,
                   p.tensionError);
  }
  std::printf("\n2. 12-fall reeving, 10 t hook block hauled at 1 m/s (12 sheaves, 60 Hz: real time is 16.7 ms/step)\n\n");
  std::printf("| mu | ms/step (mean, max) | winch tension (N) | W / sum e^(-k mu pi) (N) | error | block speed (m/s, "
              "1/12 of the winch's) | mass nodes |\n|---|---|---|---|---|---|---|\n");
  for (const double mu : {0.0, 0.05}) {
    const Reeving r = reeving(mu);
    std::printf("| %.2f | %.3f, %.3f | %.0f | %.0f | %+.2f%% | %.4f | %zu |\n", r.mu, r.meanMs, r.maxMs, r.winchTension,
                r.expected, 100 * (r.winchTension / r.expected - 1.0), r.blockSpeed, r.nodes);
    if (csv)
      std::fprintf(csv, "reeving,mu %.2f,%g,%g,%zu,%zu,%g\n", r.mu, r.meanMs, r.maxMs, r.nodes, r.nodes,
                   r.winchTension / r.expected - 1.0);
  }
  if (csv) std::fclose(csv);
  return 0;
}
