// The tennis-racket theorem in orbit: a T-handle spun about its intermediate
// principal axis flips over again and again (the Dzhanibekov effect), while
// spook keeps its angular momentum and kinetic energy. Beside it, a
// kinematic grapple moves to the handle's start pose with moveTo.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

namespace {

// A T-handle of two thin rods (kg, m): a cross bar along x and a stem along
// y. Principal moments about its center of mass: Iy < Ix < Iz, so the bar
// axis x is the intermediate one.
spook::Vec3 tHandleInertia() {
  const double barMass = 0.6, barLength = 0.12, stemMass = 0.3, stemLength = 0.08;
  const double stemOffset = 0.04 + 0.5 * stemLength;  // stem center from the bar's axis
  const double total = barMass + stemMass;
  const double cm = stemMass * stemOffset / total;  // along y
  const double bar = barMass * barLength * barLength / 12.0;
  const double stem = stemMass * stemLength * stemLength / 12.0;
  const double shift = barMass * cm * cm + stemMass * (stemOffset - cm) * (stemOffset - cm);
  return {shift + stem, bar, bar + stem + shift};
}

}  // namespace

int main() {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(1.0 / 60.0);
  sim->setUniformGravity(spook::Vec3::Zero());  // free flight

  spook::RigidBodyRef handle = new spook::RigidBody("t-handle");
  handle->getMassProperties()->setMass(0.9);
  handle->getMassProperties()->setInertiaTensor(tHandleInertia());
  handle->setAngularVelocity(spook::Vec3(6.0, 0.02, 0.02));  // about the intermediate axis x
  sim->add(handle);

  spook::RigidBodyRef grapple = new spook::RigidBody("grapple");
  grapple->setMotionControl(spook::RigidBody::KINEMATICS);
  grapple->setPosition(spook::Vec3(2.0, 0.0, 1.0));
  sim->add(grapple);
  grapple->moveTo(spook::makeTransform(spook::Vec3(0.0, 0.0, 0.3)), 4.0);

  const spook::Vec3 L0 = handle->getAngularMomentum();
  const double E0 = handle->getKineticEnergy();
  std::printf("  t (s)   bar axis · L/|L|      |ΔL|/|L|    ΔE/E       grapple z (m)\n");
  double previous = 1.0;
  int flips = 0;
  while (sim->getTimeStamp() < 12.0 - 1e-9) {
    sim->stepForward();
    const spook::Vec3 axis = handle->getRotation() * spook::Vec3::UnitX();
    const double alignment = axis.dot(L0) / L0.norm();
    if (alignment * previous < 0.0) ++flips;
    previous = alignment;
    if (sim->getStatistics().numSteps % 30 == 0)
      std::printf("%7.2f   %+18.4f   %10.2e  %+10.2e   %8.4f\n", sim->getTimeStamp(), alignment,
                  (handle->getAngularMomentum() - L0).norm() / L0.norm(), (handle->getKineticEnergy() - E0) / E0,
                  grapple->getPosition().z());
  }
  std::printf("\n%d half-flips of the handle in %.0f s; grapple %s its target.\n", flips, sim->getTimeStamp(),
              grapple->isMovingToTarget() ? "has not reached" : "sits on");
  return flips >= 2 ? 0 : 1;
}
