// The joint study's mechanisms in Bullet: rigid bodies without collision
// (their shapes collide with nothing) joined by btHingeConstraint, stepped
// by the sequential-impulse solver with Bullet's defaults (ERP 0.2, CFM 0,
// gyroscopic forces implicit) apart from the number of sweeps.
#include <memory>
#include <vector>

#include <btBulletDynamicsCommon.h>

#include "joint_study_engine.hpp"

namespace {

btVector3 toBullet(const joint_study::Point& p) { return {btScalar(p[0]), btScalar(p[1]), btScalar(p[2])}; }

class BulletJointEngine final : public joint_study::Engine {
 public:
  BulletJointEngine(const joint_study::Description& description, int iterations)
      : timeStep_(btScalar(description.timeStep)) {
    world_->setGravity(btVector3(0, 0, btScalar(description.gravity)));
    world_->getSolverInfo().m_numIterations = iterations;
    for (const joint_study::BodySpec& spec : description.bodies) {
      btRigidBody::btRigidBodyConstructionInfo info(btScalar(spec.mass), nullptr, shape_.get(), toBullet(spec.inertia));
      info.m_startWorldTransform.setOrigin(toBullet(spec.position));
      btRigidBody* body = bodies_.emplace_back(std::make_unique<btRigidBody>(info)).get();
      body->setActivationState(DISABLE_DEACTIVATION);
      world_->addRigidBody(body, 1, 0);  // collides with nothing
    }
    for (const joint_study::HingeSpec& spec : description.hinges) {
      btRigidBody& a = *bodies_[std::size_t(spec.body1)];
      const btVector3 pivotInA = toBullet(spec.pivot) - a.getCenterOfMassPosition();
      const btVector3 axis = toBullet(spec.axis);
      if (spec.body2 < 0) {
        hinges_.push_back(std::make_unique<btHingeConstraint>(a, pivotInA, axis));
      } else {
        btRigidBody& b = *bodies_[std::size_t(spec.body2)];
        const btVector3 pivotInB = toBullet(spec.pivot) - b.getCenterOfMassPosition();
        hinges_.push_back(std::make_unique<btHingeConstraint>(a, b, pivotInA, pivotInB, axis, axis));
      }
      world_->addConstraint(hinges_.back().get(), true);
    }
  }

  BulletJointEngine(const BulletJointEngine&) = delete;
  BulletJointEngine& operator=(const BulletJointEngine&) = delete;

  ~BulletJointEngine() override {
    for (const auto& hinge : hinges_) world_->removeConstraint(hinge.get());
    for (const auto& body : bodies_) world_->removeRigidBody(body.get());
  }

  // maxSubSteps 0: exactly one internal step of timeStep, no interpolation.
  void step() override { world_->stepSimulation(timeStep_, 0); }

  joint_study::Point worldPoint(int body, const joint_study::Point& local) const override {
    const btVector3 p = bodies_[std::size_t(body)]->getCenterOfMassTransform() * toBullet(local);
    return {double(p.x()), double(p.y()), double(p.z())};
  }

  double kineticEnergy() const override {
    double energy = 0.0;
    for (const auto& body : bodies_) {
      const btVector3 v = body->getLinearVelocity();
      const btVector3 bodyOmega = body->getCenterOfMassTransform().getBasis().transpose() * body->getAngularVelocity();
      const btVector3 inertia = body->getLocalInertia();
      energy += 0.5 / double(body->getInvMass()) * double(v.length2());
      for (int axis = 0; axis < 3; ++axis)
        energy += 0.5 * double(inertia[axis]) * double(bodyOmega[axis]) * double(bodyOmega[axis]);
    }
    return energy;
  }

 private:
  // Destroyed bottom-up: the world (emptied by the destructor) before the
  // constraints, bodies and shape it used, those before the solver.
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  std::unique_ptr<btCollisionDispatcher> dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
  std::unique_ptr<btBroadphaseInterface> broadphase_ = std::make_unique<btDbvtBroadphase>();
  std::unique_ptr<btConstraintSolver> solver_ = std::make_unique<btSequentialImpulseConstraintSolver>();
  std::unique_ptr<btCollisionShape> shape_ = std::make_unique<btSphereShape>(btScalar(0.01));
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::vector<std::unique_ptr<btHingeConstraint>> hinges_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_ = std::make_unique<btDiscreteDynamicsWorld>(
      dispatcher_.get(), broadphase_.get(), solver_.get(), configuration_.get());
  btScalar timeStep_;
};

}  // namespace

std::unique_ptr<joint_study::Engine> joint_study::makeBulletEngine(const Description& description, int iterations) {
  return std::make_unique<BulletJointEngine>(description, iterations);
}
