// Contact events: a capsule falls onto a static ground and comes to rest on
// it (the contacts carry its weight), and a listener prints the impact, the
// contacts and the separation once the capsule is lifted.
#include <cstdio>

#include <spook/collide/collide_through.hpp>  // the colliders of a shape list of its own
#include <spook/spook.hpp>

namespace {

class Reporter : public spook::ContactEventListener {
 public:
  KeepContactPolicy impact(const spook::TimeStamp& t, spook::GeometryContact* contact) override {
    std::printf("%.3f s  impact      %zu point(s), depth %.4f m\n", t, contact->points().size(), deepest(*contact));
    return KEEP_CONTACT;
  }
  KeepContactPolicy contact(const spook::TimeStamp& t, spook::GeometryContact* contact) override {
    std::printf("%.3f s  contact     %zu point(s), depth %.4f m\n", t, contact->points().size(), deepest(*contact));
    return KEEP_CONTACT;
  }
  void separation(const spook::TimeStamp& t, spook::GeometryPair&) override { std::printf("%.3f s  separation\n", t); }

 private:
  static double deepest(const spook::GeometryContact& contact) {
    double depth = 0;
    for (const auto& p : contact.points()) depth = std::max(depth, p.depth);
    return depth;
  }
};

}  // namespace

int main() {
  // Only capsules and planes in this scene: only their colliders are compiled.
  spook::SimulationRef sim = new spook::Simulation(spook::ShapeList<spook::CapsuleT, spook::PlaneT>{});
  sim->add(new spook::Geometry(new spook::Plane(spook::Vec3(0, 0, 1))));

  spook::RigidBodyRef capsule = new spook::RigidBody("capsule");
  const spook::Quat lying(Eigen::AngleAxisd(0.5 * 3.141592653589793, spook::Vec3::UnitZ()));
  capsule->add(new spook::Geometry(new spook::Capsule(0.1, 0.6), spook::makeTransform(spook::Vec3(0, 0, 0), lying)));
  capsule->setPosition(0, 0, 0.15);
  sim->add(capsule);
  sim->add(new Reporter());

  std::printf("capsule of %.2f kg (density 1000 kg/m^3)\n", capsule->getMassProperties()->getMass());
  for (int step = 0; step < 30; ++step) sim->stepForward();
  double normalForce = 0;
  for (const auto& contact : sim->getGeometryContacts())
    for (const auto& p : contact.points()) normalForce += p.getNormalForceMagnitude();
  std::printf("resting: normal force %.2f N, weight %.2f N\n", normalForce,
              capsule->getMassProperties()->getMass() * 9.80665);
  capsule->setPosition(0, 0, 2);  // lift it clear
  capsule->setVelocity(0, 0, 0);
  sim->stepForward();
  sim->stepForward();
}
