#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include <spook/collide/collide_through.hpp>  // the colliders of a shape list of its own
#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

namespace {

template <class S>
class Recorder : public spook::ContactEventListenerT<S> {
 public:
  using Base = spook::ContactEventListenerT<S>;
  explicit Recorder(typename Base::KeepContactPolicy policy = Base::KEEP_CONTACT) : policy_(policy) {}

  typename Base::KeepContactPolicy impact(const spook::TimeStampT<S>&, spook::GeometryContactT<S>* contact) override {
    return record("impact", *contact);
  }
  typename Base::KeepContactPolicy contact(const spook::TimeStampT<S>&, spook::GeometryContactT<S>* contact) override {
    return record("contact", *contact);
  }
  void separation(const spook::TimeStampT<S>&, spook::GeometryPairT<S>&) override { events.push_back("separation"); }

  std::vector<std::string> events;
  std::vector<S> depths;
  std::vector<bool> enabled;  ///< isEnabled() of each impact or contact as this listener saw it

 private:
  typename Base::KeepContactPolicy record(const char* event, const spook::GeometryContactT<S>& contact) {
    events.push_back(event);
    depths.push_back(maxDepth(contact));
    enabled.push_back(contact.isEnabled());
    return policy_;
  }
  static S maxDepth(const spook::GeometryContactT<S>& c) {
    S depth = S(0);
    for (const auto& p : c.points()) depth = std::max(depth, p.depth);
    return depth;
  }
  typename Base::KeepContactPolicy policy_;
};

template <class S>
struct DropScene {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::GeometryT<S>> ground =
      new spook::GeometryT<S>(new spook::PlaneT<S>(spook::Vec3T<S>::UnitZ()), spook::TransformT<S>::Identity(), "ground");
  spook::ref_ptr<spook::RigidBodyT<S>> capsule = new spook::RigidBodyT<S>("capsule");

  // A capsule (radius 0.1 m, lying along x) released with its lowest point
  // 0.05 m above the ground: free fall reaches it after √(2·0.05/g) ≈ 0.101 s.
  DropScene() {
    sim->add(ground);
    const spook::QuatT<S> lying(Eigen::AngleAxis<S>(S(1.5707963267948966), spook::Vec3T<S>::UnitZ()));
    capsule->add(new spook::GeometryT<S>(new spook::CapsuleT<S>(S(0.1), S(0.6)),
                                         spook::makeTransform<S>(spook::Vec3T<S>::Zero(), lying), "capsule"));
    capsule->setPosition(S(0), S(0), S(0.15));
    sim->add(capsule);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("a capsule dropped on the ground impacts, stays in contact, then separates when lifted", S, float,
                   double) {
  DropScene<S> scene;
  spook::ref_ptr<Recorder<S>> recorder = new Recorder<S>();
  scene.sim->add(recorder);
  int firstImpactStep = -1;
  for (int step = 0; step < 12 && firstImpactStep < 0; ++step) {
    scene.sim->stepForward();
    if (!recorder->events.empty()) firstImpactStep = step;
  }
  // Symplectic Euler free fall: after n steps the lowest point is at
  // 0.05 − g h² n(n+1)/2 (h = 1/60 s), below 0 first for n = 6; the
  // collision pass of step index 6 sees it.
  CHECK(firstImpactStep == 6);
  scene.sim->stepForward();
  scene.sim->stepForward();
  scene.capsule->setPosition(S(0), S(0), S(3));  // lifted clear
  scene.capsule->setVelocity(S(0), S(0), S(0));
  scene.sim->stepForward();
  scene.sim->stepForward();
  CHECK(recorder->events == std::vector<std::string>{"impact", "contact", "contact", "separation"});
  CHECK(recorder->depths[0] > S(0));
  CHECK(recorder->depths[1] <= recorder->depths[0]);  // solved: it stops sinking
}

// Seed 000 (ContactEventListener): a contact removed by one listener is
// removed from the solver, but the other listeners still see it (disabled).
TEST_CASE_TEMPLATE("REMOVE_CONTACT takes the contact from the solver; every other listener still sees it, disabled",
                   S, float, double) {
  using Listener = spook::ContactEventListenerT<S>;
  for (const bool removerFirst : {true, false}) {
    CAPTURE(removerFirst);
    DropScene<S> scene;
    spook::ref_ptr<Recorder<S>> remover = new Recorder<S>(Listener::REMOVE_CONTACT);
    spook::ref_ptr<Recorder<S>> keeper = new Recorder<S>();
    scene.sim->add(removerFirst ? remover : keeper);
    scene.sim->add(removerFirst ? keeper : remover);
    const int steps = 30;
    for (int step = 0; step < steps; ++step) {
      scene.sim->stepForward();
      // No contact rows, no contact forces.
      CHECK(scene.sim->getStatistics().solver.numRows == 0);
      for (const auto& contact : scene.sim->getGeometryContacts()) {
        CHECK_FALSE(contact.isEnabled());
        for (const auto& p : contact.points()) CHECK(p.getNormalForceMagnitude() == S(0));
      }
    }
    // Impact in step 6, then a contact in each later step while the
    // capsule sinks through the ground (its points stay in the plane's
    // half space).
    const std::vector<std::string> expected = [&] {
      std::vector<std::string> e{"impact"};
      e.resize(std::size_t(steps - 6), "contact");
      return e;
    }();
    CHECK(remover->events == expected);
    CHECK(keeper->events == expected);
    // The keeper, called after the remover, sees the contact already
    // disabled; called before it, enabled. The remover always sees it enabled.
    CHECK(keeper->enabled == std::vector<bool>(expected.size(), !removerFirst));
    CHECK(remover->enabled == std::vector<bool>(expected.size(), true));
    // Free fall as if there were no ground (symplectic Euler, h = 1/60 s):
    // z_n = z_0 − g h² n(n+1)/2.
    const double h = 1.0 / 60.0;
    const double z = 0.15 - 9.80665 * h * h * steps * (steps + 1) / 2.0;
    CHECK(std::abs(double(scene.capsule->getPosition().z()) - z) < spook::test::pick<S>(1e-9, 1e-4));
  }
}

TEST_CASE_TEMPLATE("execution filters select contacts by one or two geometries", S, float, double) {
  DropScene<S> scene;
  spook::ref_ptr<spook::GeometryT<S>> other =
      new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5)), spook::TransformT<S>::Identity(), "other");
  other->setPosition(S(5), S(0), S(0));
  scene.sim->add(other);
  spook::ref_ptr<Recorder<S>> byGround = new Recorder<S>(), byPair = new Recorder<S>(), byOther = new Recorder<S>();
  byGround->setFilter(scene.ground.get());
  byPair->setFilter(scene.capsule->getGeometries()[0].get(), scene.ground.get());
  byOther->setFilter(other.get(), scene.ground.get());
  byGround->setMask(spook::ContactEventListenerT<S>::IMPACT);
  scene.sim->add(byGround);
  scene.sim->add(byPair);
  scene.sim->add(byOther);
  for (int step = 0; step < 10; ++step) scene.sim->stepForward();
  CHECK(byGround->events == std::vector<std::string>{"impact"});
  CHECK(byPair->events == std::vector<std::string>{"impact", "contact", "contact", "contact"});
  CHECK(byOther->events.empty());  // two static geometries never collide
}

