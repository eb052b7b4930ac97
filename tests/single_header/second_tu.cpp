// A second translation unit including the single header: any non-inline,
// non-template definition in it becomes a duplicate symbol at link time.
#include <spook/spook.hpp>

// Kinetic energy of a free body after `steps` steps at h (J); used by main.cpp.
double kineticEnergyAfter(int steps, double h) {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(h);
  spook::RigidBodyRef body = new spook::RigidBody("second");
  body->getMassProperties()->setMass(3.0);
  sim->add(body);
  for (int i = 0; i < steps; ++i) sim->stepForward();
  return 0.5 * 3.0 * body->getVelocity().squaredNorm();
}
