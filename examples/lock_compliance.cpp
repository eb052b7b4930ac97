// A lock with compliance (seed 000, "agx::LockJoint"; seed 001 §12.1.3): a
// 1000 kg body locked to the world where it hangs, relaxed to a compliance
// of 3e-9 m/N, sags under its weight l by d = l · c (Hooke's law). Exits
// non-zero unless it does, to 1%.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();
  simulation->setSolver(new spook::DirectSolver());

  spook::RigidBodyRef rb1 = new spook::RigidBody("load");
  rb1->add(new spook::Geometry(new spook::Box(spook::Vec3(0.5, 0.5, 0.5))));
  rb1->getMassProperties()->setMass(1000.0);
  rb1->setPosition(spook::Vec3(2, 0, 2));
  simulation->add(rb1);

  // Create given position and axis in world coordinates.
  spook::Vec3 worldPos = spook::Vec3(2, 0, 2);
  spook::Vec3 worldAxis = spook::Vec3(0, 1, 0);
  spook::LockJointRef lock = spook::Constraint::createFromWorld<spook::LockJoint>(worldPos, worldAxis, rb1, nullptr);
  // Relax the lock in all six DOFs.
  lock->setCompliance(3E-9);
  simulation->add(lock);

  simulation->stepTo(simulation->getTimeStamp() + 2.0);

  const double load = rb1->getMassProperties()->getMass() * 9.80665;
  const double expected = load * 3E-9;
  const double sag = worldPos.z() - rb1->getPosition().z();
  std::printf("load %.2f N sags the lock %.6e m; load * compliance = %.6e m\n", load, sag, expected);
  return std::abs(sag / expected - 1.0) < 0.01 ? 0 : 1;
}
