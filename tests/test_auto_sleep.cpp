#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include <spook/constraints/joints/hinge.hpp>

#include "contact_scenes.hpp"
#include "error_message.hpp"
#include "tolerance.hpp"

// SimulationT::getAutoSleep (issue 20): islands at rest fall asleep, stand
// exactly still and cost no solve; whatever disturbs them wakes them.

using spook::test::addBody;
using spook::test::addGround;
using spook::test::pick;

namespace {

template <class S>
using Vec3 = spook::Vec3T<S>;

template <class S>
struct Scene {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::MaterialT<S>> wood = new spook::MaterialT<S>("wood");
  spook::ref_ptr<spook::GeometryT<S>> ground;

  explicit Scene(bool sleep = true) {
    sim->getAutoSleep()->setEnable(sleep);
    ground = addGround(*sim, wood);
  }
  spook::ref_ptr<spook::RigidBodyT<S>> box(const Vec3<S>& at, S half = S(0.5)) {
    return addBody(*sim, "box", new spook::BoxT<S>(Vec3<S>::Constant(half)), wood, at);
  }
  void run(double seconds) {
    for (long i = 0, n = std::lround(seconds / double(sim->getTimeStep())); i < n; ++i) sim->stepForward();
  }
};

}  // namespace

TEST_CASE_TEMPLATE("auto sleep is off by default: a resting box stays awake", S, float, double) {
  Scene<S> scene(false);
  CHECK_FALSE(scene.sim->getAutoSleep()->getEnable());
  const auto box = scene.box(Vec3<S>(0, 0, S(0.5)));
  scene.run(2.0);
  CHECK_FALSE(box->isSleeping());
  CHECK(scene.sim->getStatistics().numSleepingBodies == 0);
  CHECK(scene.sim->getStatistics().solver.numIslands == 1);
}

// A stack of three boxes settles (its contacts' compliance sinks it well
// under a millimetre), rests for getTime() and falls asleep as one island;
// asleep, it is solved no more and keeps its pose bit for bit.
TEST_CASE_TEMPLATE("a resting stack falls asleep as one island and then stands exactly still", S, float, double) {
  Scene<S> scene;
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> boxes;
  for (int i = 0; i < 3; ++i) boxes.push_back(scene.box(Vec3<S>(0, 0, S(0.5 + i))));
  int stepsAwake = 0;
  for (int i = 0; i < 120; ++i) {
    scene.sim->stepForward();
    if (scene.sim->getStatistics().numSleepingBodies == 0) ++stepsAwake;
  }
  // Resting from about the first step: asleep after 0.5 s (30 steps, 29 in
  // float's sum of h) and a few to settle.
  CHECK(stepsAwake >= 29);
  CHECK(stepsAwake <= 45);
  for (const auto& b : boxes) CHECK(b->isSleeping());
  CHECK(scene.sim->getStatistics().numSleepingBodies == 3);
  CHECK(scene.sim->getStatistics().solver.numIslands == 0);
  std::vector<spook::TransformT<S>> poses;
  for (const auto& b : boxes) poses.push_back(b->getTransform());
  // The normal force between the two lower boxes (a pair of sleeping bodies).
  const auto load = [&] {
    double sum = 0.0;
    for (const auto& c : scene.sim->getGeometryContacts())
      if ((c.rigidBody(0) == boxes[0].get() && c.rigidBody(1) == boxes[1].get()) ||
          (c.rigidBody(0) == boxes[1].get() && c.rigidBody(1) == boxes[0].get()))
        for (const auto& p : c.points())
          if (p.enabled) sum += double(p.getNormalForceMagnitude());
    return sum;
  };
  const std::size_t contacts = scene.sim->getGeometryContacts().size();
  scene.run(1.0);
  // Asleep, the boxes keep their contacts (not collided again) and their
  // last forces: the lowest box still carries the two above.
  CHECK(scene.sim->getGeometryContacts().size() == contacts);
  const double weight = 2.0 * double(boxes[0]->getMassProperties()->getMass()) * 9.80665;
  CHECK(std::abs(load() - weight) < 1e-3 * weight);
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    CHECK(boxes[i]->getTransform().matrix() == poses[i].matrix());
    CHECK(std::abs(double(boxes[i]->getPosition().z()) - (0.5 + double(i))) < 1e-3);
    CHECK(boxes[i]->getVelocity() == Vec3<S>::Zero());
  }
}

