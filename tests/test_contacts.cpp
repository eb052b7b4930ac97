#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <spook/constraints/joints/lock_joint.hpp>

#include "contact_scenes.hpp"
#include "tolerance.hpp"

// Contact dynamics against analytic references (PHYSICS.md §1.4, §7).

using spook::test::Policy;
using spook::test::pick;

namespace {

constexpr double kG = 9.80665;

template <class S>
struct Materials {
  spook::ref_ptr<spook::MaterialT<S>> ground = new spook::MaterialT<S>("ground");
  spook::ref_ptr<spook::MaterialT<S>> body = new spook::MaterialT<S>("body");
};

}  // namespace

TEST_CASE_TEMPLATE("a sphere resting on a plane carries its weight exactly and does not drift", S, float, double) {
  for (Policy policy : {Policy::DIRECT, Policy::HYBRID}) {
    const std::string name = spook::test::policyName(policy);
    CAPTURE(name);
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(spook::test::makeSolver(policy));
    Materials<S> m;
    spook::test::addGround(*sim, m.ground);
    auto ball = spook::test::addBody(*sim, "ball", new spook::SphereT<S>(S(0.5)), m.body, spook::Vec3T<S>(S(0), S(0), S(0.5)));
    const S weight = ball->getMassProperties()->getMass() * S(kG);
    S low = S(1e9), high = S(-1e9), worstForce = S(0);
    for (int step = 0; step < 600; ++step) {
      sim->stepForward();
      if (step < 60) continue;
      const S z = ball->getPosition().z();
      low = std::min(low, z);
      high = std::max(high, z);
      worstForce = std::max(worstForce, std::abs(spook::test::normalForceOn(*sim, ball.get()) - weight) / weight);
    }
    MESSAGE(name, ": |N - mg|/mg <= ", worstForce, ", height range ", high - low, " m");
    CHECK(worstForce < pick<S>(1e-6, 1e-4));
    CHECK(high - low < pick<S>(1e-6, 1e-5));
    // It rests where the contact's compliance puts it: overlap mg/E.
    CHECK(std::abs(ball->getPosition().z() - S(0.5)) < S(1e-4));
  }
}

namespace {

// A unit cube on a plane tilted by 30° about x, released from rest 10 µm
// into it (in float, a cube placed exactly on the plane may touch it at two
// corners only: the others' rounding leaves them 1e-8 m above); returns
// the velocity gained along the slope from t = 0.5 s to 2 s and the distance
// travelled in 2 s (m).
template <class S>
std::pair<double, double> slideOnIncline(Policy policy, S mu, const spook::ref_ptr<spook::FrictionModelT<S>>& model = nullptr) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setSolver(spook::test::makeSolver(policy));
  Materials<S> m;
  const S theta = S(std::numbers::pi / 6);
  const spook::QuatT<S> tilt(Eigen::AngleAxis<S>(theta, spook::Vec3T<S>::UnitX()));
  spook::test::addGround(*sim, m.ground, spook::Vec3T<S>(tilt * spook::Vec3T<S>::UnitZ()));
  auto cm = sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get());
  cm->setFrictionCoefficient(mu);
  cm->setYoungsModulus(S(1e10));
  if (model) cm->setFrictionModel(model);
  auto box = spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), m.body,
                                  spook::Vec3T<S>(tilt * spook::Vec3T<S>(S(0), S(0), S(0.5) - S(1e-5))), tilt);
  const spook::Vec3T<S> downSlope = tilt * spook::Vec3T<S>(S(0), S(-1), S(0));
  const spook::Vec3T<S> start = box->getPosition();
  double early = 0.0;
  for (int step = 1; step <= 120; ++step) {
    sim->stepForward();
    if (step == 30) early = double(box->getVelocity().dot(downSlope));
  }
  return {double(box->getVelocity().dot(downSlope)) - early, double((box->getPosition() - start).dot(downSlope))};
}

}  // namespace

TEST_CASE_TEMPLATE("a box on a 30 degree incline slides with g(sin - mu cos) or sticks (Coulomb)", S, float, double) {
  const double theta = std::numbers::pi / 6;
  const double exact = kG * (std::sin(theta) - 0.5 * std::cos(theta));
  for (Policy policy : {Policy::DIRECT, Policy::HYBRID, Policy::ITERATIVE}) {
    const std::string name = spook::test::policyName(policy);
    CAPTURE(name);
    const auto [gained, travelled] = slideOnIncline<S>(policy, S(0.5));
    const double a = gained / 1.5;
    const auto [gainedStuck, travelledStuck] = slideOnIncline<S>(policy, S(0.7));
    MESSAGE(name, ": mu 0.5 a = ", a, " (exact ", exact, ", ", 100 * (a / exact - 1),
            "%); mu 0.7 moves ", travelledStuck, " m in 2 s");
    if (policy == Policy::ITERATIVE) continue;  // reported only
    CHECK(std::abs(a / exact - 1) < 0.01);
    CHECK(std::abs(travelledStuck) < 1e-3);
    (void)travelled;
    (void)gainedStuck;
  }
}

