// The seeds' steering listener (seed 001 §12.13.3): a StepEventListener
// steers an Ackermann front axle with the seeds' input, up to 1 rad. The
// seeds' Ackermann reaches only getMaximumSteeringAngle() = 0.513 rad, so
// larger requests are clamped to it. Exits non-zero unless the mechanism
// holds the clamped angle and the wheels follow it.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

class SteeringListener : public spook::StepEventListener {
 public:
  explicit SteeringListener(spook::Ackermann* ackermann) : spook::StepEventListener(PRE_STEP), ackermann(ackermann) {}
  void pre(const spook::TimeStamp& t) override {
    if (t < 1.0) {
      ackermann->setSteeringAngle(t);
    } else if (t <= 3.0) {
      ackermann->setSteeringAngle(1 - (t - 1) / 2);
    } else {
      ackermann->setSteeringAngle(0.0);
    }
  }

 private:
  spook::AckermannRef ackermann;
};

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setSolver(new spook::DirectSolver());

  // A static chassis and two 15 kg wheels on wheel joints 1.5 m apart
  // (x forward, y left, z up: wheel axles along y, steering axes along z).
  spook::RigidBodyRef chassis = new spook::RigidBody("chassis");
  chassis->setMotionControl(spook::RigidBody::STATIC);
  sim->add(chassis);
  spook::WheelJointRef wheelJoints[2];
  for (int i = 0; i < 2; ++i) {
    const double side = i == 0 ? 1.0 : -1.0;  // left, right
    spook::RigidBodyRef wheel = new spook::RigidBody(i == 0 ? "left wheel" : "right wheel");
    wheel->add(new spook::Geometry(new spook::Cylinder(0.3, 0.2)));
    wheel->getMassProperties()->setMass(15.0);
    wheel->setPosition(spook::Vec3(0, side * 0.85, 0));
    sim->add(wheel);
    wheelJoints[i] = new spook::WheelJoint(
        spook::WheelJointFrame(spook::Vec3(0, side * 0.75, 0), spook::Y_AXIS, spook::Z_AXIS), wheel, chassis);
    sim->add(wheelJoints[i]);
  }

  spook::AckermannRef ackermann = new spook::Ackermann(wheelJoints[0], wheelJoints[1]);
  sim->add(ackermann);
  sim->add(new SteeringListener(ackermann));

  const double maximum = ackermann->getMaximumSteeringAngle();
  std::printf("Ackermann reaches +-%.3f rad\n", maximum);
  bool ok = true;
  while (sim->getTimeStamp() < 4.0) {
    sim->stepForward();
    const double asked = ackermann->getRequestedSteeringAngle(), held = ackermann->getSteeringAngle();
    const double left = wheelJoints[0]->getAngle(spook::WheelJoint::STEERING);
    ok = ok && held == std::clamp(asked, -maximum, maximum) &&
         std::abs(left - ackermann->getWheelAngles().left) < 0.05;
    if (std::lround(sim->getTimeStamp() * 60) % 30 == 0)
      std::printf("t = %.1f s: asked %.3f rad, held %.3f rad, left wheel %.3f rad, right wheel %.3f rad\n",
                  sim->getTimeStamp(), asked, held, left, wheelJoints[1]->getAngle(spook::WheelJoint::STEERING));
  }
  return ok ? 0 : 1;
}
