#include <doctest/doctest.h>

#include <spook/sim/simulation.hpp>

#include "scene_state.hpp"
#include "tolerance.hpp"

using spook::test::pick;

namespace {

template <class S>
struct KinematicCrane {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  spook::ref_ptr<spook::RigidBodyT<S>> hook = new spook::RigidBodyT<S>("hook");
  KinematicCrane() {
    hook->setMotionControl(spook::RigidBodyT<S>::KINEMATICS);
    hook->setPosition(spook::Vec3T<S>(S(1), S(0), S(2)));
    hook->setCmLocalTranslate(spook::Vec3T<S>(S(0), S(0.2), S(-0.1)));
    sim->add(hook);
  }
};

}  // namespace

TEST_CASE_TEMPLATE("moveTo reaches its target pose at the stated time and stops", S, float, double) {
  const S tol = pick<S>(1e-9, 2e-5);
  KinematicCrane<S> crane;
  const S h = crane.sim->getTimeStep();
  const spook::TransformT<S> target = spook::makeTransform<S>(
      spook::Vec3T<S>(S(-2), S(3), S(5)), spook::toQuat(spook::EulerAnglesT<S>{S(0.3), S(-0.5), S(2.0)}));
  crane.hook->moveTo(target, S(1.5));
  for (int i = 0; i < 89; ++i) crane.sim->stepForward();
  CHECK(crane.hook->isMovingToTarget());
  CHECK(spook::test::poseError<S>(crane.hook->getTransform(), target) > S(1e-3));
  crane.sim->stepForward();
  CHECK(crane.sim->getTimeStamp() == doctest::Approx(1.5).epsilon(pick<S>(1e-12, 1e-5)));
  CHECK(spook::test::poseError<S>(crane.hook->getTransform(), target) < tol);
  CHECK(!crane.hook->isMovingToTarget());
  CHECK(crane.hook->getVelocity() == spook::Vec3T<S>::Zero());
  for (int i = 0; i < 10; ++i) crane.sim->stepForward();
  CHECK(spook::test::poseError<S>(crane.hook->getTransform(), target) < tol);
  (void)h;
}

TEST_CASE_TEMPLATE("moveTo moves at constant velocity along the way", S, float, double) {
  const S tol = pick<S>(1e-9, 2e-5);
  KinematicCrane<S> crane;
  const spook::Vec3T<S> start = crane.hook->getCmPosition();
  const spook::TransformT<S> target = spook::makeTransform<S>(spook::Vec3T<S>(S(4), S(0), S(2)));
  crane.hook->moveTo(target, S(1));
  const spook::Vec3T<S> v = crane.hook->getVelocity();
  CHECK((v - spook::Vec3T<S>(S(3), S(0), S(0))).norm() < tol);
  for (int i = 0; i < 30; ++i) crane.sim->stepForward();
  CHECK((crane.hook->getCmPosition() - (start + v * S(0.5))).norm() < tol);
}

TEST_CASE_TEMPLATE("a moveTo that is not a whole number of steps lands on the next step", S, float, double) {
  const S tol = pick<S>(1e-9, 2e-5);
  KinematicCrane<S> crane;
  const spook::TransformT<S> target = spook::makeTransform<S>(spook::Vec3T<S>(S(0), S(0), S(0)));
  crane.hook->moveTo(target, S(0.11));  // 6.6 steps of 1/60 s
  for (int i = 0; i < 6; ++i) crane.sim->stepForward();
  CHECK(crane.hook->isMovingToTarget());
  crane.sim->stepForward();
  CHECK(!crane.hook->isMovingToTarget());
  CHECK(spook::test::poseError<S>(crane.hook->getTransform(), target) < tol);
}

TEST_CASE_TEMPLATE("a kinematic body turns by exp(h ω) each step", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  KinematicCrane<S> crane;
  const spook::Vec3T<S> omega(S(0.2), S(-0.4), S(0.9));
  crane.hook->setAngularVelocity(omega);
  const spook::QuatT<S> q0 = crane.hook->getCmRotation();
  const int n = 120;
  for (int i = 0; i < n; ++i) crane.sim->stepForward();
  const spook::QuatT<S> expected = spook::expRotation<S>(omega * (S(n) * crane.sim->getTimeStep())) * q0;
  CHECK(std::abs(std::abs(crane.hook->getCmRotation().dot(expected)) - S(1)) < tol);
}
