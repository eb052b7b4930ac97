// Cost of the constraint solver on chains of n links (n = 10 … 1000) hanging
// from the world, one joint per link (ball joints: 3 rows each; hinges: 5):
//
//   collectRows   every body to solver form and every constraint's rows
//                 (what Simulation does before the islands)
//   buildProblem  islands and their IslandProblem (Σ, q, M⁻¹Gᵀ per row)
//                 through IslandStepper with a policy that solves nothing;
//                 includes the O(n) write-back and the complementarity check
//                 that Solver::solve does after every island
//   directSolve   one DirectSolve: block-sparse assembly of S + Σ, sparse
//                 LDLᵀ (AMD ordering, symbolic + numeric) and the solve
//   pgsSweep      one projected Gauss–Seidel sweep (plus its O(n) setup)
//   jacobiSweep   one Jacobi sweep
//   step          Simulation::stepForward under each policy: direct,
//                 iterative (16 sweeps, tolerance 0 so every sweep runs) and
//                 hybrid (default solve types: the joints are
//                 DIRECT_AND_ITERATIVE, so it solves them directly)
//
// Each family is fitted by Google Benchmark (`oAuto`: the best of O(1), O(n),
// O(n log n), O(n²), …) and, after the run, by a least-squares power law
// t = c·nᵖ over all sizes: the exponent p should be 1 for everything here.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include <spook/solver/direct_solve.hpp>
#include <spook/solver/integrator.hpp>
#include <spook/solver/islands.hpp>
#include <spook/solver/iterative_solve.hpp>
#include <spook/spook.hpp>

namespace {

using spook::Vec3;
constexpr double kStep = 1.0 / 60.0;  // s

/// A frame at `point` of its parent with z along `axis`.
spook::FrameRef frameAt(const Vec3& point, const Vec3& axis = Vec3::UnitZ()) {
  spook::FrameRef f = new spook::Frame();
  f->setLocalTranslate(point);
  f->setLocalRotate(spook::rotate<double>(Vec3::UnitZ(), axis));
  return f;
}

/// n links of 1 kg and 1 m hanging straight down from a world pivot at the
/// origin; hinges turn about y.
template <class Joint>
spook::SimulationRef makeChain(int links) {
  spook::SimulationRef sim = new spook::Simulation();
  sim->setTimeStep(kStep);
  spook::RigidBody* previous = nullptr;
  for (int i = 0; i < links; ++i) {
    spook::RigidBodyRef link = new spook::RigidBody("link");
    link->getMassProperties()->setMass(1.0);
    link->getMassProperties()->setInertiaTensor(Vec3(0.1, 0.1, 0.01));
    link->setPosition(Vec3(0, 0, -0.5 - i));
    sim->add(link);
    const Vec3 axis = Vec3::UnitY();
    spook::FrameRef above = previous ? frameAt(Vec3(0, 0, -0.5), axis) : frameAt(Vec3::Zero(), axis);
    sim->add(spook::ref_ptr<spook::Constraint>(
        new Joint(link.get(), frameAt(Vec3(0, 0, 0.5), axis).get(), previous, above.get())));
    previous = link.get();
  }
  return sim;
}

/// A policy that solves nothing, and optionally keeps a copy of the island.
class NullSolver final : public spook::Solver {
 public:
  [[nodiscard]] const char* getName() const override { return "none"; }
  bool capture = false;
  spook::detail::IslandProblem captured;

 protected:
  void solveIsland(spook::detail::IslandProblem& problem, spook::SolverStatistics&) override {
    if (capture) captured = problem;
  }
};

/// The simulation's first half-step, done by hand through spook::detail:
/// bodies in solver form and the rows of every constraint.
struct RowCollector {
  explicit RowCollector(spook::Simulation& sim) : sim_(sim) {
    for (std::size_t i = 0; i < sim.getRigidBodies().size(); ++i) index_[sim.getRigidBodies()[i].get()] = int(i);
  }
  void collect() {
    bodies.clear();
    for (const auto& body : sim_.getRigidBodies())
      bodies.push_back(spook::detail::BodyIntegrator<double>::solverBody(*body, *sim_.getGravityField(), kStep));
    rows.clear();
    for (const auto& c : sim_.getConstraints()) {
      spook::RigidBody* body2 = c->getBodyAt(1);
      spook::detail::RowSink sink{&rows.rows, index_.at(c->getBodyAt(0)), body2 ? index_.at(body2) : -1,
                                  c->getSolveType(), false, nullptr, &rows.arms};
      spook::detail::ConstraintAccess::addRows(*c, sink, kStep);
    }
    rows.impulses.assign(rows.size(), 0.0);
  }
  std::vector<spook::detail::SolverBody> bodies;
  spook::detail::RowSet rows;

