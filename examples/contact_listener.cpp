// The seeds' contact listener (seed 000, "agxSDK::ContactEventListener"): a
// capsule dropped on a static slab. The impact is kept; every later contact
// is removed from the solver, so the capsule sinks through the slab and
// separates from it. Prints the events and their counts; exits non-zero
// unless there is one impact, contacts, one separation and the capsule ends
// below the slab.
#include <cstdio>

#include <spook/spook.hpp>

class MyContactEventListener : public spook::ContactEventListener {
 public:
  MyContactEventListener() { setMask(IMPACT | CONTACT | SEPARATION); }
  KeepContactPolicy impact(const spook::TimeStamp& t, spook::GeometryContact* /*gc*/) override {
    // Contact kept if impacting (i.e., the geometries didn't overlap last update).
    std::printf("impact:     %.5f s\n", t);
    ++impacts;
    return KEEP_CONTACT;
  }
  KeepContactPolicy contact(const spook::TimeStamp& t, spook::GeometryContact* /*gc*/) override {
    // Remove contact: the solver won't see it.
    std::printf("contact:    %.5f s\n", t);
    ++contacts;
    return REMOVE_CONTACT;
  }
  void separation(const spook::TimeStamp& t, spook::GeometryPair& /*gp*/) override {
    // The geometries don't overlap anymore.
    std::printf("separation: %.5f s\n", t);
    ++separations;
  }
  int impacts = 0, contacts = 0, separations = 0;

 protected:
  ~MyContactEventListener() override = default;
};

int main() {
  spook::SimulationRef simulation = new spook::Simulation();

  // A static slab 0.1 m thick, its top at z = 0.
  spook::GeometryRef ground = new spook::Geometry(new spook::Box(spook::Vec3(2, 2, 0.05)));
  ground->setPosition(spook::Vec3(0, 0, -0.05));
  simulation->add(ground);

  spook::RigidBodyRef capsule = new spook::RigidBody("capsule");
  capsule->add(new spook::Geometry(new spook::Capsule(0.05, 0.3)));
  capsule->setPosition(spook::Vec3(0, 0, 1));
  simulation->add(capsule);

  spook::ref_ptr<MyContactEventListener> listener = new MyContactEventListener();
  simulation->add(listener);

  simulation->stepTo(simulation->getTimeStamp() + 1.5);

  std::printf("%d impact(s), %d contact(s), %d separation(s); capsule at z = %.2f m\n", listener->impacts,
              listener->contacts, listener->separations, capsule->getPosition().z());
  const bool ok = listener->impacts == 1 && listener->contacts > 0 && listener->separations == 1 &&
                  capsule->getPosition().z() < -0.1;
  return ok ? 0 : 1;
}
