#include <doctest/doctest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

/// A listener that writes "name.stage" to a shared log, keeps the time
/// stamps it received, and runs an optional hook per stage.
template <class S>
class Probe : public spook::StepEventListenerT<S> {
 public:
  using Listener = spook::StepEventListenerT<S>;
  using Hook = std::function<void(S)>;

  Probe(std::string name, std::vector<std::string>* log, std::uint32_t mask = Listener::DEFAULT, int priority = 0)
      : Listener(mask, priority), name_(std::move(name)), log_(log) {}

  void preCollide(S t) override { call("preCollide", t, onPreCollide); }
  void pre(S t) override { call("pre", t, onPre); }
  void post(S t) override { call("post", t, onPost); }
  void last(S t) override { call("last", t, onLast); }

  Hook onPreCollide, onPre, onPost, onLast;
  std::vector<S> times;

 protected:
  ~Probe() override = default;

 private:
  void call(const char* stage, S t, const Hook& hook) {
    if (log_) log_->push_back(name_ + "." + stage);
    times.push_back(t);
    if (hook) hook(t);
  }

  std::string name_;
  std::vector<std::string>* log_;
};

template <class S>
struct Scene {
  using Body = spook::RigidBodyT<S>;
  using Listener = spook::StepEventListenerT<S>;
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  std::vector<std::string> log;

  spook::ref_ptr<Probe<S>> probe(std::string name, std::uint32_t mask = Listener::DEFAULT, int priority = 0) {
    spook::ref_ptr<Probe<S>> p = new Probe<S>(std::move(name), &log, mask, priority);
    sim->add(p);
    return p;
  }
  spook::ref_ptr<Body> body(std::string name) {
    spook::ref_ptr<Body> b = new Body(std::move(name));
    sim->add(b);
    return b;
  }
  /// The log as one line, then cleared: "a.pre b.pre a.post".
  std::string calls() {
    std::string line;
    for (const auto& entry : log) line += (line.empty() ? "" : " ") + entry;
    log.clear();
    return line;
  }
  spook::Vec3T<S> gravity() const { return spook::Vec3T<S>(S(0), S(0), S(-9.80665)); }
};

}  // namespace

TEST_CASE_TEMPLATE("a new simulation steps 1/60 s under uniform gravity (0, 0, -9.80665) m/s^2", S, float, double) {
  Scene<S> scene;
  CHECK(scene.sim->getTimeStep() == S(1) / S(60));
  CHECK(scene.sim->getTimeStamp() == S(0));
  CHECK(scene.sim->getStatistics().numSteps == 0);
  const auto* field = dynamic_cast<const spook::UniformGravityFieldT<S>*>(scene.sim->getGravityField());
  REQUIRE(field != nullptr);
  CHECK(field->getGravity() == scene.gravity());

  auto body = scene.body("crate");
  scene.sim->stepForward();
  CHECK((body->getVelocity() - scene.sim->getTimeStep() * scene.gravity()).norm() < pick<S>(1e-15, 1e-7));
}

TEST_CASE_TEMPLATE("stepForward advances the time stamp by h and counts the step", S, float, double) {
  Scene<S> scene;
  scene.sim->setTimeStep(S(0.25));
  scene.sim->stepForward();
  CHECK(scene.sim->getTimeStamp() == S(0.25));
  scene.sim->stepForward();
  scene.sim->stepForward();
  CHECK(scene.sim->getTimeStamp() == S(0.75));
  CHECK(scene.sim->getStatistics().numSteps == 3);
}

TEST_CASE_TEMPLATE("stepTo(t) takes round((t - now) / h) steps", S, float, double) {
  Scene<S> scene;
  scene.sim->setTimeStep(S(0.1));
  scene.sim->stepTo(S(0.26));  // 2.6 steps → 3
  CHECK(scene.sim->getStatistics().numSteps == 3);
  scene.sim->stepTo(scene.sim->getTimeStamp() + S(0.14));  // 1.4 steps → 1
  CHECK(scene.sim->getStatistics().numSteps == 4);
  scene.sim->stepTo(scene.sim->getTimeStamp() + S(0.04));  // 0.4 steps → none
  CHECK(scene.sim->getStatistics().numSteps == 4);
  CHECK(scene.sim->getTimeStamp() == doctest::Approx(0.4).epsilon(pick<S>(1e-14, 1e-6)));
}

