#include <doctest/doctest.h>

#include <vector>

#include <spook/sim/assembly.hpp>
#include <spook/sim/simulation.hpp>

#include "scene_state.hpp"
#include "tolerance.hpp"

using spook::test::firstDifference;
using spook::test::pick;

namespace {

template <class S>
using BodyRef = spook::ref_ptr<spook::RigidBodyT<S>>;
template <class S>
using CollectionRef = spook::ref_ptr<spook::CollectionT<S>>;
template <class S>
using AssemblyRef = spook::ref_ptr<spook::AssemblyT<S>>;
template <class S>
using ListenerRef = spook::ref_ptr<spook::StepEventListenerT<S>>;
template <class S>
using SimulationRef = spook::ref_ptr<spook::SimulationT<S>>;
template <class S>
using Capture = spook::test::SceneState<S>;

template <class S>
class Counter : public spook::StepEventListenerT<S> {
 public:
  void pre(const spook::TimeStampT<S>&) override { ++calls; }
  int calls = 0;

 protected:
  ~Counter() override = default;
};

/// root { crate, counter, middle (an assembly) { barrel, inner { pallet } } }
template <class S>
struct Tree {
  CollectionRef<S> root = new spook::CollectionT<S>("root");
  CollectionRef<S> middle = new spook::AssemblyT<S>("middle");
  CollectionRef<S> inner = new spook::CollectionT<S>("inner");
  BodyRef<S> crate = new spook::RigidBodyT<S>("crate");
  BodyRef<S> barrel = new spook::RigidBodyT<S>("barrel");
  BodyRef<S> pallet = new spook::RigidBodyT<S>("pallet");
  spook::ref_ptr<Counter<S>> counter = new Counter<S>();
  Tree() {
    inner->add(pallet);
    middle->add(barrel);
    middle->add(inner);
    root->add(crate);
    root->add(counter);
    root->add(middle);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("collections and assemblies hold bodies, listeners and nested collections until removed", S, float,
                   double) {
  Tree<S> tree;
  CHECK(tree.root->getRigidBodies() == std::vector<BodyRef<S>>{tree.crate});
  CHECK(tree.root->getEventListeners() == std::vector<ListenerRef<S>>{tree.counter});
  CHECK(tree.root->getCollections() == std::vector<CollectionRef<S>>{tree.middle});
  CHECK(tree.middle->getRigidBodies() == std::vector<BodyRef<S>>{tree.barrel});
  CHECK(tree.middle->getCollections() == std::vector<CollectionRef<S>>{tree.inner});
  CHECK(tree.root->containsCollection(tree.inner));
  CHECK(!tree.inner->containsCollection(tree.root));
  tree.root->remove(tree.crate);
  tree.root->remove(tree.counter);
  tree.root->remove(tree.middle);
  CHECK(tree.root->getRigidBodies().empty());
  CHECK(tree.root->getEventListeners().empty());
  CHECK(tree.root->getCollections().empty());
  CHECK(!tree.root->containsCollection(tree.inner));
}

TEST_CASE_TEMPLATE("adding a collection to a simulation adds its content, nested collections included", S, float,
                   double) {
  Tree<S> tree;
  SimulationRef<S> sim = new spook::SimulationT<S>();
  sim->add(tree.root);
  CHECK(sim->getCollections() == std::vector<CollectionRef<S>>{tree.root});
  CHECK(sim->getRigidBodies().size() == 3);
  for (const auto& body : {tree.crate, tree.barrel, tree.pallet}) CHECK(sim->contains(body));
  CHECK(tree.counter->getSimulation() == sim.get());
  sim->stepForward();
  CHECK(tree.counter->calls == 1);
  CHECK(tree.pallet->getVelocity().z() < S(0));
}

TEST_CASE_TEMPLATE("removing a collection from a simulation removes its content, nested collections included", S, float,
                   double) {
  Tree<S> tree;
  SimulationRef<S> sim = new spook::SimulationT<S>();
  BodyRef<S> loose = new spook::RigidBodyT<S>("loose");
  sim->add(loose);
  sim->add(tree.root);
  sim->remove(tree.root);
  CHECK(sim->getCollections().empty());
  CHECK(sim->getRigidBodies() == std::vector<BodyRef<S>>{loose});
  CHECK(tree.counter->getSimulation() == nullptr);
  sim->stepForward();
  CHECK(tree.counter->calls == 0);
  CHECK(tree.pallet->getVelocity() == spook::Vec3T<S>::Zero());
  // The collection and its nested ones are free again: another simulation takes them.
  SimulationRef<S> next = new spook::SimulationT<S>();
  next->add(tree.root);
  CHECK(next->contains(tree.pallet));
}

TEST_CASE_TEMPLATE("what is added to a collection in a simulation joins it, and what is removed leaves it", S, float,
                   double) {
  Tree<S> tree;
  SimulationRef<S> sim = new spook::SimulationT<S>();
  sim->add(tree.root);
  BodyRef<S> late = new spook::RigidBodyT<S>("late"), deep = new spook::RigidBodyT<S>("deep");
  CollectionRef<S> branch = new spook::CollectionT<S>("branch");
  spook::ref_ptr<Counter<S>> listener = new Counter<S>();
  branch->add(deep);
  tree.root->add(late);
  tree.inner->add(listener);
  tree.middle->add(branch);
  CHECK(sim->contains(late));
  CHECK(sim->contains(deep));
  CHECK(listener->getSimulation() == sim.get());

  tree.root->remove(late);
  tree.inner->remove(listener);
  tree.middle->remove(branch);
  CHECK(!sim->contains(late));
  CHECK(!sim->contains(deep));
  CHECK(listener->getSimulation() == nullptr);
  CHECK(sim->getRigidBodies().size() == 3);
}

TEST_CASE_TEMPLATE("a collection cannot contain itself, directly or through nesting", S, float, double) {
  Tree<S> tree;
  CHECK_THROWS_AS(tree.root->add(tree.root), spook::Error);
  CHECK_THROWS_AS(tree.inner->add(tree.root), spook::Error);
  CHECK_THROWS_AS(tree.middle->add(tree.root), spook::Error);
  CHECK(tree.inner->getCollections().empty());
  CHECK(tree.middle->getCollections() == std::vector<CollectionRef<S>>{tree.inner});
  CHECK(tree.root->getCollections() == std::vector<CollectionRef<S>>{tree.middle});
}

// Content of the crane assembly: two bodies, a nested assembly (the hook)
// with a body, and a plain collection inside the hook with another body.
template <class S>
struct CraneAssembly {
  using Vec3 = spook::Vec3T<S>;
  AssemblyRef<S> crane = new spook::AssemblyT<S>("crane");
  AssemblyRef<S> hook = new spook::AssemblyT<S>("hook");
  CollectionRef<S> cargo = new spook::CollectionT<S>("cargo");
  std::vector<BodyRef<S>> bodies;

  CraneAssembly() {
    hook->setPosition(Vec3(S(1), S(0), S(-2)));
    const auto body = [&](const char* name, Vec3 p, spook::EulerAnglesT<S> angles, spook::CollectionT<S>* into) {
      BodyRef<S> b = new spook::RigidBodyT<S>(name);
      b->setTransform(spook::makeTransform<S>(p, spook::toQuat(angles)));
      b->setVelocity(p.cross(Vec3(S(1), S(2), S(3))));
      b->setAngularVelocity(Vec3(S(0.5), S(-1), S(2)) - p);
      into->add(b);
      bodies.push_back(b);
    };
    body("boom", Vec3(S(0), S(0), S(3)), {S(0.1), S(0.2), S(0.3)}, crane.get());
    body("trolley", Vec3(S(2), S(1), S(3)), {S(0), S(0), S(1)}, crane.get());
    body("block", Vec3(S(1), S(0.5), S(-1)), {S(-0.4), S(0), S(0.2)}, hook.get());
    body("crate", Vec3(S(1), S(0), S(-3)), {S(0), S(0.7), S(0)}, cargo.get());
    hook->add(cargo);
    crane->add(hook);
  }

  /// Poses of the bodies and of the hook frame in the crane frame.
  std::vector<spook::TransformT<S>> localPoses() const {
    const spook::TransformT<S> toCrane = crane->getTransform().inverse();
    std::vector<spook::TransformT<S>> poses{toCrane * hook->getTransform()};
    for (const auto& b : bodies) poses.push_back(toCrane * b->getTransform());
    return poses;
  }
  void checkRigid(const std::vector<spook::TransformT<S>>& before) const {
    const std::vector<spook::TransformT<S>> after = localPoses();
    for (std::size_t i = 0; i < before.size(); ++i) CHECK(spook::test::poseError<S>(after[i], before[i]) < pick<S>(1e-12, 1e-5));
  }
};

TEST_CASE_TEMPLATE("moving an assembly moves its content rigidly, nested assemblies and collections included", S, float,
                   double) {
  using Vec3 = spook::Vec3T<S>;
  const S tol = pick<S>(1e-12, 1e-5);
  CraneAssembly<S> scene;
  const auto before = scene.localPoses();
  const Vec3 boomAt = scene.bodies[0]->getPosition();
  const spook::QuatT<S> boomTurn = scene.bodies[0]->getRotation();

  scene.crane->setPosition(Vec3(S(3), S(-1), S(0.5)));
  CHECK((scene.crane->getPosition() - Vec3(S(3), S(-1), S(0.5))).norm() < tol);
  CHECK((scene.bodies[0]->getPosition() - (boomAt + Vec3(S(3), S(-1), S(0.5)))).norm() < tol);
  CHECK(scene.bodies[0]->getRotation().angularDistance(boomTurn) < tol);
  scene.checkRigid(before);

  const spook::QuatT<S> q = spook::toQuat(spook::EulerAnglesT<S>{S(0.3), S(-0.2), S(1.1)});
  scene.crane->setRotation(q);
  CHECK((scene.crane->getPosition() - Vec3(S(3), S(-1), S(0.5))).norm() < tol);
  CHECK(scene.crane->getRotation().angularDistance(q) < tol);
  scene.checkRigid(before);

  const spook::TransformT<S> X =
      spook::makeTransform<S>(Vec3(S(-2), S(4), S(1)), spook::toQuat(spook::EulerAnglesT<S>{S(2), S(0.1), S(-0.5)}));
  scene.crane->setTransform(X);
  CHECK(spook::test::poseError<S>(scene.crane->getTransform(), X) < tol);
  scene.checkRigid(before);
}

TEST_CASE_TEMPLATE("turning an assembly turns the velocities of its bodies with it", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  CraneAssembly<S> scene;
  std::vector<spook::Vec3T<S>> v, w;
  for (const auto& b : scene.bodies) v.push_back(b->getVelocity()), w.push_back(b->getAngularVelocity());
  const spook::QuatT<S> q = spook::toQuat(spook::EulerAnglesT<S>{S(0.3), S(-0.2), S(1.1)});
  scene.crane->setRotation(q);                                 // from the identity: the turn is q
  scene.crane->setPosition(spook::Vec3T<S>(S(5), S(5), S(5)));  // a translation leaves velocities alone
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    CHECK((scene.bodies[i]->getVelocity() - q * v[i]).norm() < tol);
    CHECK((scene.bodies[i]->getAngularVelocity() - q * w[i]).norm() < tol);
  }
}

TEST_CASE_TEMPLATE("adding a body to a moved assembly does not move the body", S, float, double) {
  AssemblyRef<S> assembly = new spook::AssemblyT<S>("crane");
  assembly->setPosition(spook::Vec3T<S>(S(1), S(2), S(3)));
  BodyRef<S> body = new spook::RigidBodyT<S>("crate");
  body->setPosition(spook::Vec3T<S>(S(-1), S(0), S(4)));
  assembly->add(body);
  CHECK(body->getPosition() == spook::Vec3T<S>(S(-1), S(0), S(4)));
}

TEST_CASE_TEMPLATE("a body reachable twice through nested collections moves with its assembly once", S, float, double) {
  AssemblyRef<S> assembly = new spook::AssemblyT<S>("crane");
  CollectionRef<S> cargo = new spook::CollectionT<S>("cargo");
  BodyRef<S> crate = new spook::RigidBodyT<S>("crate");
  assembly->add(crate);
  cargo->add(crate);
  assembly->add(cargo);
  assembly->setPosition(spook::Vec3T<S>(S(2), S(0), S(0)));
  CHECK((crate->getPosition() - spook::Vec3T<S>(S(2), S(0), S(0))).norm() < pick<S>(1e-12, 1e-5));
}

TEST_CASE_TEMPLATE("a failed add of a collection leaves both simulations and the collection as they were", S, float,
                   double) {
  Tree<S> tree;
  SimulationRef<S> sim = new spook::SimulationT<S>(), other = new spook::SimulationT<S>();
  sim->add(new spook::RigidBodyT<S>("anchor"));
  sim->stepForward();
  BodyRef<S> stray = new spook::RigidBodyT<S>("stray");
  other->add(stray);
  BodyRef<S> twice = new spook::RigidBodyT<S>("twice");

  SUBCASE("a body inside belongs to another simulation") { tree.inner->add(stray); }
  SUBCASE("the same body appears twice in the tree") {
    tree.root->add(twice);
    tree.inner->add(twice);
  }
  SUBCASE("the same listener appears twice in the tree") { tree.inner->add(tree.counter); }
  SUBCASE("a nested collection is already in another simulation") { other->add(tree.inner); }

  const auto before = Capture<S>::capture(*sim, {tree.root}, {stray, twice});
  const auto otherBefore = Capture<S>::capture(*other);
  CHECK_THROWS_AS(sim->add(tree.root), spook::Error);
  CHECK(firstDifference(before, Capture<S>::capture(*sim, {tree.root}, {stray, twice})) == "");
  CHECK(firstDifference(otherBefore, Capture<S>::capture(*other)) == "");
  CHECK(tree.counter->getSimulation() == nullptr);
}

TEST_CASE_TEMPLATE("a failed add to a collection in a simulation changes neither", S, float, double) {
  Tree<S> tree;
  SimulationRef<S> sim = new spook::SimulationT<S>(), other = new spook::SimulationT<S>();
  sim->add(tree.root);
  BodyRef<S> stray = new spook::RigidBodyT<S>("stray");
  other->add(stray);
  CollectionRef<S> branch = new spook::CollectionT<S>("branch");
  branch->add(new spook::RigidBodyT<S>("fresh"));
  branch->add(stray);

  const auto before = Capture<S>::capture(*sim, {branch}, {stray});
  CHECK_THROWS_AS(tree.middle->add(stray), spook::Error);
  CHECK_THROWS_AS(tree.middle->add(branch), spook::Error);
  CHECK_THROWS_AS(tree.root->add(tree.crate), spook::Error);  // already in it
  CHECK(firstDifference(before, Capture<S>::capture(*sim, {branch}, {stray})) == "");
  CHECK(other->contains(stray));
}