TEST_CASE_TEMPLATE("a sphere dropped with restitution 0.5 rebounds to e^2 h", S, float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setSolver(new spook::DirectSolver());
  sim->setTimeStep(S(1e-3));
  Materials<S> m;
  spook::test::addGround(*sim, m.ground);
  sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get())->setRestitution(S(0.5));
  const S r = S(0.1), h = S(1);
  auto ball = spook::test::addBody(*sim, "ball", new spook::SphereT<S>(r), m.body, spook::Vec3T<S>(S(0), S(0), r + h));
  bool bounced = false;
  S apex = S(0);
  for (int step = 0; step < 2500; ++step) {
    sim->stepForward();
    if (ball->getVelocity().z() > S(0)) bounced = true;
    if (bounced) apex = std::max(apex, ball->getPosition().z() - r);
    if (bounced && ball->getVelocity().z() < S(0)) break;
  }
  MESSAGE("rebound apex ", apex, " m, e^2 h = 0.25 m");
  CHECK(bounced);
  CHECK(std::abs(apex / S(0.25) - S(1)) < S(0.02));
}

TEST_CASE_TEMPLATE("a box on a conveyor reaches the belt speed", S, float, double) {
  for (Policy policy : {Policy::DIRECT, Policy::HYBRID, Policy::ITERATIVE}) {
    const std::string name = spook::test::policyName(policy);
    CAPTURE(name);
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(spook::test::makeSolver(policy));
    Materials<S> m;
    auto belt = spook::test::addGround(*sim, m.ground);
    belt->setSurfaceVelocity(spook::Vec3T<S>(S(1), S(0), S(0)));
    auto box = spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.25))), m.body,
                                    spook::Vec3T<S>(S(0), S(0), S(0.25)));
    for (int step = 0; step < 120; ++step) sim->stepForward();
    MESSAGE(name, ": box speed ", box->getVelocity().transpose());
    CHECK(std::abs(box->getVelocity().x() - S(1)) < S(1e-3));
    CHECK(std::abs(box->getVelocity().y()) < S(1e-3));
  }
}

TEST_CASE_TEMPLATE("a sensor reports its contacts and applies no force", S, float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  Materials<S> m;
  auto ground = spook::test::addGround(*sim, m.ground);
  ground->setSensor(true);
  auto ball = spook::test::addBody(*sim, "ball", new spook::SphereT<S>(S(0.5)), m.body, spook::Vec3T<S>(S(0), S(0), S(0.4)));
  const S h = sim->getTimeStep();
  std::size_t reported = 0;
  for (int n = 1; n <= 30; ++n) {
    sim->stepForward();
    reported += sim->getGeometryContacts().size();
    // Symplectic Euler free fall: z_n = z_0 − g h² n(n+1)/2.
    const S expected = S(0.4) - S(kG) * h * h * S(n * (n + 1)) / S(2);
    REQUIRE(std::abs(ball->getPosition().z() - expected) < pick<S>(1e-12, 1e-5));
  }
  CHECK(reported >= 29);
}

TEST_CASE_TEMPLATE("a box created half inside the ground separates no faster than the stated bound", S, float, double) {
  for (Policy policy : {Policy::DIRECT, Policy::HYBRID}) {
    const std::string name = spook::test::policyName(policy);
    CAPTURE(name);
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(spook::test::makeSolver(policy));
    Materials<S> m;
    spook::test::addGround(*sim, m.ground);
    auto box = spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), m.body,
                                    spook::Vec3T<S>(S(0), S(0), S(0)));
    // Bound: the stabilization asks at most getMaxDepenetrationSpeed (1 m/s);
    // SPOOK's b' term may add what the body already moves at, 1/(1+4d) of it.
    const S bound = sim->getMaxDepenetrationSpeed() * S(1.1);
    S fastest = S(0);
    for (int step = 0; step < 300; ++step) {
      sim->stepForward();
      fastest = std::max(fastest, box->getVelocity().norm());
    }
    MESSAGE(name, ": fastest ", fastest, " m/s, rests at z = ", box->getPosition().z());
    CHECK(fastest <= bound);
    CHECK(std::abs(box->getPosition().z() - S(0.5)) < S(1e-3));
  }
}