TEST_CASE_TEMPLATE("stepTo(t) lands on t when t is a whole number of steps away", S, float, double) {
  Scene<S> scene;
  scene.sim->stepTo(S(1));
  CHECK(scene.sim->getStatistics().numSteps == 60);
  CHECK(std::abs(scene.sim->getTimeStamp() - S(1)) < pick<S>(1e-12, 1e-5));
  scene.sim->stepTo(S(2.5));
  CHECK(scene.sim->getStatistics().numSteps == 150);
  CHECK(std::abs(scene.sim->getTimeStamp() - S(2.5)) < pick<S>(1e-12, 1e-5));
}

// A target more than 2³¹ steps away is refused before the first step (it
// would run for days: 1e9 s at 60 Hz is 6e10 steps); stepTo(now) takes none.
TEST_CASE_TEMPLATE("stepTo a time more than 2^31 steps away throws before stepping; stepTo(now) does nothing", S, float,
                   double) {
  Scene<S> scene;
  auto probe = scene.probe("probe");
  scene.sim->stepForward();
  // Any further step fails the test at once instead of hanging it.
  probe->onPre = [](S) { throw std::logic_error("stepTo stepped"); };
  const S now = scene.sim->getTimeStamp();
  const S h = scene.sim->getTimeStep();
  for (const S t : {S(1e9), S(1e12), std::numeric_limits<S>::max(), now + S(2.01) * S(1u << 30) * h}) {
    CAPTURE(t);
    std::string what = "(no spook::Error)";
    try {
      scene.sim->stepTo(t);
    } catch (const spook::Error& e) {
      what = e.what();
    } catch (const std::logic_error& e) {
      what = e.what();
    }
    MESSAGE("stepTo(", t, "): ", what);
    CHECK(what.find("Simulation") != std::string::npos);
    CHECK(what.find("2^31") != std::string::npos);
    std::array<char, 64> printed{};
    const auto end = std::to_chars(printed.data(), printed.data() + printed.size(), t).ptr;
    CHECK(what.find("got " + std::string(printed.data(), end)) != std::string::npos);
  }
  CHECK(scene.sim->getStatistics().numSteps == 1);
  CHECK(scene.sim->getTimeStamp() == now);
  CHECK_NOTHROW(scene.sim->stepTo(now));
  CHECK(scene.sim->getStatistics().numSteps == 1);
}

// Summing h 6000 times in float drifts by 7e-3 s (0.4 h); n·h does not.
TEST_CASE_TEMPLATE("after 6000 steps of 1/60 s the time stamp is 100 s to round-off", S, float, double) {
  Scene<S> scene;
  scene.sim->stepTo(S(100));
  CHECK(scene.sim->getStatistics().numSteps == 6000);
  CHECK(std::abs(scene.sim->getTimeStamp() - S(100)) < S(100) * pick<S>(1e-12, 1e-5));
}

TEST_CASE_TEMPLATE("each step calls preCollide, pre, post, last, all with the start-of-step time", S, float, double) {
  Scene<S> scene;
  auto probe = scene.probe("a");
  const S h = scene.sim->getTimeStep();
  scene.sim->stepForward();
  scene.sim->stepForward();
  CHECK(scene.calls() == "a.preCollide a.pre a.post a.last a.preCollide a.pre a.post a.last");
  CHECK(probe->times == std::vector<S>{S(0), S(0), S(0), S(0), h, h, h, h});
}

TEST_CASE_TEMPLATE("the mask selects the callbacks a listener receives; a disabled one receives none", S, float,
                   double) {
  using L = spook::StepEventListenerT<S>;
  Scene<S> scene;
  auto probe = scene.probe("a", L::PRE_STEP | L::LAST_STEP);
  scene.sim->stepForward();
  CHECK(scene.calls() == "a.pre a.last");
  probe->setMask(L::PRE_COLLIDE | L::POST_STEP);
  scene.sim->stepForward();
  CHECK(scene.calls() == "a.preCollide a.post");
  probe->setMask(0);
  scene.sim->stepForward();
  CHECK(scene.calls() == "");
  probe->setMask(L::DEFAULT);
  probe->setEnable(false);
  scene.sim->stepForward();
  CHECK(scene.calls() == "");
}

