#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <spook/constraints/joints/hinge.hpp>

#include "contact_scenes.hpp"
#include "error_message.hpp"
#include "policies.hpp"
#include "tolerance.hpp"

// Solver::setMaxDirectWork: the direct solves of an island spend at most
// that many multiply-adds on factorizations in a step, and a solve that
// cannot afford one falls back to its safe answer (Gauss–Seidel from the
// best start) at once. A pile of spheres is the case it is for: its matrix
// fills in like a 3D mesh's, and its pivoting rarely converges.

namespace direct_work_test {

struct PileRun {
  double rmsSpeed = 0.0;   ///< over the last second (m/s)
  double deepest = 0.0;    ///< deepest contact over the last second (m)
  double lowest = 0.0;     ///< lowest sphere center (m)
  int factorizations = 0;  ///< over the run
  int fallbacks = 0;       ///< over the run
  int cuts = 0;            ///< coupling and friction passes the budget cut, over the run
  double mostWork = 0.0;   ///< the largest SolverStatistics::directWork of a step
  int mostIslands = 0;
  int steps = 0;
};

/// 6 s at 60 Hz; 3 s in the sanitized build.
constexpr int kPileSteps = spook::test::sweep(360, 180);

template <class S>
PileRun runPile(double maxWork, int steps = kPileSteps, spook::test::Policy policy = spook::test::Policy::DIRECT) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setSolver(spook::test::makeSolver(policy));
  if (maxWork > 0.0) sim->getSolver()->setMaxDirectWork(maxWork);
  spook::ref_ptr<spook::MaterialT<S>> material = new spook::MaterialT<S>("rubber");
  spook::test::addGround(*sim, material);
  const auto balls = spook::test::addSpherePile(*sim, material, material);
  PileRun run;
  run.steps = steps;
  run.lowest = std::numeric_limits<double>::infinity();
  double kinetic = 0.0;
  for (int step = 0; step < steps; ++step) {
    sim->stepForward();
    const auto& solver = sim->getStatistics().solver;
    run.factorizations += solver.factorizations;
    run.fallbacks += solver.directFallbacks;
    run.cuts += solver.pivotBudgetCuts;
    run.mostWork = std::max(run.mostWork, solver.directWork);
    run.mostIslands = std::max(run.mostIslands, solver.numIslands);
    if (step < steps - 60) continue;
    for (const auto& b : balls) {
      const double m = double(b->getMassProperties()->getMass());
      kinetic += 0.5 * m * double(b->getVelocity().squaredNorm()) / 60.0;
      run.lowest = std::min(run.lowest, double(b->getPosition().z()));
    }
    for (const auto& c : sim->getGeometryContacts())
      for (const auto& p : c.points())
        if (p.enabled) run.deepest = std::max(run.deepest, double(p.depth));
  }
  const double mass = double(balls[0]->getMassProperties()->getMass());
  run.rmsSpeed = std::sqrt(2.0 * kinetic / (mass * double(balls.size())));
  return run;
}

}  // namespace direct_work_test

TEST_CASE("Solver::setMaxDirectWork rejects a budget that is not positive") {
  spook::ref_ptr<spook::Solver> solver = new spook::DirectSolver();
  const double before = solver->getMaxDirectWork();
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    const std::string message = spook::test::errorMessage([&] { solver->setMaxDirectWork(bad); });
    CAPTURE(message);
    CHECK(message.find("Solver 'direct'") != std::string::npos);
    CHECK(message.find("maximum direct work must be > 0") != std::string::npos);
    CHECK(solver->getMaxDirectWork() == before);
  }
  solver->setMaxDirectWork(1e6);
  CHECK(solver->getMaxDirectWork() == 1e6);
  spook::ref_ptr<spook::Solver> copy = new spook::HybridSolver();
  copy->copySettings(*solver);
  CHECK(copy->getMaxDirectWork() == 1e6);
}

