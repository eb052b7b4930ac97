#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "contact_scenes.hpp"
#include "error_message.hpp"
#include "policies.hpp"

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
  double mostWork = 0.0;   ///< the largest SolverStatistics::directWork of a step
  int mostIslands = 0;
};

template <class S>
PileRun runPile(double maxWork, int steps = 360) {
  spook::ref_ptr<spook::SimulationT<S>> sim = new spook::SimulationT<S>();
  sim->setSolver(spook::test::makeSolver(spook::test::Policy::DIRECT));
  if (maxWork > 0.0) sim->getSolver()->setMaxDirectWork(maxWork);
  spook::ref_ptr<spook::MaterialT<S>> material = new spook::MaterialT<S>("rubber");
  spook::test::addGround(*sim, material);
  const auto balls = spook::test::addSpherePile(*sim, material, material);
  PileRun run;
  run.lowest = std::numeric_limits<double>::infinity();
  double kinetic = 0.0;
  for (int step = 0; step < steps; ++step) {
    sim->stepForward();
    const auto& solver = sim->getStatistics().solver;
    run.factorizations += solver.factorizations;
    run.fallbacks += solver.directFallbacks;
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
  CHECK(starved.fallbacks >= 360);  // at least one island a step
  CHECK(starved.rmsSpeed < 0.01);
  CHECK(starved.deepest < 2e-3);
  CHECK(starved.lowest > 0.1 - 2e-3);  // radius 0.1 m on the ground

  // A budget that binds: the default's solves took more work in a step
  // within the first half second (from the 10th step on, 1.3e7 to 3.4e7
  // multiply-adds, float and double, measured 2026-12-06).
  const direct_work_test::PileRun unbound = direct_work_test::runPile<S>(0.0, 30);
  const double budget = 5e6;
  const direct_work_test::PileRun bound = direct_work_test::runPile<S>(budget);
  MESSAGE("default budget: most work in a step ", unbound.mostWork, "; budget ", budget, ": most ", bound.mostWork,
          ", ", bound.factorizations, " factorizations, rms speed ", bound.rmsSpeed * 1e3, " mm/s");
  CHECK(unbound.mostWork > budget);
  CHECK(bound.factorizations > 0);
  CHECK(bound.mostWork <= budget * bound.mostIslands);
  CHECK(bound.rmsSpeed < 0.01);
  CHECK(bound.lowest > 0.1 - 2e-3);
}