TEST_CASE_TEMPLATE("a simulation refuses bodies with shapes outside its list and keeps its content", S, float,
                   double) {
  spook::ref_ptr<spook::SimulationT<S>> sim =
      new spook::SimulationT<S>(spook::ShapeList<spook::SphereT, spook::PlaneT>{});
  spook::ref_ptr<spook::RigidBodyT<S>> ball = new spook::RigidBodyT<S>("ball"), crate = new spook::RigidBodyT<S>("crate");
  ball->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5))));
  crate->add(new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>::Ones()), spook::TransformT<S>::Identity(),
                                     "crate"));
  sim->add(ball);
  CHECK_THROWS_WITH_AS(sim->add(crate), doctest::Contains("shape type not in this space's shape list, got Box"),
                       spook::Error);
  spook::ref_ptr<spook::CollectionT<S>> group = new spook::CollectionT<S>("group");
  spook::ref_ptr<spook::RigidBodyT<S>> ball2 = new spook::RigidBodyT<S>("ball2");
  ball2->add(new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5))));
  group->add(ball2);
  group->add(crate);
  CHECK_THROWS_AS(sim->add(group), spook::Error);
  CHECK(sim->getRigidBodies().size() == 1);
  CHECK_FALSE(sim->contains(ball2.get()));
}

// A shape that joins a geometry after the geometry joined the simulation is
// checked when the simulation steps: an Error before anything moves, not a
// shape that silently collides with nothing.
TEST_CASE_TEMPLATE("a step refuses a shape added outside the list after the geometry joined", S, float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim =
      new spook::SimulationT<S>(spook::ShapeList<spook::SphereT, spook::PlaneT, spook::CompositeT>{});
  spook::ref_ptr<spook::RigidBodyT<S>> ball = new spook::RigidBodyT<S>("ball");
  spook::ref_ptr<spook::GeometryT<S>> geometry =
      new spook::GeometryT<S>(new spook::SphereT<S>(S(0.5)), spook::TransformT<S>::Identity(), "ball geometry");
  ball->add(geometry);
  sim->add(ball);
  sim->stepForward();
  const spook::Vec3T<S> before = ball->getPosition();
  const S timeBefore = sim->getTimeStamp();
  spook::ref_ptr<spook::CompositeT<S>> parts = new spook::CompositeT<S>();
  parts->add(new spook::SphereT<S>(S(0.2)));
  geometry->add(parts);
  sim->stepForward();  // composites of spheres are in the list
  parts->add(new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.1))));
  const spook::Vec3T<S> moved = ball->getPosition();
  const S timeMoved = sim->getTimeStamp();
  CHECK_THROWS_WITH_AS(sim->stepForward(),
                       doctest::Contains("Geometry 'ball geometry': shape type not in this space's shape list, got Box"),
                       spook::Error);
  CHECK(ball->getPosition() == moved);
  CHECK(sim->getTimeStamp() == timeMoved);
  CHECK(timeMoved > timeBefore);
  CHECK(moved != before);
  geometry->remove(parts.get());
  sim->stepForward();
  CHECK(sim->getTimeStamp() > timeMoved);
}