 private:
  spook::Simulation& sim_;
  std::unordered_map<const spook::RigidBody*, int> index_;
};

/// The chain's single island as the policies see it.
template <class Joint>
spook::detail::IslandProblem chainProblem(int links) {
  spook::SimulationRef sim = makeChain<Joint>(links);
  RowCollector collector(*sim);
  collector.collect();
  spook::ref_ptr<NullSolver> none = new NullSolver();
  none->capture = true;
  spook::SolverStatistics statistics;
  spook::detail::IslandStepper().solve(collector.rows, collector.bodies, kStep, *none, statistics);
  return none->captured;
}

std::vector<int> allRows(const spook::detail::IslandProblem& problem) {
  std::vector<int> rows(problem.rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = int(i);
  return rows;
}

void setCounters(benchmark::State& state, std::size_t rows) {
  state.SetComplexityN(state.range(0));
  state.counters["rows"] = double(rows);
  // Time per row (printed with its SI prefix, e.g. 250ns).
  state.counters["per_row"] =
      benchmark::Counter(double(rows), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

template <class Joint>
void collectRows(benchmark::State& state) {
  spook::SimulationRef sim = makeChain<Joint>(int(state.range(0)));
  RowCollector collector(*sim);
  for (auto _ : state) {
    collector.collect();
    benchmark::DoNotOptimize(collector.rows.rows.data());
  }
  setCounters(state, collector.rows.size());
}

template <class Joint>
void buildProblem(benchmark::State& state) {
  spook::SimulationRef sim = makeChain<Joint>(int(state.range(0)));
  RowCollector collector(*sim);
  collector.collect();
  spook::ref_ptr<NullSolver> none = new NullSolver();
  spook::detail::IslandStepper stepper;
  for (auto _ : state) {
    spook::SolverStatistics statistics;
    stepper.solve(collector.rows, collector.bodies, kStep, *none, statistics);
    benchmark::DoNotOptimize(statistics);
  }
  setCounters(state, collector.rows.size());
}

template <class Joint>
void directSolve(benchmark::State& state) {
  spook::detail::IslandProblem problem = chainProblem<Joint>(int(state.range(0)));
  const std::vector<int> rows = allRows(problem);
  spook::detail::DirectSolve direct;
  for (auto _ : state) {
    const auto result = direct.solve(problem, rows, 200);
    benchmark::DoNotOptimize(result);
  }
  setCounters(state, rows.size());
}

template <class Joint, bool kJacobi>
void sweep(benchmark::State& state) {
  spook::detail::IslandProblem problem = chainProblem<Joint>(int(state.range(0)));
  const std::vector<int> rows = allRows(problem);
  for (auto _ : state) {
    const auto result = spook::detail::iterativeSolve(problem, rows, 1, 0.0, kJacobi);
    benchmark::DoNotOptimize(result);
  }
  setCounters(state, rows.size());
}

template <class Joint, class Policy>
void step(benchmark::State& state) {
  spook::SimulationRef sim = makeChain<Joint>(int(state.range(0)));
  spook::ref_ptr<Policy> policy = new Policy();
  policy->setTolerance(0.0);  // iterative: always the 16 default sweeps
  sim->setSolver(policy);
  for (auto _ : state) sim->stepForward();
  setCounters(state, std::size_t(sim->getStatistics().solver.numRows));
  if (sim->getStatistics().solver.nonFiniteIslands > 0) state.SkipWithError("non-finite impulses");
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int n : {10, 30, 100, 300, 1000}) b->Arg(n);
  b->ArgName("links")->Complexity(benchmark::oAuto)->Unit(benchmark::kMicrosecond);
}

using spook::BallJoint;
using spook::Hinge;
BENCHMARK(collectRows<BallJoint>)->Apply(sizes);
BENCHMARK(collectRows<Hinge>)->Apply(sizes);
BENCHMARK(buildProblem<BallJoint>)->Apply(sizes);
BENCHMARK(buildProblem<Hinge>)->Apply(sizes);
BENCHMARK(directSolve<BallJoint>)->Apply(sizes);
BENCHMARK(directSolve<Hinge>)->Apply(sizes);
BENCHMARK(sweep<BallJoint, false>)->Name("pgsSweep<BallJoint>")->Apply(sizes);
BENCHMARK(sweep<Hinge, false>)->Name("pgsSweep<Hinge>")->Apply(sizes);
BENCHMARK(sweep<BallJoint, true>)->Name("jacobiSweep<BallJoint>")->Apply(sizes);
BENCHMARK(sweep<Hinge, true>)->Name("jacobiSweep<Hinge>")->Apply(sizes);
BENCHMARK(step<BallJoint, spook::DirectSolver>)->Name("step<BallJoint,direct>")->Apply(sizes);
BENCHMARK(step<BallJoint, spook::IterativeSolver>)->Name("step<BallJoint,iterative16>")->Apply(sizes);
BENCHMARK(step<BallJoint, spook::HybridSolver>)->Name("step<BallJoint,hybrid>")->Apply(sizes);
BENCHMARK(step<Hinge, spook::DirectSolver>)->Name("step<Hinge,direct>")->Apply(sizes);
BENCHMARK(step<Hinge, spook::IterativeSolver>)->Name("step<Hinge,iterative16>")->Apply(sizes);
BENCHMARK(step<Hinge, spook::HybridSolver>)->Name("step<Hinge,hybrid>")->Apply(sizes);

/// The console report, then a power-law fit t = c·nᵖ (least squares in
/// log–log over every size) per family, with the slope of each decade.
class ExponentReporter : public benchmark::ConsoleReporter {
 public:
  ExponentReporter() : ConsoleReporter(OO_Tabular) {}

  void ReportRuns(const std::vector<Run>& reports) override {
    ConsoleReporter::ReportRuns(reports);
    for (const Run& run : reports) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred || run.complexity_n <= 0) continue;
      auto& family = families_[run.run_name.function_name];
      if (family.empty()) order_.push_back(run.run_name.function_name);
      family[run.complexity_n] = run.GetAdjustedCPUTime();  // last repetition wins
    }
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::FILE* out = stdout;
    std::fprintf(out, "\nPower-law fit t = c * n^p over n = 10..1000 links (CPU time):\n\n");
    std::fprintf(out, "| %-28s | %10s | %10s | %10s | %8s | %8s | %6s |\n", "family", "t(10) us", "t(100) us",
                 "t(1000) us", "p 10-100", "p 100-1k", "p fit");
    std::fprintf(out, "|%s|%s|%s|%s|%s|%s|%s|\n", std::string(30, '-').c_str(), std::string(12, '-').c_str(),
                 std::string(12, '-').c_str(), std::string(12, '-').c_str(), std::string(10, '-').c_str(),
                 std::string(10, '-').c_str(), std::string(8, '-').c_str());
    for (const std::string& name : order_) {
      const auto& points = families_[name];
      double sx = 0, sy = 0, sxx = 0, sxy = 0;
      for (const auto& [n, t] : points) {
        const double x = std::log(double(n)), y = std::log(t);
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
      }
      const double m = double(points.size());
      const double p = points.size() > 1 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
      const auto at = [&](std::int64_t n) { return points.count(n) ? points.at(n) : NAN; };
      const auto slope = [&](std::int64_t a, std::int64_t b) {
        return std::log(at(b) / at(a)) / std::log(double(b) / double(a));
      };
      std::fprintf(out, "| %-28s | %10.2f | %10.2f | %10.2f | %8.2f | %8.2f | %6.2f |\n", name.c_str(), at(10), at(100),
                   at(1000), slope(10, 100), slope(100, 1000), p);
    }
    std::fflush(out);
  }

 private:
  std::map<std::string, std::map<std::int64_t, double>> families_;
  std::vector<std::string> order_;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  ExponentReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