// A budget below one factorization: no direct solve factorizes, every one
// falls back, and the safe answer still brings the 64-sphere pile to rest
// on the ground without sinking into it. A budget below what the solves
// take is kept in every step, and the pile rests under it too.
TEST_CASE_TEMPLATE("a direct solve that cannot afford a factorization falls back and the pile rests", S, float,
                   double) {
  const direct_work_test::PileRun starved = direct_work_test::runPile<S>(1.0);
  MESSAGE("budget 1: rms speed ", starved.rmsSpeed * 1e3, " mm/s, deepest ", starved.deepest * 1e3, " mm, ",
          starved.fallbacks, " fallbacks");
  CHECK(starved.factorizations == 0);
  CHECK(starved.mostWork == 0.0);
  CHECK(starved.fallbacks >= starved.steps);  // at least one island a step
  CHECK(starved.rmsSpeed < 0.01);
  CHECK(starved.deepest < 2e-3);
  CHECK(starved.lowest > 0.1 - 2e-3);  // radius 0.1 m on the ground

  // A budget that binds: the default's solves took more work in a step
  // within the first half second (from the 10th step on, float and double,
  // measured 2026-12-06).
  const direct_work_test::PileRun unbound = direct_work_test::runPile<S>(0.0, 30);
  const double budget = 1e6;
  const direct_work_test::PileRun bound = direct_work_test::runPile<S>(budget);
  MESSAGE("default budget: most work in a step ", unbound.mostWork, "; budget ", budget, ": most ", bound.mostWork,
          ", ", bound.factorizations, " factorizations, rms speed ", bound.rmsSpeed * 1e3, " mm/s");
  CHECK(unbound.mostWork > budget);
  CHECK(bound.factorizations > 0);
  CHECK(bound.mostWork <= budget * bound.mostIslands);
  CHECK(bound.rmsSpeed < 0.01);
  CHECK(bound.lowest > 0.1 - 2e-3);
}

// The hybrid's direct normals and Gauss–Seidel friction: where a direct
// pass falls back or its budget cuts it short, the step's closing pass of
// Gauss–Seidel sweeps the normals with the friction, so that the normals
// answer the friction that moved after their last direct solve. Held
// instead, they let this pile overlap 2.9-3.8 mm (swept: 0.26-0.56 mm,
// measured 2026-12-06); 200 spheres in a box under a budget of 1e6, 23 mm
// (2 mm); 1,000 (bench/contact_study) under the default budget, 18 mm
// (0.8 mm).
TEST_CASE_TEMPLATE("the hybrid's normals answer the friction when its direct solves run out of budget", S, float,
                   double) {
  for (const double budget : {1.0, 1e5}) {
    // 6 s in every build: the float pile still moves at 37 mm/s after 3 s.
    const direct_work_test::PileRun run = direct_work_test::runPile<S>(budget, 360, spook::test::Policy::HYBRID);
    MESSAGE("budget ", budget, ": deepest ", run.deepest * 1e3, " mm, rms speed ", run.rmsSpeed * 1e3, " mm/s, ",
            run.fallbacks, " fallbacks, ", run.cuts, " cuts");
    CAPTURE(budget);
    CHECK(run.fallbacks + run.cuts >= run.steps * 5 / 6);  // the budget binds in most steps
    CHECK(run.deepest < 1.5e-3);
    CHECK(run.rmsSpeed < 0.01);
    CHECK(run.lowest > 0.1 - 2e-3);
  }
}

// A chain's factor costs a few dozen multiply-adds a row, its pivot steps
// ten to thirty times more (residuals, solves, sparse bookkeeping): the work
// counted for a step of 200 hinged links is at least
// Solver::kDirectRowWork a row (about 47 a row by its factor alone), and a
// budget below what the step takes is kept.
TEST_CASE("the direct work of a step counts every row of each pivot step, and a chain keeps its budget") {
  const auto chainStep = [](double budget) {
    spook::SimulationRef sim = new spook::Simulation();
    sim->setSolver(new spook::DirectSolver());
    if (budget > 0.0) sim->getSolver()->setMaxDirectWork(budget);
    spook::RigidBody* previous = nullptr;
    for (int i = 0; i < 200; ++i) {
      spook::RigidBodyRef link =
          new spook::RigidBody(new spook::Geometry(new spook::Box(spook::Vec3(0.25, 0.05, 0.05))));
      link->setPosition(0.5 * i + 0.25, 0, 10);
      for (const auto& g : link->getGeometries()) g->setEnableCollisions(false);
      sim->add(link);
      spook::FrameRef pin = new spook::Frame();
      pin->setLocalTranslate(spook::Vec3(-0.25, 0, 0));
      pin->setLocalRotate(spook::Quat(Eigen::AngleAxisd(spook::PI_2, spook::Vec3::UnitX())));
      sim->add(spook::HingeRef(previous ? new spook::Hinge(link.get(), pin.get(), previous)
                                        : new spook::Hinge(link.get(), pin.get())));
      previous = link.get();
    }
    sim->stepForward();
    return sim->getStatistics().solver;
  };
  const spook::SolverStatistics free = chainStep(0.0);
  MESSAGE("200 links: ", free.numRows, " rows, ", free.factorizations, " factorizations, work ", free.directWork);
  REQUIRE(free.factorizations >= 1);
  CHECK(free.directWork >= spook::Solver::kDirectRowWork * free.numRows);
  CHECK(free.directFallbacks == 0);

  const double budget = free.directWork / 3.0;  // below the first solve's one pivot step
  const spook::SolverStatistics bound = chainStep(budget);
  CHECK(bound.directWork <= budget);
  CHECK(bound.directFallbacks >= 1);
}