TEST_CASE_TEMPLATE("higher priority is called first, equal priorities in the order added", S, float, double) {
  using L = spook::StepEventListenerT<S>;
  Scene<S> scene;
  scene.probe("a", L::PRE_STEP, 0);
  scene.probe("b", L::PRE_STEP, 10);
  scene.probe("c", L::PRE_STEP, 0);
  scene.probe("d", L::PRE_STEP, -5);
  scene.probe("e", L::PRE_STEP, 10);
  scene.sim->stepForward();
  CHECK(scene.calls() == "b.pre e.pre a.pre c.pre d.pre");
}

TEST_CASE_TEMPLATE("a listener that removes itself in pre() gets no post() or last(), and the step completes", S, float,
                   double) {
  Scene<S> scene;
  auto self = scene.probe("self");
  scene.probe("other");
  auto* sim = scene.sim.get();
  self->onPre = [sim, l = self.get()](S) { sim->remove(l); };
  scene.sim->stepForward();
  CHECK(scene.calls() == "self.preCollide other.preCollide self.pre other.pre other.post other.last");
  CHECK(self->getSimulation() == nullptr);
  scene.sim->stepForward();
  CHECK(scene.calls() == "other.preCollide other.pre other.post other.last");
  CHECK(scene.sim->getStatistics().numSteps == 2);
}

TEST_CASE_TEMPLATE("a body added in pre() falls in the same step: v = h g", S, float, double) {
  Scene<S> scene;
  auto adder = scene.probe("adder");
  spook::ref_ptr<spook::RigidBodyT<S>> late = new spook::RigidBodyT<S>("late");
  adder->onPre = [sim = scene.sim.get(), body = late.get()](S) {
    if (!sim->contains(body)) sim->add(body);
  };
  const S h = scene.sim->getTimeStep();
  scene.sim->stepForward();
  CHECK(scene.sim->contains(late));
  CHECK((late->getVelocity() - h * scene.gravity()).norm() < pick<S>(1e-15, 1e-7));
  CHECK(std::abs(late->getPosition().z() - h * h * scene.gravity().z()) < pick<S>(1e-16, 1e-8));
}

// A listener added during a stage is not called in that stage (the stage
// runs over the listeners it started with) but from the next stage on: added
// in pre() of the first step, it receives post() and last() of that step.
TEST_CASE_TEMPLATE("a listener added in a callback is called from the next stage on", S, float, double) {
  Scene<S> scene;
  auto adder = scene.probe("adder");
  spook::ref_ptr<Probe<S>> late = new Probe<S>("late", &scene.log);
  adder->onPre = [sim = scene.sim.get(), l = late.get()](S) {
    if (!l->getSimulation()) sim->add(l);
  };
  const S h = scene.sim->getTimeStep();
  scene.sim->stepForward();
  CHECK(scene.calls() == "adder.preCollide adder.pre adder.post late.post adder.last late.last");
  scene.sim->stepForward();
  CHECK(scene.calls() ==
        "adder.preCollide late.preCollide adder.pre late.pre adder.post late.post adder.last late.last");
  CHECK(late->times == std::vector<S>{S(0), S(0), h, h, h, h});
}

TEST_CASE_TEMPLATE("a body removed in post() has moved in that step and moves no more", S, float, double) {
  Scene<S> scene;
  auto body = scene.body("crate");
  auto remover = scene.probe("remover");
  remover->onPost = [sim = scene.sim.get(), b = body.get()](S) {
    if (sim->contains(b)) sim->remove(b);
  };
  scene.sim->stepForward();
  CHECK(!scene.sim->contains(body));
  CHECK(scene.sim->getRigidBodies().empty());
  CHECK(body->getPosition().z() < S(0));
  const spook::Vec3T<S> position = body->getPosition();
  scene.sim->stepForward();
  CHECK(body->getPosition() == position);
}

