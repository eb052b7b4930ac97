// The contact study's scenes in Bullet (compiled when CMake finds the
// `bullet` package): a btDiscreteDynamicsWorld with Bullet's default
// collision setup, stepped with the sequential-impulse solver or with the
// MLCP solver and its Dantzig LCP.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include <BulletDynamics/MLCPSolvers/btDantzigSolver.h>
#include <BulletDynamics/MLCPSolvers/btMLCPSolver.h>
#include <btBulletDynamicsCommon.h>

#include "study_engine.hpp"

namespace {

enum class BulletSolver { SEQUENTIAL_IMPULSE, MLCP_DANTZIG };

btVector3 toBullet(const study::Point& p) { return {btScalar(p[0]), btScalar(p[1]), btScalar(p[2])}; }

std::unique_ptr<btCollisionShape> makeShape(const study::BodySpec& spec) {
  switch (spec.shape) {
    case study::ShapeType::PLANE:
      return std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), btScalar(0));
    case study::ShapeType::BOX:
      // Bullet's default collision margin (0.04 m) lies inside the half
      // extents: the box keeps its size and gets edges rounded by the margin.
      return std::make_unique<btBoxShape>(toBullet(spec.halfExtents));
    case study::ShapeType::SPHERE:
      return std::make_unique<btSphereShape>(btScalar(spec.radius));
  }
  return nullptr;
}

// Bullet's sequential impulses with the time of their sweeps
// (solveGroupCacheFriendlyIterations: not the setup that converts contacts
// to rows, nor the write-back) and the rows they updated (its row pools at
// each sweep), for the cost per row update beside spook's.
class TimedSequentialImpulse final : public btSequentialImpulseConstraintSolver {
 public:
  study::SolverCost cost;

  btScalar solveGroupCacheFriendlyIterations(btCollisionObject** bodies, int numBodies, btPersistentManifold** manifolds,
                                             int numManifolds, btTypedConstraint** constraints, int numConstraints,
                                             const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override {
    const auto start = std::chrono::steady_clock::now();
    const btScalar residual = btSequentialImpulseConstraintSolver::solveGroupCacheFriendlyIterations(
        bodies, numBodies, manifolds, numManifolds, constraints, numConstraints, info, debugDrawer);
    cost.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return residual;
  }

  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int numBodies,
                                btPersistentManifold** manifolds, int numManifolds, btTypedConstraint** constraints,
                                int numConstraints, const btContactSolverInfo& info, btIDebugDraw* debugDrawer) override {
    cost.rowUpdates += double(m_tmpSolverContactConstraintPool.size() + m_tmpSolverNonContactConstraintPool.size() +
                              m_tmpSolverContactFrictionConstraintPool.size() +
                              m_tmpSolverContactRollingFrictionConstraintPool.size());
    return btSequentialImpulseConstraintSolver::solveSingleIteration(iteration, bodies, numBodies, manifolds,
                                                                     numManifolds, constraints, numConstraints, info,
                                                                     debugDrawer);
  }
};

