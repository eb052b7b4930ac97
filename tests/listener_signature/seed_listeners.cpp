// The listeners of seed 000 spelled as there (apart from the namespace):
// they compile and are called. Built with SPOOK_PRE_BY_VALUE, a listener whose
// pre takes the time stamp by value (another signature, no override, so it
// would never be called) must fail to compile, stopped by the static_assert
// of spook::detail::requireStepCallbacks where the listener is added.
#include <cstdio>

#include <spook/spook.hpp>

namespace {

class MyStepEventListener : public spook::StepEventListener {
 public:
  MyStepEventListener() { setMask(PRE_COLLIDE | PRE_STEP | POST_STEP | LAST_STEP); }

  void preCollide(const spook::TimeStamp&) override { ++calls; }
  void pre(const spook::TimeStamp&) override { ++calls; }
  void post(const spook::TimeStamp&) override { ++calls; }
  void last(const spook::TimeStamp&) override { ++calls; }

  int calls = 0;
};

class MyContactEventListener : public spook::ContactEventListener {
 public:
  MyContactEventListener() { setMask(IMPACT | CONTACT | SEPARATION); }
  KeepContactPolicy impact(const spook::TimeStamp&, spook::GeometryContact*) override {
    ++impacts;
    return KEEP_CONTACT;
  }
  KeepContactPolicy contact(const spook::TimeStamp&, spook::GeometryContact*) override { return KEEP_CONTACT; }
  void separation(const spook::TimeStamp&, spook::GeometryPair&) override {}

  int impacts = 0;
};

#ifdef SPOOK_PRE_BY_VALUE
class ByValue : public spook::StepEventListener {
 public:
  void pre(double) {}
};
#endif

}  // namespace

int main() {
  spook::SimulationRef simulation = new spook::Simulation();
  simulation->add(new spook::Geometry(new spook::Plane(spook::Vec3(0, 0, 1))));
  spook::RigidBodyRef ball = new spook::RigidBody("ball");
  ball->add(new spook::Geometry(new spook::Sphere(0.5)));
  ball->setPosition(0, 0, 0.55);
  simulation->add(ball);
  spook::ref_ptr<MyStepEventListener> steps = new MyStepEventListener();
  spook::ref_ptr<MyContactEventListener> contacts = new MyContactEventListener();
  simulation->add(steps);
  simulation->add(contacts);
#ifdef SPOOK_PRE_BY_VALUE
  simulation->add(new ByValue());
#endif
  for (int i = 0; i < 30; ++i) simulation->stepForward();
  std::printf("step callbacks %d, impacts %d\n", steps->calls, contacts->impacts);
  return steps->calls == 4 * 30 && contacts->impacts >= 1 ? 0 : 1;
}