// A 1 kg sphere dropped 1 m onto the sleeping stack: its contact wakes the
// top box, whose contacts wake the rest; the stack carries it (nothing sinks
// more than a millimetre) and the whole falls asleep again.
TEST_CASE_TEMPLATE("a sphere dropped onto a sleeping stack wakes it and rests on top", S, float, double) {
  Scene<S> scene;
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> boxes;
  for (int i = 0; i < 3; ++i) boxes.push_back(scene.box(Vec3<S>(0, 0, S(0.5 + i))));
  scene.run(1.0);
  REQUIRE(boxes[2]->isSleeping());
  const S radius = S(0.1);
  const auto ball = addBody(*scene.sim, "ball", new spook::SphereT<S>(radius), scene.wood, Vec3<S>(0, 0, S(4)));
  bool woke = false;
  for (int i = 0; i < 90; ++i) {
    scene.sim->stepForward();
    woke = woke || !boxes[0]->isSleeping();
  }
  CHECK(woke);
  CHECK(std::abs(double(ball->getPosition().z()) - (3.0 + double(radius))) < 2e-3);
  for (int i = 0; i < 3; ++i) CHECK(std::abs(double(boxes[std::size_t(i)]->getPosition().z()) - (0.5 + i)) < 1e-3);
  scene.run(2.0);
  CHECK(ball->isSleeping());
  CHECK(scene.sim->getStatistics().numSleepingBodies == 4);
}

TEST_CASE_TEMPLATE("a sleeping box wakes when it is moved, pushed, given a velocity or its ground goes", S, float,
                   double) {
  Scene<S> scene;
  const auto box = scene.box(Vec3<S>(0, 0, S(0.5)));
  scene.run(1.0);
  REQUIRE(box->isSleeping());
  const double h = double(scene.sim->getTimeStep());

  SUBCASE("a velocity") {
    box->setVelocity(Vec3<S>(1, 0, 0));
    scene.sim->stepForward();
    CHECK_FALSE(box->isSleeping());
    CHECK(double(box->getPosition().x()) > 0.5 * h);
  }
  SUBCASE("a force") {
    box->addForce(Vec3<S>(0, 0, S(100 * 1000 * 9.80665)));  // a hundred times its weight, up
    scene.sim->stepForward();
    CHECK_FALSE(box->isSleeping());
    CHECK(box->getVelocity().z() > S(0));
  }
  SUBCASE("moved 1 m up: it falls") {
    box->setPosition(Vec3<S>(0, 0, S(1.5)));
    scene.run(0.25);
    CHECK_FALSE(box->isSleeping());
    CHECK(double(box->getPosition().z()) < 1.5 - 0.2);
  }
  SUBCASE("its ground removed: it falls") {
    REQUIRE(scene.sim->remove(scene.ground.get()));
    scene.run(0.5);
    CHECK_FALSE(box->isSleeping());
    CHECK(double(box->getPosition().z()) < 0.5 - 1.0);
  }
  SUBCASE("woken by hand, it rests and sleeps again") {
    box->wakeUp();
    scene.sim->stepForward();
    CHECK_FALSE(box->isSleeping());
    scene.run(1.0);
    CHECK(box->isSleeping());
  }
  SUBCASE("auto sleep turned off: it wakes") {
    scene.sim->getAutoSleep()->setEnable(false);
    scene.sim->stepForward();
    CHECK_FALSE(box->isSleeping());
  }
}

// A box asleep on a kinematic platform: the platform starting to rise wakes
// it and carries it up.
TEST_CASE_TEMPLATE("a kinematic platform that starts to move wakes what sleeps on it", S, float, double) {
  Scene<S> scene;
  const auto platform = scene.box(Vec3<S>(0, 0, S(2)));
  platform->setMotionControl(spook::RigidBodyT<S>::KINEMATICS);
  const auto box = scene.box(Vec3<S>(0, 0, S(2.75)), S(0.25));
  scene.run(1.0);
  REQUIRE(box->isSleeping());
  platform->setVelocity(Vec3<S>(0, 0, S(0.5)));
  scene.run(1.0);
  CHECK_FALSE(box->isSleeping());
  CHECK(std::abs(double(box->getPosition().z()) - (3.25 + 0.0)) < 0.02);
}

