// A four-wheeled vehicle on a height-field terrain: a box chassis on four
// cylinder wheels, each on a WheelJoint (steering locked, suspension
// locked), driven by the wheel motors up a 6° slope. Prints the speed and
// the wheels' contact forces; exits non-zero unless, at rest on the flat
// part, the wheels' normal forces sum to the vehicle's weight within 1 %.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <spook/spook.hpp>

namespace {

constexpr double kG = 9.80665;         // m/s²
constexpr double kWheelRadius = 0.3;   // m
constexpr double kSlopeDegrees = 6.0;  // the terrain's ramp

// 81 × 21 samples over 40 m × 10 m: flat for x < 0, a ramp of kSlopeDegrees
// from x = 0 to x = 10 m, flat again beyond.
spook::HeightField* makeTerrain() {
  const std::size_t nx = 81, ny = 21;
  const double sizeX = 40.0, sizeY = 10.0;
  std::vector<double> heights(nx * ny);
  const double slope = std::tan(kSlopeDegrees * spook::PI / 180.0);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) {
      const double x = -0.5 * sizeX + sizeX * double(i) / double(nx - 1);
      heights[i + nx * j] = slope * std::clamp(x, 0.0, 10.0);
    }
  return new spook::HeightField(nx, ny, sizeX, sizeY, heights);
}

// Sum of the normal forces (N) on `body` from its contacts.
double normalForce(const spook::Simulation& sim, const spook::RigidBody* body) {
  double sum = 0.0;
  for (const auto& contact : sim.getGeometryContacts())
    if (contact.rigidBody(0) == body || contact.rigidBody(1) == body)
      for (const auto& p : contact.points())
        if (p.getEnabled()) sum += p.getNormalForceMagnitude();
  return sum;
}

}  // namespace

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(1.0 / 60.0);
  sim->add(new spook::Geometry(makeTerrain(), spook::Transform::Identity(), "terrain"));

  // The chassis: 1.0 m × 0.5 m × 0.15 m half extents, its bottom 0.1 m above the axles.
  const double start = -8.0, axleHeight = kWheelRadius;
  spook::RigidBodyRef chassis = new spook::RigidBody("chassis");
  chassis->add(new spook::Geometry(new spook::Box(spook::Vec3(1.0, 0.5, 0.15)), spook::Transform::Identity(), "chassis"));
  chassis->setPosition(spook::Vec3(start, 0, axleHeight + 0.25));
  sim->add(chassis);

  std::vector<spook::RigidBodyRef> wheels;
  std::vector<spook::ref_ptr<spook::WheelJoint>> joints;
  for (const double x : {0.8, -0.8})
    for (const double y : {0.7, -0.7}) {
      spook::RigidBodyRef wheel = new spook::RigidBody("wheel");
      // The cylinder's axis is its y axis: the axle, across the vehicle.
      wheel->add(new spook::Geometry(new spook::Cylinder(kWheelRadius, 0.2), spook::Transform::Identity(), "wheel"));
      wheel->setPosition(spook::Vec3(start + x, y, axleHeight));
      sim->add(wheel);
      const spook::WheelJointFrame frame(spook::Vec3(start + x, y, axleHeight), spook::Y_AXIS, spook::Z_AXIS);
      spook::ref_ptr<spook::WheelJoint> joint = new spook::WheelJoint(frame, wheel.get(), chassis.get());
      joint->getLock1D(spook::WheelJoint::STEERING)->setEnable(true);
      auto* motor = joint->getMotor1D(spook::WheelJoint::WHEEL);
      motor->setEnable(true);  // at speed 0 it holds the wheel: the brake
      motor->setForceRange(-400.0, 400.0);
      sim->add(joint);
      wheels.push_back(wheel);
      joints.push_back(joint);
    }

  double mass = chassis->getMassProperties()->getMass();
  for (const auto& wheel : wheels) mass += wheel->getMassProperties()->getMass();
  const double weight = mass * kG;

  // At rest on the flat part: the wheels carry the whole weight.
  sim->stepTo(2.0);
  double carried = 0.0;
  for (const auto& wheel : wheels) carried += normalForce(*sim, wheel.get());
  const double error = (carried - weight) / weight;
  std::printf("at rest: weight %.1f N, wheels' normal forces %.1f N (%+.3f %%)\n", weight, carried, 100.0 * error);

  // Driving: the motors turn the wheels at 4 rad/s (1.2 m/s), over the ramp.
  for (const auto& joint : joints) joint->getMotor1D(spook::WheelJoint::WHEEL)->setSpeed(4.0);
  for (int second = 1; second <= 14; ++second) {
    sim->stepTo(2.0 + second);
    std::printf("t = %4.1f s  x = %6.2f m  speed = %5.2f m/s  wheel normal forces:", sim->getTimeStamp(),
                chassis->getPosition().x(), chassis->getVelocity().norm());
    for (const auto& wheel : wheels) std::printf(" %7.1f", normalForce(*sim, wheel.get()));
    std::printf(" N\n");
  }
  return std::abs(error) <= 0.01 ? 0 : 1;
}
