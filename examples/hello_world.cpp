// A 10 kg box dropped from 5 m: the smallest complete spook program.
#include <iostream>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(1.0 / 60.0);

  spook::RigidBodyRef body = new spook::RigidBody("box");
  body->getMassProperties()->setMass(10.0);
  body->setPosition(spook::Vec3(0, 0, 5));
  sim->add(body);

  sim->stepTo(sim->getTimeStamp() + 2.0);

  const spook::Vec3 p = body->getPosition();
  std::cout << body->getName() << " after " << sim->getTimeStamp() << " s: z = " << p.z()
            << " m, vz = " << body->getVelocity().z() << " m/s\n";
}