TEST_CASE_TEMPLATE("a push at 45 degrees to the friction axes tells the cone from the box", S, float, double) {
  // F = 1.2 μmg horizontally, at 45° to the primary direction x: the cone
  // slides with a = (F − μmg)/m; a box bounding each tangent by μN holds up
  // to √2 μmg and sticks.
  const S mu = S(0.5);
  for (int useBox = 0; useBox < 2; ++useBox) {
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(new spook::DirectSolver());
    Materials<S> m;
    spook::test::addGround(*sim, m.ground);
    auto box = spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), m.body,
                                    spook::Vec3T<S>(S(0), S(0), S(0.5)));
    const S mass = box->getMassProperties()->getMass();
    spook::ref_ptr<spook::FrictionModelT<S>> model;
    if (useBox) {
      auto boxFriction = new spook::BoxFrictionT<S>();
      boxFriction->setNormalForceMagnitude(mass * S(kG));
      model = boxFriction;
    } else {
      model = new spook::IterativeProjectedConeFrictionT<S>();
    }
    model->setPrimaryDirection(spook::Vec3T<S>::UnitX());
    model->setSolveType(spook::SolveType::DIRECT);
    auto cm = sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get());
    cm->setFrictionCoefficient(mu);
    cm->setFrictionModel(model);
    const S push = S(1.2) * mu * mass * S(kG);
    const spook::Vec3T<S> along = spook::Vec3T<S>(S(1), S(1), S(0)).normalized();
    int mostFrictionIterations = 0;
    for (int step = 0; step < 60; ++step) {
      box->addForce(along * push);
      sim->stepForward();
      mostFrictionIterations = std::max(mostFrictionIterations, sim->getStatistics().solver.frictionIterations);
    }
    // The cone's direction is found by the friction iterations; fixed box
    // bounds need none beyond the first solve.
    if (useBox) {
      CHECK(mostFrictionIterations == 1);
    } else {
      CHECK(mostFrictionIterations >= 2);
      CHECK(mostFrictionIterations <= sim->getSolver()->getNumFrictionIterations());
    }
    const S speed = box->getVelocity().norm();
    const S expected = useBox ? S(0) : (push - mu * mass * S(kG)) / mass * S(1);
    MESSAGE(std::string(useBox ? "box" : "cone"), ": speed after 1 s ", speed, " m/s, expected ", expected);
    CHECK(std::abs(speed - expected) < S(0.01) * std::max(expected, S(1)));
  }
}

// Coulomb's law at every point of a settling pile: 64 spheres (4 x 4 x 4,
// radius 0.1 m) poured into a box of four walls, μ 0.5, the default cone
// model solved SPLIT (the hybrid's normals direct, friction by Gauss-Seidel).
// The friction force must never exceed μ times the normal force. The hybrid
// once left up to 4 μFn: its last direct pass moved the normals after the
// friction was solved against the earlier ones. The direct policy is not
// held to it yet: its cone iterations, stopped before their bounds settle
// (8 iterations or the pivot budget), keep the bounds of an earlier pass
// (up to 56 μFn on this pile; open).
TEST_CASE_TEMPLATE("friction at every point of a settling pile stays within the Coulomb cone (hybrid, iterative)", S,
                   float, double) {
  const S mu = S(0.5);
  for (const Policy policy : {Policy::HYBRID, Policy::ITERATIVE}) {
    CAPTURE(spook::test::policyName(policy));
    spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
    sim->setSolver(spook::test::makeSolver(policy));
    Materials<S> m;
    spook::test::addGround(*sim, m.ground);
    spook::test::addSpherePile(*sim, m.ground, m.body);
    spook::ref_ptr<spook::FrictionModelT<S>> model = new spook::IterativeProjectedConeFrictionT<S>();
    model->setSolveType(spook::SolveType::SPLIT);
    for (auto* pair : {sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get()),
                       sim->getMaterialManager()->getOrCreateContactMaterial(m.body.get(), m.body.get())}) {
      pair->setFrictionCoefficient(mu);
      pair->setFrictionModel(model);
    }
    double worstExcess = -std::numeric_limits<double>::infinity(), largestFriction = 0.0, worstRatio = 0.0;
    int points = 0;
    for (int step = 0; step < spook::test::sweep(120, 40); ++step) {
      sim->stepForward();
      for (const auto& contact : sim->getGeometryContacts())
        for (const auto& p : contact.points()) {
          if (!p.enabled) continue;
          ++points;
          const double friction = double(p.getTangentialForceMagnitude());
          const double limit = double(mu) * std::max(0.0, double(p.getNormalForceMagnitude()));
          // Round-off of the stored force (float: 24-bit components).
          const double slack = pick<S>(1e-10, 1e-5) * double(p.getForce().norm()) + pick<S>(1e-12, 1e-6);
          worstExcess = std::max(worstExcess, friction - limit - slack);
          if (limit > 0.1) worstRatio = std::max(worstRatio, friction / limit);
          largestFriction = std::max(largestFriction, friction);
        }
    }
    MESSAGE(spook::test::policyName(policy), ": ", points, " point-steps, largest friction ", largestFriction,
            " N, at most ", worstRatio, " mu Fn where mu Fn > 0.1 N");
    CHECK(largestFriction > 1.0);  // the pile's points carry friction
    CHECK(worstExcess <= 0.0);
  }
}

