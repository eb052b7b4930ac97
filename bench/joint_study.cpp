// Cost against accuracy of the solver policies on ill-conditioned joints
// (issue 23), beside Bullet's sequential-impulse solver from the same run:
// each scene × time step × solver is simulated for 10 s from rest, and the
// program prints an aligned table and writes a CSV (argv[1], default
// joint_study.csv); argv[2], when given, runs only the scenes whose name
// contains it.
//
// Scenes (gravity (0, 0, −9.80665) m/s², released horizontally from rest):
//   pendulum I   a 1 kg bob 1 m from a world hinge about y, with inertia I
//                on each axis: 1e-6 (a point), 1e-4, 1e-2 kg m² (a 0.16 m
//                sphere); h = 1/60 and 1/240
//   chain        10 links of 5 kg, 0.5 × 0.1 × 0.1 m boxes' inertia, hinged
//                end to end about y, the first to the world; h = 1/60 and 0.1
// Nothing collides: the bodies carry mass and inertia only.
//
// Solvers: spook's direct, hybrid and iterative policies with their
// defaults (iterative: 16 Gauss–Seidel sweeps, cold started), iterative with
// 10 sweeps (Bullet's default count); Bullet SI with 10 (its default) and 16
// sweeps, when Bullet is installed.
//
// Measures:
//   us/step   wall-clock time of one step (µs), best of three runs;
//             us/sweep: the cost of one more sweep of an iterative solver
//             (the slope between its 10 and 16 sweeps' us/step)
//   gain      largest energy above the start over the run, in units of the
//             releasable potential energy (m g L: pendulum 1 kg · g · 1 m,
//             chain 50 kg · g · 0.5 m, one link's length)
//   dE        energy change at the end, same units (negative: lost)
//   gap       worst hinge pin separation over every step and hinge (m)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "joint_study_engine.hpp"

namespace {

using joint_study::Description;
using joint_study::Engine;
using joint_study::Point;

constexpr double kG = 9.80665;      // m/s²
constexpr double kDuration = 10.0;  // s of simulated time per run

spook::Vec3 toSpook(const Point& p) { return {p[0], p[1], p[2]}; }

class SpookEngine final : public Engine {
 public:
  SpookEngine(const Description& description, spook::SolverRef solver) {
    sim_->setUniformGravity(spook::Vec3(0, 0, description.gravity));
    sim_->setTimeStep(description.timeStep);
    sim_->setSolver(std::move(solver));
    for (const joint_study::BodySpec& spec : description.bodies) {
      spook::RigidBodyRef body = new spook::RigidBody();
      body->getMassProperties()->setMass(spec.mass);
      body->getMassProperties()->setInertiaTensor(spook::SPDMat3(toSpook(spec.inertia)));
      body->setPosition(toSpook(spec.position));
      sim_->add(body);
      bodies_.push_back(body);
    }
    for (const joint_study::HingeSpec& spec : description.hinges)
      sim_->add(spook::Constraint::createFromWorld<spook::Hinge>(
          toSpook(spec.pivot), toSpook(spec.axis), bodies_[std::size_t(spec.body1)].get(),
          spec.body2 < 0 ? nullptr : bodies_[std::size_t(spec.body2)].get()));
  }

  void step() override { sim_->stepForward(); }

  Point worldPoint(int body, const Point& local) const override {
    const spook::RigidBody& b = *bodies_[std::size_t(body)];
    const spook::Vec3 p = b.getCmPosition() + b.getRotation() * toSpook(local);
    return {p.x(), p.y(), p.z()};
  }

  double kineticEnergy() const override {
    double energy = 0.0;
    for (const auto& body : bodies_) energy += body->getKineticEnergy();
    return energy;
  }

