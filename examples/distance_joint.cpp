// A DistanceJoint as a spring (seed 001 §12.7, example 1): a 10 kg body
// hanging 1 m below a world point on a DistanceJoint of compliance 1e-4 m/N
// stretches by m g c. Exits non-zero unless it does, to 1%.
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();
  simulation->setSolver(new spook::DirectSolver());

  spook::RigidBodyRef body1 = new spook::RigidBody("weight");
  body1->add(new spook::Geometry(new spook::Sphere(0.1)));
  body1->getMassProperties()->setMass(10.0);
  body1->setPosition(spook::Vec3(0, 0, 9));
  simulation->add(body1);

  // Position in the world where the attachment of the distance joint is
  spook::Vec3 worldConnectPoint(0.0, 0.0, 10.0);
  spook::FrameRef frame = new spook::Frame();  // Other end of joint is at origo of rigid body
  spook::DistanceJointRef d = new spook::DistanceJoint(body1, frame, worldConnectPoint);
  // One DOF (the distance); its compliance makes the joint a spring of k = 1/c.
  d->setCompliance(1E-4);
  simulation->add(d);

  simulation->stepTo(simulation->getTimeStamp() + 4.0);

  const double stretch = d->getAngle() - 1.0;
  const double expected = body1->getMassProperties()->getMass() * 9.80665 * 1E-4;
  std::printf("DistanceJoint: %d DOF, stretched %.6e m; m g c = %.6e m\n", d->getNumDOF(), stretch, expected);
  return d->getNumDOF() == 1 && std::abs(stretch / expected - 1.0) < 0.01 ? 0 : 1;
}