// A kinematic platform gliding at 1 cm/s (under the linear threshold) keeps
// the box it carries awake: asleep, the box would stop and be woken again
// every step.
TEST_CASE_TEMPLATE("a box on a slowly gliding kinematic platform stays awake and rides along", S, float, double) {
  Scene<S> scene;
  const auto platform = scene.box(Vec3<S>(0, 0, S(2)));
  platform->setMotionControl(spook::RigidBodyT<S>::KINEMATICS);
  platform->setVelocity(Vec3<S>(S(0.01), 0, 0));
  const auto box = scene.box(Vec3<S>(0, 0, S(2.75)), S(0.25));
  bool slept = false;
  for (int i = 0; i < 120; ++i) {
    scene.sim->stepForward();
    slept = slept || box->isSleeping();
  }
  CHECK_FALSE(slept);
  CHECK(std::abs(double(box->getPosition().x()) - 0.02) < 2e-3);
}

// A crank held level by its motor at speed 0 falls asleep; setting the
// motor's speed wakes it (the motor's row drives it) and it turns.
TEST_CASE_TEMPLATE("a sleeping crank wakes when its motor is given a speed", S, float, double) {
  Scene<S> scene;
  scene.sim->setSolver(new spook::DirectSolver());
  const auto crank = scene.box(Vec3<S>(S(0.25), 0, S(3)), S(0.05));
  const auto hinge = spook::ConstraintT<S>::template createFromWorld<spook::HingeT<S>>(
      Vec3<S>(0, 0, S(3)), Vec3<S>::UnitY(), crank.get(), nullptr);
  scene.sim->add(hinge);
  hinge->getMotor1D()->setEnable(true);
  hinge->getMotor1D()->setSpeed(S(0));
  scene.run(1.0);
  REQUIRE(crank->isSleeping());
  hinge->getMotor1D()->setSpeed(S(1));
  scene.sim->stepForward();
  CHECK_FALSE(crank->isSleeping());
  CHECK(std::abs(std::abs(double(crank->getAngularVelocity().y())) - 1.0) < 1e-3);
  scene.run(1.0);
  CHECK_FALSE(crank->isSleeping());
}

// A pendulum passes through zero speed at its turning points: resting there
// for one step is not resting for getTime().
TEST_CASE_TEMPLATE("a swinging hinge chain does not fall asleep at its turning points; at rest it does, as one", S,
                   float, double) {
  Scene<S> scene;
  scene.sim->setSolver(new spook::DirectSolver());
  std::vector<spook::ref_ptr<spook::RigidBodyT<S>>> links;
  spook::RigidBodyT<S>* previous = nullptr;
  for (int i = 0; i < 3; ++i) {
    links.push_back(scene.box(Vec3<S>(S(0.5 * i + 0.25), 0, S(5)), S(0.05)));
    scene.sim->add(spook::ConstraintT<S>::template createFromWorld<spook::HingeT<S>>(
        Vec3<S>(S(0.5 * i), 0, S(5)), Vec3<S>::UnitY(), links.back().get(), previous));
    previous = links.back().get();
  }
  scene.run(5.0);
  for (const auto& link : links) CHECK_FALSE(link->isSleeping());
  // Damped to rest, it sleeps as one island; a push on its last link wakes
  // all three through the joints.
  for (const auto& link : links) {
    link->setLinearVelocityDamping(S(5));
    link->setAngularVelocityDamping(S(5));
  }
  scene.run(10.0);
  for (const auto& link : links) CHECK(link->isSleeping());
  links.back()->addForce(Vec3<S>(S(50), 0, 0));
  scene.sim->stepForward();
  for (const auto& link : links) CHECK_FALSE(link->isSleeping());
}

TEST_CASE("auto sleep thresholds that are negative or not finite are refused and change nothing") {
  spook::SimulationRef sim = new spook::Simulation();
  spook::AutoSleep& sleep = *sim->getAutoSleep();
  for (const double bad : {-0.1, std::nan(""), HUGE_VAL}) {
    const std::string value = std::to_string(bad).substr(0, 3);
    const std::string linear = spook::test::errorMessage([&] { sleep.setLinearVelocityThreshold(bad); });
    CHECK(linear.find("AutoSleep") != std::string::npos);
    CHECK(linear.find("linear velocity threshold") != std::string::npos);
    CHECK(spook::test::errorMessage([&] { sleep.setAngularVelocityThreshold(bad); }).find("angular") !=
          std::string::npos);
    CHECK(spook::test::errorMessage([&] { sleep.setTime(bad); }).find("time must be") != std::string::npos);
  }
  CHECK(spook::test::errorMessage([&] { sleep.setTime(0.0); }).find("AutoSleep") != std::string::npos);
  CHECK(sleep.getLinearVelocityThreshold() == 0.02);
  CHECK(sleep.getAngularVelocityThreshold() == 0.05);
  CHECK(sleep.getTime() == 0.5);
}
