#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <spook/collide/shapes/box.hpp>
#include <spook/sim/simulation.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

template <class S>
struct OneBody {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::RigidBodyT<S>> body = new spook::RigidBodyT<S>("body");
  explicit OneBody(bool gravity = false) {
    if (!gravity) sim->setUniformGravity(spook::Vec3T<S>::Zero());
    sim->add(body);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("changing mass properties keeps the center-of-mass offset", S, float, double) {
  OneBody<S> scene;
  spook::RigidBodyT<S>& body = *scene.body;
  body.setPosition(spook::Vec3T<S>(S(1), S(2), S(3)));
  body.setCmLocalTranslate(spook::Vec3T<S>(S(0.1), S(-0.2), S(0.3)));
  body.getMassProperties()->setMass(S(40));
  body.getMassProperties()->setInertiaTensor(spook::Vec3T<S>(S(1), S(2), S(2.5)));
  body.getMassProperties()->setMassCoefficients(spook::Vec3T<S>(S(0.5), S(0), S(0)));
  CHECK(body.getCmLocalTranslate() == spook::Vec3T<S>(S(0.1), S(-0.2), S(0.3)));
  CHECK(body.getPosition() == spook::Vec3T<S>(S(1), S(2), S(3)));
  CHECK((body.getCmPosition() - spook::Vec3T<S>(S(1.1), S(1.8), S(3.3))).norm() < pick<S>(1e-15, 1e-6));
}

TEST_CASE_TEMPLATE("a force at a point adds the torque r × F", S, float, double) {
  const S tol = pick<S>(1e-13, 1e-6);
  OneBody<S> scene;
  spook::RigidBodyT<S>& body = *scene.body;
  body.getMassProperties()->setMass(S(2));
  body.getMassProperties()->setInertiaTensor(spook::Vec3T<S>::Constant(S(0.5)));
  const spook::Vec3T<S> force(S(0), S(4), S(0)), at(S(0.25), S(0), S(0));
  body.addForceAtPosition(force, at);
  CHECK((body.getTorque() - at.cross(force)).norm() < tol);
  const S h = scene.sim->getTimeStep();
  scene.sim->stepForward();
  CHECK((body.getVelocity() - force / S(2) * h).norm() < tol);
  CHECK((body.getAngularVelocity() - at.cross(force) / S(0.5) * h).norm() < tol);
  // Cleared after the step: the next step changes nothing.
  CHECK(body.getForce() == spook::Vec3T<S>::Zero());
  CHECK(body.getTorque() == spook::Vec3T<S>::Zero());
  const spook::Vec3T<S> v = body.getVelocity();
  scene.sim->stepForward();
  CHECK((body.getVelocity() - v).norm() < tol);
}

// Added mass raises the inertial mass along a body axis, m(1 + c), but
// gravity still accelerates the body at g.
TEST_CASE_TEMPLATE("added mass changes the response to a force but not to gravity", S, float, double) {
  const S tol = pick<S>(1e-13, 1e-6);
  OneBody<S> scene;
  spook::RigidBodyT<S>& hull = *scene.body;
  const S h = scene.sim->getTimeStep();
  hull.getMassProperties()->setMass(S(1000));
  hull.getMassProperties()->setMassCoefficients(spook::Vec3T<S>(S(0.2), S(0), S(1)));
  hull.setRotation(spook::rotate<S>(spook::Vec3T<S>::UnitX(), spook::Vec3T<S>::UnitY()));  // body x = world y
  hull.addForce(spook::Vec3T<S>(S(600), S(600), S(0)));
  scene.sim->stepForward();
  CHECK((hull.getVelocity() - spook::Vec3T<S>(S(0.6) * h, S(0.5) * h, S(0))).norm() < tol);

  OneBody<S> falling(true);
  falling.body->getMassProperties()->setMassCoefficients(spook::Vec3T<S>(S(0.2), S(3), S(1)));
  falling.sim->stepForward();
  CHECK((falling.body->getVelocity() - spook::Vec3T<S>(S(0), S(0), S(-9.80665) * h)).norm() < tol);
}

// dv/dt = −d v stepped implicitly: vₙ = v₀ / (1 + h d)ⁿ, which tends to
// v₀ e^{−d t} as h → 0.
TEST_CASE_TEMPLATE("linear velocity damping follows v0 / (1 + h d)^n", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  OneBody<S> scene;
  const S h = scene.sim->getTimeStep(), d = S(0.8);
  const spook::Vec3T<S> v0(S(3), S(-1), S(2));
  scene.body->setLinearVelocityDamping(d);
  scene.body->setVelocity(v0);
  for (int n = 1; n <= 120; ++n) {
    scene.sim->stepForward();
    CHECK((scene.body->getVelocity() - v0 / std::pow(S(1) + h * d, S(n))).norm() < tol * v0.norm());
  }
  const S t = S(2);
  CHECK((scene.body->getVelocity() - v0 * std::exp(-d * t)).norm() < S(0.5) * d * d * h * t * v0.norm());
}

TEST_CASE_TEMPLATE("angular velocity damping follows w0 / (1 + h d)^n", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  OneBody<S> scene;
  const S h = scene.sim->getTimeStep(), d = S(0.3);
  const spook::Vec3T<S> w0(S(0.5), S(2), S(-1));
  scene.body->setAngularVelocityDamping(d);
  scene.body->setAngularVelocity(w0);
  for (int n = 0; n < 90; ++n) scene.sim->stepForward();
  CHECK((scene.body->getAngularVelocity() - w0 / std::pow(S(1) + h * d, S(90))).norm() < tol * w0.norm());
}

TEST_CASE_TEMPLATE("velocity damping acts along the body's own axes", S, float, double) {
  const S tol = pick<S>(1e-13, 1e-6);
  OneBody<S> scene;
  const S h = scene.sim->getTimeStep();
  scene.body->setRotation(spook::rotate<S>(spook::Vec3T<S>::UnitX(), spook::Vec3T<S>::UnitZ()));  // body x = world z
  scene.body->setLinearVelocityDamping(spook::Vec3T<S>(S(2), S(0), S(0)));
  scene.body->setVelocity(spook::Vec3T<S>(S(1), S(1), S(1)));
  scene.sim->stepForward();
  CHECK((scene.body->getVelocity() - spook::Vec3T<S>(S(1), S(1), S(1) / (S(1) + S(2) * h))).norm() < tol);
}

TEST_CASE_TEMPLATE("static bodies stay put and kinematic bodies ignore forces", S, float, double) {
  const S tol = pick<S>(1e-13, 1e-6);
  OneBody<S> scene(true);
  spook::ref_ptr<spook::RigidBodyT<S>> ground = new spook::RigidBodyT<S>("ground");
  ground->setMotionControl(spook::RigidBodyT<S>::STATIC);
  ground->setVelocity(spook::Vec3T<S>(S(1), S(0), S(0)));
  ground->addForce(spook::Vec3T<S>(S(0), S(0), S(100)));
  scene.sim->add(ground);
  spook::RigidBodyT<S>& conveyor = *scene.body;
  conveyor.setMotionControl(spook::RigidBodyT<S>::KINEMATICS);
  conveyor.setVelocity(spook::Vec3T<S>(S(0.5), S(0), S(0)));
  conveyor.addForce(spook::Vec3T<S>(S(0), S(0), S(100)));
  for (int i = 0; i < 60; ++i) scene.sim->stepForward();
  CHECK(ground->getPosition() == spook::Vec3T<S>::Zero());
  CHECK(ground->getVelocity() == spook::Vec3T<S>::Zero());
  CHECK((conveyor.getPosition() - spook::Vec3T<S>(S(0.5), S(0), S(0))).norm() < tol);
  CHECK((conveyor.getVelocity() - spook::Vec3T<S>(S(0.5), S(0), S(0))).norm() < tol);
}

TEST_CASE_TEMPLATE("attachments ride with their body", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  OneBody<S> scene;
  spook::RigidBodyT<S>& arm = *scene.body;
  spook::ref_ptr<spook::FrameT<S>> tip = new spook::FrameT<S>();
  tip->setLocalTranslate(S(1), S(0), S(0));
  arm.addAttachment(tip.get(), "tip");
  CHECK(arm.getAttachment("tip") == tip.get());
  CHECK(arm.getAttachment("base") == nullptr);
  arm.setVelocity(spook::Vec3T<S>(S(0), S(0), S(1)));
  arm.setAngularVelocity(spook::Vec3T<S>(S(0), S(0), S(0.5)));
  for (int i = 0; i < 60; ++i) scene.sim->stepForward();
  CHECK((tip->getTranslate() - arm.getTransform() * spook::Vec3T<S>(S(1), S(0), S(0))).norm() < tol);
  CHECK(std::abs((tip->getTranslate() - arm.getPosition()).norm() - S(1)) < tol);
  CHECK(arm.removeAttachment("tip"));
  CHECK(tip->getParent() == nullptr);
}

TEST_CASE_TEMPLATE("a body whose state would overflow is frozen and reported, not NaN", S, float, double) {
  OneBody<S> scene;
  spook::RigidBodyT<S>& dust = *scene.body;
  const spook::Vec3T<S> start(S(1), S(2), S(3));
  dust.setPosition(start);
  dust.setVelocity(spook::Vec3T<S>(S(1), S(0), S(0)));
  dust.getMassProperties()->setMass(std::numeric_limits<S>::min());
  dust.addForce(spook::Vec3T<S>(std::numeric_limits<S>::max(), S(0), S(0)));  // finite, but F/m overflows
  scene.sim->stepForward();
  REQUIRE(scene.sim->getStatistics().frozenBodies.size() == 1);
  CHECK(scene.sim->getStatistics().frozenBodies[0].body.get() == &dust);
  CHECK(scene.sim->getStatistics().frozenBodies[0].reason == spook::FreezeReason::NON_FINITE_STATE);
  CHECK(dust.getPosition() == start);
  CHECK(dust.getVelocity() == spook::Vec3T<S>::Zero());
  scene.sim->stepForward();
  CHECK(scene.sim->getStatistics().frozenBodies.empty());
  CHECK(dust.getPosition().allFinite());
}

// The center of mass stays finite but the model frame, 0.6·max from it,
// would not after the half turn of one step: the body is frozen, not the
// Frame asked to take an infinite translation (which throws).
TEST_CASE_TEMPLATE("a body whose model frame would overflow is frozen and reported, the step does not throw", S, float,
                   double) {
  OneBody<S> scene;
  spook::RigidBodyT<S>& body = *scene.body;
  const S big = S(0.6) * std::numeric_limits<S>::max();
  body.setCmLocalTranslate(spook::Vec3T<S>(big, S(0), S(0)));
  body.setCmPosition(spook::Vec3T<S>(big, S(0), S(0)));
  const spook::Vec3T<S> start = body.getPosition();
  body.setAngularVelocity(spook::Vec3T<S>(S(0), S(0), S(std::numbers::pi) / scene.sim->getTimeStep()));
  CHECK_NOTHROW(scene.sim->stepForward());
  REQUIRE(scene.sim->getStatistics().frozenBodies.size() == 1);
  CHECK(scene.sim->getStatistics().frozenBodies[0].reason == spook::FreezeReason::NON_FINITE_STATE);
  CHECK(body.getPosition() == start);
  CHECK(body.getAngularVelocity() == spook::Vec3T<S>::Zero());
}

// A 1 m cube of water (1000 kg, I = m (0.5² + 0.5²)/3 per axis) set to
// 100 kg: its inertia comes from its geometry, so it scales with the mass
// whichever comes first; a tensor set by hand stays as set.
TEST_CASE_TEMPLATE("setMass scales an inertia generated from the geometries, in either order", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  using Mat3 = spook::Mat3T<S>;
  const S tol = pick<S>(1e-12, 1e-5);
  const auto cube = [](const Vec3& at) {
    return spook::ref_ptr<spook::GeometryT<S>>(
        new spook::GeometryT<S>(new spook::BoxT<S>(Vec3::Constant(S(0.5))), spook::makeTransform<S>(at)));
  };
  const Mat3 expected = Mat3::Identity() * (S(100) * S(0.5) / S(3));
  spook::ref_ptr<spook::RigidBodyT<S>> after = new spook::RigidBodyT<S>("after");
  after->add(cube(Vec3::Zero()));
  REQUIRE(std::abs(after->getMassProperties()->getMass() - S(1000)) < S(1000) * tol);
  after->getMassProperties()->setMass(S(100));
  MESSAGE("inertia after setMass(100): ", after->getMassProperties()->getInertiaTensor()(0, 0), " kg m^2, expected ",
          expected(0, 0));
  CHECK((after->getMassProperties()->getInertiaTensor() - expected).norm() < tol * expected.norm());

  spook::ref_ptr<spook::RigidBodyT<S>> before = new spook::RigidBodyT<S>("before");
  before->getMassProperties()->setMass(S(100));
  before->add(cube(Vec3::Zero()));
  CHECK((before->getMassProperties()->getInertiaTensor() - expected).norm() < tol * expected.norm());

  // Two cubes side by side (parallel-axis terms): setMass gives what a
  // regeneration with the hand-set mass gives.
  spook::ref_ptr<spook::RigidBodyT<S>> pair = new spook::RigidBodyT<S>("pair");
  pair->add(cube(Vec3(S(-1), S(0), S(0))));
  pair->add(cube(Vec3(S(1), S(0.5), S(0))));
  pair->getMassProperties()->setMass(S(30));
  const Mat3 scaled = pair->getMassProperties()->getInertiaTensor();
  pair->updateMassProperties();
  CHECK((scaled - pair->getMassProperties()->getInertiaTensor()).norm() < tol * scaled.norm());
  CHECK(pair->getMassProperties()->getMass() == S(30));

  // A tensor set by hand is kept, set before or after the geometry.
  const Vec3 byHand(S(1), S(2), S(3));
  spook::ref_ptr<spook::RigidBodyT<S>> handFirst = new spook::RigidBodyT<S>("handFirst");
  handFirst->getMassProperties()->setInertiaTensor(byHand);
  handFirst->add(cube(Vec3::Zero()));
  handFirst->getMassProperties()->setMass(S(100));
  CHECK(handFirst->getMassProperties()->getInertiaTensor() == Mat3(byHand.asDiagonal()));
  spook::ref_ptr<spook::RigidBodyT<S>> handLast = new spook::RigidBodyT<S>("handLast");
  handLast->add(cube(Vec3::Zero()));
  handLast->getMassProperties()->setInertiaTensor(byHand);
  handLast->getMassProperties()->setMass(S(100));
  CHECK(handLast->getMassProperties()->getInertiaTensor() == Mat3(byHand.asDiagonal()));
  // A body without geometries keeps its default tensor.
  spook::ref_ptr<spook::RigidBodyT<S>> bare = new spook::RigidBodyT<S>("bare");
  const Mat3 defaultTensor = bare->getMassProperties()->getInertiaTensor();
  bare->getMassProperties()->setMass(S(100));
  CHECK(bare->getMassProperties()->getInertiaTensor() == defaultTensor);
}