TEST_CASE_TEMPLATE("a force added in post() acts in the next step, then is cleared", S, float, double) {
  Scene<S> scene;
  scene.sim->setUniformGravity(spook::Vec3T<S>::Zero());
  auto body = scene.body("crate");
  body->getMassProperties()->setMass(S(2));
  const spook::Vec3T<S> force(S(4), S(0), S(-2));
  auto pusher = scene.probe("pusher");
  pusher->onPost = [b = body.get(), force, steps = 0](S) mutable {
    if (steps++ == 0) b->addForce(force);
  };
  const S h = scene.sim->getTimeStep();
  scene.sim->stepForward();
  CHECK(body->getVelocity() == spook::Vec3T<S>::Zero());
  CHECK(body->getForce() == force);
  scene.sim->stepForward();
  CHECK((body->getVelocity() - h * force / S(2)).norm() < pick<S>(1e-15, 1e-7));
  CHECK(body->getForce() == spook::Vec3T<S>::Zero());
}

// A step is taken whole with the h it started with: after the bodies were
// integrated with h, the clock must advance by h too.
TEST_CASE_TEMPLATE("a time step changed in post() applies from the next step", S, float, double) {
  Scene<S> scene;
  auto body = scene.body("crate");
  auto changer = scene.probe("changer");
  changer->onPost = [sim = scene.sim.get()](S) { sim->setTimeStep(S(0.5)); };
  const S h = scene.sim->getTimeStep(), tol = pick<S>(1e-14, 1e-6);
  scene.sim->stepForward();
  CHECK(std::abs(scene.sim->getTimeStamp() - h) < tol);
  CHECK((body->getVelocity() - h * scene.gravity()).norm() < tol);
  scene.sim->stepForward();
  CHECK(std::abs(scene.sim->getTimeStamp() - (h + S(0.5))) < tol);
  CHECK((body->getVelocity() - (h + S(0.5)) * scene.gravity()).norm() < tol);
}

TEST_CASE_TEMPLATE("getRigidBody finds a body of the simulation by its name", S, float, double) {
  Scene<S> scene;
  auto crate = scene.body("crate");
  auto barrel = scene.body("barrel");
  CHECK(scene.sim->getRigidBody("barrel") == barrel.get());
  CHECK(scene.sim->getRigidBody("crate") == crate.get());
  CHECK(scene.sim->getRigidBody("pallet") == nullptr);
  scene.sim->remove(barrel);
  CHECK(scene.sim->getRigidBody("barrel") == nullptr);
}

TEST_CASE_TEMPLATE("a body belongs to at most one simulation", S, float, double) {
  Scene<S> first, second;
  auto body = first.body("crate");
  CHECK_THROWS_AS(second.sim->add(body), spook::Error);
  CHECK(second.sim->getRigidBodies().empty());
  CHECK(!second.sim->contains(body));
  CHECK(first.sim->contains(body));
  second.sim->stepForward();
  CHECK(body->getVelocity() == spook::Vec3T<S>::Zero());
}

TEST_CASE_TEMPLATE("a removed body can be added again, to another simulation or the same", S, float, double) {
  Scene<S> first, second;
  auto body = first.body("crate");
  first.sim->remove(body);
  second.sim->add(body);
  CHECK(second.sim->contains(body));
  first.sim->stepForward();
  CHECK(body->getVelocity() == spook::Vec3T<S>::Zero());
  second.sim->stepForward();
  CHECK(body->getVelocity().z() < S(0));
  second.sim->remove(body);
  first.sim->add(body);
  CHECK(first.sim->contains(body));
  CHECK(first.sim->getRigidBodies().size() == 1);
}

TEST_CASE_TEMPLATE("removing bodies in any order keeps the others in the simulation", S, float, double) {
  Scene<S> scene;
  auto a = scene.body("a");
  auto b = scene.body("b");
  auto c = scene.body("c");
  scene.sim->remove(a);
  scene.sim->remove(c);
  REQUIRE(scene.sim->getRigidBodies().size() == 1);
  CHECK(scene.sim->getRigidBodies()[0] == b.get());
  CHECK(scene.sim->contains(b));
  CHECK(!scene.sim->contains(a));
  CHECK(!scene.sim->contains(c));
  scene.sim->stepForward();
  CHECK(b->getVelocity().z() < S(0));
  CHECK(a->getVelocity() == spook::Vec3T<S>::Zero());
  CHECK(c->getVelocity() == spook::Vec3T<S>::Zero());
}