 private:
  spook::SimulationRef sim_ = new spook::Simulation();
  std::vector<spook::RigidBodyRef> bodies_;
};

// --- Scenes -------------------------------------------------------------------

struct Scene {
  std::string name;
  Description description;
  double energyScale = 1.0;  ///< J: m g L
  std::vector<double> timeSteps;
};

Scene pendulum(double inertia) {
  Scene scene;
  char name[32];
  std::snprintf(name, sizeof name, "pendulum %.0e", inertia);
  scene.name = name;
  scene.description.bodies.push_back({1.0, {inertia, inertia, inertia}, {1, 0, 0}});
  scene.description.hinges.push_back({0, -1, {0, 0, 0}, {0, 1, 0}});
  scene.energyScale = 1.0 * kG * 1.0;
  scene.timeSteps = {1.0 / 60, 1.0 / 240};
  return scene;
}

Scene chain() {
  constexpr int kLinks = 10;
  constexpr double kLength = 0.5, kMass = 5.0, kThickness = 0.1;
  Scene scene;
  scene.name = "chain";
  const double across = kMass / 12.0 * (kLength * kLength + kThickness * kThickness);
  const double along = kMass / 12.0 * 2.0 * kThickness * kThickness;
  for (int k = 0; k < kLinks; ++k) {
    scene.description.bodies.push_back({kMass, {along, across, across}, {kLength * (k + 0.5), 0, 0}});
    scene.description.hinges.push_back({k, k - 1, {kLength * k, 0, 0}, {0, 1, 0}});
  }
  scene.energyScale = kLinks * kMass * kG * kLength;
  scene.timeSteps = {1.0 / 60, 0.1};
  return scene;
}

// --- Solvers ------------------------------------------------------------------

struct Solver {
  std::string name;
  std::string family;  ///< iterative solvers: runs differing only in sweeps
  int sweeps = 0;      ///< iterative solvers: sweeps per step (0: direct)
  std::function<std::unique_ptr<Engine>(const Description&)> make;
};

std::vector<Solver> solvers() {
  const auto spookSolver = [](std::function<spook::SolverRef()> make) {
    return [make](const Description& d) -> std::unique_ptr<Engine> { return std::make_unique<SpookEngine>(d, make()); };
  };
  std::vector<Solver> list;
  list.push_back({"direct", "", 0, spookSolver([] { return spook::SolverRef(new spook::DirectSolver()); })});
  list.push_back({"hybrid", "", 0, spookSolver([] { return spook::SolverRef(new spook::HybridSolver()); })});
  for (int sweeps : {10, 16})
    list.push_back({"iterative" + std::to_string(sweeps), "iterative", sweeps, spookSolver([sweeps] {
                      spook::SolverRef s = new spook::IterativeSolver();
                      s->setNumIterations(sweeps);
                      return s;
                    })});
  list.push_back({"iterative16w", "", 16, spookSolver([] {
                    spook::SolverRef s = new spook::IterativeSolver();
                    s->setEnableWarmStarting(true);
                    return s;
                  })});
#ifdef SPOOK_STUDY_BULLET
  for (int sweeps : {10, 16})
    list.push_back({"bullet SI " + std::to_string(sweeps), "bullet SI", sweeps,
                    [sweeps](const Description& d) { return joint_study::makeBulletEngine(d, sweeps); }});
#endif
  return list;
}

// --- Measuring ----------------------------------------------------------------

double energyOf(const Engine& engine, const Description& d) {
  double e = engine.kineticEnergy();
  for (std::size_t i = 0; i < d.bodies.size(); ++i)
    e -= d.bodies[i].mass * d.gravity * engine.worldPoint(int(i), {0, 0, 0})[2];
  return e;
}

double worstGap(const Engine& engine, const Description& d) {
  double worst = 0.0;
  for (const joint_study::HingeSpec& hinge : d.hinges) {
    const auto local = [&](int body) {
      const Point& c = d.bodies[std::size_t(body)].position;
      return Point{hinge.pivot[0] - c[0], hinge.pivot[1] - c[1], hinge.pivot[2] - c[2]};
    };
    const Point a = engine.worldPoint(hinge.body1, local(hinge.body1));
    const Point b = hinge.body2 < 0 ? hinge.pivot : engine.worldPoint(hinge.body2, local(hinge.body2));
    const double gap = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    worst = std::isfinite(gap) ? std::max(worst, gap) : INFINITY;
  }
  return worst;
}

struct Result {
  std::string scene, solver, family;
  double h = 0, costUs = INFINITY, sweepUs = NAN, gain = -INFINITY, energy = 0, gap = 0;
  int sweeps = 0;
  bool finite = true;
};

Result run(const Scene& scene, const Solver& solver, double h) {
  Description d = scene.description;
  d.timeStep = h;
  Result r{scene.name, solver.name, solver.family, h};
  r.sweeps = solver.sweeps;
  const long steps = std::lround(kDuration / h);
  {
    std::unique_ptr<Engine> engine = solver.make(d);
    const double e0 = energyOf(*engine, d);
    for (long k = 0; k < steps && r.finite; ++k) {
      engine->step();
      const double e = (energyOf(*engine, d) - e0) / scene.energyScale;
      r.gap = std::max(r.gap, worstGap(*engine, d));
      r.finite = std::isfinite(e) && std::isfinite(r.gap);
      r.gain = std::max(r.gain, e);
      r.energy = e;
    }
  }
  for (int repeat = 0; repeat < 3 && r.finite; ++repeat) {
    std::unique_ptr<Engine> engine = solver.make(d);
    const auto start = std::chrono::steady_clock::now();
    for (long k = 0; k < steps; ++k) engine->step();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.costUs = std::min(r.costUs, 1e6 * wall / double(steps));
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csvPath = argc > 1 ? argv[1] : "joint_study.csv";
  const std::string only = argc > 2 ? argv[2] : "";
  std::vector<Scene> scenes = {pendulum(1e-6), pendulum(1e-4), pendulum(1e-2), chain()};
  std::erase_if(scenes, [&](const Scene& s) { return s.name.find(only) == std::string::npos; });

  std::vector<Result> results;
  for (const Scene& scene : scenes)
    for (double h : scene.timeSteps)
      for (const Solver& solver : solvers()) results.push_back(run(scene, solver, h));
  // The cost of one more sweep: the slope between two sweep counts of one
  // solver family on one scene and step.
  for (Result& a : results)
    for (const Result& b : results)
      if (!a.family.empty() && a.family == b.family && a.scene == b.scene && a.h == b.h && a.sweeps != b.sweeps)
        a.sweepUs = (a.costUs - b.costUs) / double(a.sweeps - b.sweeps);

  std::printf("%-14s  %-12s  %5s  %8s  %8s  %10s  %10s  %10s  %s\n", "scene", "solver", "h", "us/step", "us/sweep",
              "gain", "dE", "gap (m)", "finite");
  std::string previous;
  for (const Result& r : results) {
    if (r.scene != previous && !previous.empty()) std::printf("\n");
    previous = r.scene;
    char perSweep[16] = "-";
    if (std::isfinite(r.sweepUs)) std::snprintf(perSweep, sizeof perSweep, "%.2f", r.sweepUs);
    std::printf("%-14s  %-12s  1/%-3.0f  %8.2f  %8s  %+10.2e  %+10.2e  %10.2e  %s\n", r.scene.c_str(), r.solver.c_str(),
                1.0 / r.h, r.costUs, perSweep, r.gain, r.energy, r.gap, r.finite ? "yes" : "NO");
  }
  std::printf(
      "\ngain: largest energy above the start over the run; dE: energy change at the end; both in m g L.\n"
      "gap: worst hinge pin separation. us/step: wall-clock, best of three runs of %g s; us/sweep: the cost\n"
      "of one more sweep of an iterative solver (the slope between its 10 and 16 sweeps' us/step).\n",
      kDuration);

  std::FILE* csv = std::fopen(csvPath.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csvPath.c_str());
    return 1;
  }
  std::fprintf(
      csv, "scene,solver,h,sweeps,cost_us_per_step,cost_us_per_sweep,energy_gain,energy_error,worst_gap_m,finite\n");
  for (const Result& r : results)
    std::fprintf(csv, "%s,%s,%.17g,%d,%.6g,%.6g,%.6e,%.6e,%.6e,%d\n", r.scene.c_str(), r.solver.c_str(), r.h, r.sweeps,
                 r.costUs, r.sweepUs, r.gain, r.energy, r.gap, r.finite ? 1 : 0);
  std::fclose(csv);
  std::printf("CSV written to %s\n", csvPath.c_str());
  return 0;
}
