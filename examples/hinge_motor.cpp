// A hinge motor (seed 000, "agx::Hinge"): a wheel on a hinge to a static
// base, driven by the motor at 1 rad/s. Exits non-zero unless the wheel
// turns at the set speed.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();

  spook::RigidBodyRef rb1 = new spook::RigidBody("wheel");
  rb1->add(new spook::Geometry(new spook::Cylinder(0.5, 0.2)));
  simulation->add(rb1);
  spook::RigidBodyRef rb2 = new spook::RigidBody("base");
  rb2->setMotionControl(spook::RigidBody::STATIC);
  simulation->add(rb2);

  // Constraint frame relative rb1.
  spook::FrameRef frame1 = new spook::Frame();
  // Constraint frame relative rb2.
  spook::FrameRef frame2 = new spook::Frame();

  // Create hinge given the two rigid bodies and their frames (axis: z).
  spook::HingeRef hinge = new spook::Hinge(rb1, frame1, rb2, frame2);
  // Enable the motor (default disabled) and set speed.
  hinge->getMotor1D()->setEnable(true);
  hinge->getMotor1D()->setSpeed(1);
  simulation->add(hinge);

  simulation->stepTo(simulation->getTimeStamp() + 1.0);

  // To read last torque applied by the motor.
  const double lastTorque = hinge->getMotor1D()->getCurrentForce();
  const double speed = hinge->getCurrentSpeed();
  std::printf("hinge speed %.6f rad/s (set 1), angle %.4f rad after %.2f s, last motor torque %.3g N m\n", speed,
              hinge->getAngle(), simulation->getTimeStamp(), lastTorque);
  return std::abs(speed - 1.0) < 1e-6 ? 0 : 1;
}