TEST_CASE_TEMPLATE("a disabled body and a static body do not move", S, float, double) {
  Scene<S> scene;
  auto disabled = scene.body("disabled");
  disabled->setVelocity(S(1), S(2), S(3));
  disabled->setEnable(false);
  auto fixed = scene.body("fixed");
  fixed->setMotionControl(spook::RigidBodyT<S>::STATIC);
  fixed->setVelocity(S(1), S(2), S(3));
  const spook::TransformT<S> disabledPose = disabled->getTransform(), fixedPose = fixed->getTransform();
  for (int i = 0; i < 10; ++i) {
    fixed->addForce(S(100), S(0), S(0));
    fixed->addTorque(S(0), S(100), S(0));
    scene.sim->stepForward();
  }
  CHECK(disabled->getTransform().matrix() == disabledPose.matrix());
  CHECK(disabled->getVelocity() == spook::Vec3T<S>(S(1), S(2), S(3)));
  CHECK(fixed->getTransform().matrix() == fixedPose.matrix());
  CHECK(fixed->getVelocity() == spook::Vec3T<S>::Zero());
  CHECK(fixed->getAngularVelocity() == spook::Vec3T<S>::Zero());
}

TEST_CASE_TEMPLATE("stepForward or stepTo from inside a callback throws and the outer step completes", S, float,
                   double) {
  Scene<S> scene;
  auto probe = scene.probe("reentrant");
  int thrown = 0;
  probe->onPre = [sim = scene.sim.get(), &thrown](S now) {
    CHECK_THROWS_AS(sim->stepForward(), spook::Error);
    CHECK_THROWS_AS(sim->stepTo(now + S(1)), spook::Error);
    ++thrown;
  };
  scene.sim->stepForward();
  CHECK(thrown == 1);
  CHECK(scene.calls() == "reentrant.preCollide reentrant.pre reentrant.post reentrant.last");
  CHECK(scene.sim->getTimeStamp() == scene.sim->getTimeStep());
  CHECK(scene.sim->getStatistics().numSteps == 1);
  probe->onPre = nullptr;
  scene.sim->stepForward();  // the guard was reset: stepping works again
  CHECK(scene.sim->getStatistics().numSteps == 2);
}

TEST_CASE_TEMPLATE("a listener knows its simulation while it is added and not after", S, float, double) {
  Scene<S> scene;
  spook::ref_ptr<Probe<S>> probe = new Probe<S>("a", nullptr);
  CHECK(probe->getSimulation() == nullptr);
  scene.sim->add(probe);
  CHECK(probe->getSimulation() == scene.sim.get());
  scene.sim->remove(probe);
  CHECK(probe->getSimulation() == nullptr);
  CHECK(scene.sim->getEventListeners().empty());
}

TEST_CASE_TEMPLATE("objects outlive a destroyed simulation and can join a new one", S, float, double) {
  auto sim = spook::ref_ptr<spook::SimulationT<S>>(new spook::SimulationT<S>());
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("crate");
  spook::ref_ptr<spook::RigidBodyT<S>> boxed = new spook::RigidBodyT<S>("boxed");
  spook::ref_ptr<Probe<S>> probe = new Probe<S>("a", nullptr);
  spook::ref_ptr<spook::CollectionT<S>> collection = new spook::CollectionT<S>("stack");
  collection->add(boxed);
  sim->add(body);
  sim->add(probe);
  sim->add(collection);
  sim->stepForward();
  spook::observer_ptr<spook::SimulationT<S>> watch(sim.get());

  sim = nullptr;
  CHECK(watch == nullptr);
  CHECK(body->getReferenceCount() == 1);
  CHECK(probe->getSimulation() == nullptr);

  spook::ref_ptr<spook::SimulationT<S>> next = new spook::SimulationT<S>();
  next->add(body);
  next->add(probe);
  next->add(collection);
  CHECK(next->contains(boxed));
  const S vz = body->getVelocity().z();
  next->stepForward();
  CHECK(body->getVelocity().z() < vz);
  CHECK(probe->times.size() == 8);
}