class BulletEngine final : public study::Engine {
 public:
  BulletEngine(const study::SceneDescription& scene, BulletSolver solver) : timeStep_(btScalar(scene.timeStep)) {
    if (solver == BulletSolver::MLCP_DANTZIG) {
      dantzig_ = std::make_unique<btDantzigSolver>();
      solver_ = std::make_unique<btMLCPSolver>(dantzig_.get());
    } else {
      auto timed = std::make_unique<TimedSequentialImpulse>();
      timed_ = timed.get();
      solver_ = std::move(timed);
    }
    world_ = std::make_unique<btDiscreteDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                       configuration_.get());
    world_->setGravity(btVector3(0, 0, btScalar(scene.gravity)));
    // As in Bullet's examples: one island per MLCP keeps its dense matrices
    // small (the default, 128, batches islands for the iterative solver).
    if (solver == BulletSolver::MLCP_DANTZIG) world_->getSolverInfo().m_minimumSolverBatchSize = 1;
    for (const study::BodySpec& spec : scene.bodies) add(spec, scene);
  }

  BulletEngine(const BulletEngine&) = delete;
  BulletEngine& operator=(const BulletEngine&) = delete;

  ~BulletEngine() override {
    for (const auto& body : bodies_) world_->removeRigidBody(body.get());
  }

  // maxSubSteps 0: exactly one internal step of timeStep, no interpolation.
  void step() override { world_->stepSimulation(timeStep_, 0); }

  study::Point position(std::size_t dynamicIndex) const override {
    const btVector3& p = dynamicBodies_[dynamicIndex]->getCenterOfMassPosition();
    return {double(p.x()), double(p.y()), double(p.z())};
  }

  double kineticEnergy() const override {
    double energy = 0.0;
    for (const btRigidBody* body : dynamicBodies_) {
      const btVector3 v = body->getLinearVelocity();
      const btVector3 bodyOmega = body->getCenterOfMassTransform().getBasis().transpose() * body->getAngularVelocity();
      const btVector3 inertia = body->getLocalInertia();
      energy += 0.5 / double(body->getInvMass()) * double(v.length2());
      for (int axis = 0; axis < 3; ++axis) energy += 0.5 * double(inertia[axis]) * double(bodyOmega[axis] * bodyOmega[axis]);
    }
    return energy;
  }

  study::SolverCost solverCost() const override { return timed_ ? timed_->cost : study::SolverCost{}; }

  // The manifolds hold the points of the last step's collision pass (before
  // its solve), including speculative ones still apart by less than the
  // contact breaking threshold (about 0.02 m): only touching points,
  // distance <= 0, count.
  study::ContactSummary contacts() const override {
    study::ContactSummary summary;
    const btCollisionDispatcher& dispatcher = *dispatcher_;
    for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
      const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
      for (int i = 0; i < manifold->getNumContacts(); ++i) {
        const double distance = double(manifold->getContactPoint(i).getDistance());
        if (distance > 0.0) continue;
        ++summary.points;
        summary.deepest = std::max(summary.deepest, -distance);
      }
    }
    return summary;
  }

 private:
  void add(const study::BodySpec& spec, const study::SceneDescription& scene) {
    btCollisionShape* shape = shapes_.emplace_back(makeShape(spec)).get();
    const btScalar mass = spec.dynamic ? btScalar(scene.density * study::volumeOf(spec)) : btScalar(0);
    btVector3 inertia(0, 0, 0);
    if (spec.dynamic) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform.setOrigin(toBullet(spec.position));
    // Bullet's pair friction is the product of the two bodies' values, so
    // each gets √μ and every pair μ.
    info.m_friction = btScalar(std::sqrt(scene.friction));
    info.m_restitution = 0;
    btRigidBody* body = bodies_.emplace_back(std::make_unique<btRigidBody>(info)).get();
    if (spec.dynamic) {
      // spook and ODE (auto-disable off by default) never put bodies to
      // sleep; Bullet's deactivation would freeze a slowly drifting stack.
      body->setActivationState(DISABLE_DEACTIVATION);
      dynamicBodies_.push_back(body);
    }
    world_->addRigidBody(body);
  }

  // Destroyed bottom-up: the world (emptied by the destructor) before the
  // bodies and shapes it used, those before the solvers and collision setup.
  std::unique_ptr<btDefaultCollisionConfiguration> configuration_ = std::make_unique<btDefaultCollisionConfiguration>();
  std::unique_ptr<btCollisionDispatcher> dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
  std::unique_ptr<btBroadphaseInterface> broadphase_ = std::make_unique<btDbvtBroadphase>();
  std::unique_ptr<btMLCPSolverInterface> dantzig_;
  std::unique_ptr<btConstraintSolver> solver_;
  const TimedSequentialImpulse* timed_ = nullptr;  ///< solver_, when sequential impulses
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
  std::unique_ptr<btDiscreteDynamicsWorld> world_;
  std::vector<btRigidBody*> dynamicBodies_;
  btScalar timeStep_;
};

}  // namespace

std::vector<study::ReferenceEngine> study::bulletEngines() {
  return {
      {"bullet SI",
       [](const SceneDescription& scene) -> std::unique_ptr<Engine> {
         return std::make_unique<BulletEngine>(scene, BulletSolver::SEQUENTIAL_IMPULSE);
       }},
      {"bullet MLCP",
       [](const SceneDescription& scene) -> std::unique_ptr<Engine> {
         return std::make_unique<BulletEngine>(scene, BulletSolver::MLCP_DANTZIG);
       }},
  };
}