TEST_CASE_TEMPLATE("a joint and a contact share a load by their compliances; getLastForce sees the joint's part", S,
                   float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setSolver(new spook::DirectSolver());
  Materials<S> m;
  spook::test::addGround(*sim, m.ground);
  const S E = S(1e8);
  sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get())->setYoungsModulus(E);
  auto box = spook::test::addBody(*sim, "box", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), m.body,
                                  spook::Vec3T<S>(S(0), S(0), S(0.5)));
  // Four contact points of stiffness E each in parallel with a lock of
  // stiffness 2E: the lock carries a third of the weight.
  spook::ref_ptr<spook::LockJointT<S>> lock = new spook::LockJointT<S>(box.get());
  lock->setCompliance(S(1) / (S(2) * E));
  lock->setEnableComputeForces(true);
  sim->add(lock);
  for (int step = 0; step < 300; ++step) sim->stepForward();
  const S weight = box->getMassProperties()->getMass() * S(kG);
  spook::Vec3T<S> force = spook::Vec3T<S>::Zero(), torque = spook::Vec3T<S>::Zero();
  REQUIRE(lock->getLastForce(box.get(), force, torque));
  const S contact = spook::test::normalForceOn(*sim, box.get());
  MESSAGE("lock carries ", force.z() / weight, " of the weight, contacts ", contact / weight);
  CHECK(std::abs(force.z() / weight - S(1) / S(3)) < S(0.01));
  CHECK(std::abs((force.z() + contact) / weight - S(1)) < pick<S>(1e-6, 1e-4));
}

TEST_CASE_TEMPLATE("an explicit contact material chooses the contact reduction of its pair", S, float, double) {
  // A cube turned 45° on a static block of its size: the square faces
  // overlap in an octagon, eight contact points.
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  Materials<S> m;
  spook::ref_ptr<spook::GeometryT<S>> block =
      new spook::GeometryT<S>(new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), spook::TransformT<S>::Identity(), "block");
  block->setMaterial(m.ground);
  sim->add(block);
  const spook::QuatT<S> turned(Eigen::AngleAxis<S>(S(std::numbers::pi / 4), spook::Vec3T<S>::UnitZ()));
  spook::test::addBody(*sim, "cube", new spook::BoxT<S>(spook::Vec3T<S>::Constant(S(0.5))), m.body,
                       spook::Vec3T<S>(S(0), S(0), S(0.999)), turned);
  const auto counts = [&] {
    sim->getSpace()->update(sim->getRigidBodies());
    std::size_t all = 0, enabled = 0;
    for (const auto& c : sim->getGeometryContacts()) {
      all += c.points().size();
      enabled += c.getNumEnabledPoints();
    }
    return std::pair{all, enabled};
  };
  const auto [all, reduced] = counts();
  REQUIRE(all > 4);
  CHECK(reduced < all);
  auto cm = sim->getMaterialManager()->getOrCreateContactMaterial(m.ground.get(), m.body.get());
  cm->setContactReductionMode(spook::ContactReductionMode::REDUCE_NONE);
  CHECK(counts().second == all);
  cm->setContactReductionMode(spook::ContactReductionMode::REDUCE_GEOMETRY);
  CHECK(counts().second == reduced);
}

TEST_CASE_TEMPLATE("contact settings refuse bad values and keep theirs", S, float, double) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setRestitutionThreshold(S(0.5));
  sim->setMaxDepenetrationSpeed(S(2));
  CHECK_THROWS_WITH_AS(sim->setRestitutionThreshold(S(-1)), doctest::Contains("-1"), spook::Error);
  CHECK_THROWS_AS(sim->setRestitutionThreshold(std::numeric_limits<S>::quiet_NaN()), spook::Error);
  CHECK_THROWS_WITH_AS(sim->setMaxDepenetrationSpeed(S(0)), doctest::Contains("depenetration"), spook::Error);
  CHECK(sim->getRestitutionThreshold() == S(0.5));
  CHECK(sim->getMaxDepenetrationSpeed() == S(2));
}
