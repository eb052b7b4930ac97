// A box resting on a plane (seed 000, "Contact Reduction"): four contact
// points, each holding up a quarter of the box's weight. Exits non-zero when
// it does not (direct solver: each point carries m g / 4 to 1e-6).
#include <cmath>
#include <cstdio>

#include <spook/spook.hpp>

int main() {
  spook::SimulationRef simulation = new spook::Simulation();
  simulation->setSolver(new spook::DirectSolver());

  // The ground: a static plane through the origin, normal up.
  simulation->add(new spook::Geometry(new spook::Plane(spook::Vec3(0, 0, 1))));

  // A 1 m cube (half extents 0.5 m) resting on it.
  spook::GeometryRef geometry = new spook::Geometry(new spook::Box(spook::Vec3(0.5, 0.5, 0.5)));
  spook::RigidBodyRef box = new spook::RigidBody("box");
  box->add(geometry);
  box->setPosition(spook::Vec3(0, 0, 0.5));
  simulation->add(box);

  simulation->stepTo(simulation->getTimeStamp() + 2.0);

  const double quarter = box->getMassProperties()->getMass() * 9.80665 / 4.0;
  int points = 0;
  bool ok = true;
  for (const auto& contact : simulation->getGeometryContacts())
    for (const auto& point : contact.points()) {
      const double force = point.getNormalForceMagnitude();
      std::printf("point %d at (%+.2f, %+.2f, %+.2f): %.6f N\n", ++points, point.getPoint().x(), point.getPoint().y(),
                  point.getPoint().z(), force);
      ok = ok && std::abs(force / quarter - 1.0) < 1e-6;
    }
  std::printf("%d contact points, m g / 4 = %.6f N\n", points, quarter);
  return ok && points == 4 ? 0 : 1;
}
