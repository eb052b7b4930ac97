// Speed against accuracy of the solver policies (DESIGN.md, promise 1): each
// policy × time step × scene is simulated, and the program reports the
// wall-clock cost per step, the worst joint gap over the run, the relative
// energy error at the end and whether anything went non-finite. It prints an
// aligned table and writes a CSV (argv[1], default speed_accuracy.csv) that
// bench/plot_speed_accuracy.py turns into a cost-vs-gap plot; argv[2], when
// given, runs only the scenes whose name contains it.
//
// Scenes (gravity (0, 0, −9.80665) m/s², every run 10 s from rest):
//   chain 1:R   10 links of 1 kg and 1 m, end mass R kg (R = 1, 1e2, 1e3,
//               1e4, 1e6), ball joints of compliance 1e-12, one end on a world
//               pivot, released horizontally (the mass-ratio chain of the
//               solver tests)
//   crane       a 500 kg boom on a world hinge held at 30° by its Lock1D, a
//               200 kg telescope on a prismatic held by its Lock1D, a 2 t
//               load 5 m below the tip on a hinge, released 30° sideways so
//               that it twists the boom; every row has compliance 1e-10
//   pendulum    1 kg, 1 m from a world hinge, released at 90°; default
//               compliance 1e-8 and damping 2/60 s
//
// Policies: direct (its defaults: post-stabilization, one projection, and
// geometric stiffness at its default threshold), also with geometric
// stiffness on every body (direct+gs0, threshold 0); direct without
// post-stabilization (direct-nops), also without geometric stiffness
// (direct-nops-nogs); iterative
// (Gauss–Seidel) with 4, 16, 64 and 256 sweeps, cold started (the default);
// hybrid with the default solve types (joints DIRECT_AND_ITERATIVE: with no
// contacts it solves exactly what direct solves); hybrid-mixed, where the
// scene marks its bulk joints ITERATIVE and keeps the joints at the world and
// at the heavy body DIRECT_AND_ITERATIVE (16 sweeps for the iterative part).
//
// Measures:
//   cost      wall-clock time of stepForward per step (µs), nothing else; the
//             best of three runs (and, beside it, the CPU time, best of two)
//   gap       worst translational joint error over every step and joint (m):
//             |p1 − p2| of the attachment frames, for a prismatic the part
//             across its axis
//   energy    (E(T) − E(0)) / E_scale, E = Σ ½vᵀMv + ½ωᵀIω + m g z, E_scale
//             the largest potential energy the scene can release (all three
//             scenes are conservative: no motors, no friction)
//   verdict   ok: gap < 1 mm; soft: gap < 0.1 m; broken: larger, or non-finite
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <spook/spook.hpp>

namespace {

using Vec3 = spook::Vec3;
using Quat = spook::Quat;
constexpr double kG = 9.80665;      // m/s²
constexpr double kDuration = 10.0;  // s of simulated time per run
constexpr double kOkGap = 1e-3;     // m
constexpr double kBrokenGap = 0.1;  // m

// --- Scenes ------------------------------------------------------------------

/// A joint whose gap is measured, and how.
struct Measured {
  spook::ConstraintRef joint;
  bool alongAxisIsFree = false;  ///< prismatic: only the error across frame 2's z counts
};

struct Scene {
  spook::SimulationRef sim = new spook::Simulation();
  std::vector<spook::RigidBodyRef> bodies;
  std::vector<Measured> joints;
  double energyScale = 1.0;  ///< J
};

spook::RigidBodyRef addBody(Scene& scene, const char* name, double mass, const Vec3& inertia, const Vec3& position,
                            const Quat& rotation = Quat::Identity()) {
  spook::RigidBodyRef body = new spook::RigidBody(name);
  body->getMassProperties()->setMass(mass);
  body->getMassProperties()->setInertiaTensor(inertia);
  body->setPosition(position);
  body->setRotation(rotation);
  scene.sim->add(body);
  scene.bodies.push_back(body);
  return body;
}

/// A frame at `point` of its parent with z along `axis`.
spook::FrameRef frameAt(const Vec3& point, const Vec3& axis = Vec3::UnitZ()) {
  spook::FrameRef f = new spook::Frame();
  f->setLocalTranslate(point);
  f->setLocalRotate(spook::rotate<double>(Vec3::UnitZ(), axis));
  return f;
}

void addJoint(Scene& scene, spook::ConstraintRef joint, bool mixedIterative, bool prismatic = false) {
  if (mixedIterative) joint->setSolveType(spook::Constraint::ITERATIVE);
  scene.sim->add(joint);
  scene.joints.push_back({joint, prismatic});
}

/// The mass-ratio chain; `mixed`: the joints between light links ITERATIVE.
Scene massRatioChain(double endMass, bool mixed) {
  Scene scene;
  constexpr int kLinks = 10;
  scene.energyScale = 0.0;
  spook::RigidBody* previous = nullptr;
  for (int i = 0; i <= kLinks; ++i) {
    const bool end = i == kLinks;
    const double mass = end ? endMass : 1.0;
    auto body = addBody(scene, end ? "end" : "link", mass, Vec3::Constant(0.1 * mass), Vec3(i + 0.5, 0, 0));
    scene.energyScale += mass * kG * (i + 0.5);  // hanging straight down
    spook::FrameRef above = previous ? frameAt(Vec3(0.5, 0, 0)) : frameAt(Vec3::Zero());
    spook::ref_ptr<spook::BallJoint> joint =
        new spook::BallJoint(body.get(), frameAt(Vec3(-0.5, 0, 0)).get(), previous, above.get());
    joint->setCompliance(1e-12);
    addJoint(scene, joint, mixed && i > 0 && !end);
    previous = body.get();
  }
  return scene;
}

/// The crane; `mixed`: the load's hinge ITERATIVE.
Scene crane(bool mixed) {
  Scene scene;
  constexpr double kCompliance = 1e-10;
  const double elevation = std::numbers::pi / 6.0;
  const Vec3 along(std::cos(elevation), 0, std::sin(elevation));  // the boom's axis
  const Quat boomRotation = spook::rotate<double>(Vec3::UnitX(), along);
  // Slender beams along their local x: I = m(L²/12) across, small along.
  auto boom = addBody(scene, "boom", 500.0, Vec3(20, 500.0 * 64 / 12, 500.0 * 64 / 12), 4.0 * along, boomRotation);
  auto telescope =
      addBody(scene, "telescope", 200.0, Vec3(5, 200.0 * 36 / 12, 200.0 * 36 / 12), 9.0 * along, boomRotation);
  const Vec3 tip = 12.0 * along;
  const double swing = std::numbers::pi / 6.0, cable = 5.0;
  auto load =
      addBody(scene, "load", 2000.0, Vec3::Constant(400.0), tip + cable * Vec3(0, std::sin(swing), -std::cos(swing)));
  scene.energyScale = 2000.0 * kG * cable * (1.0 - std::cos(swing));

  auto luffing = spook::Hinge::createFromWorld<spook::Hinge>(Vec3::Zero(), Vec3::UnitY(), boom.get());
  auto telescopic =
      spook::Prismatic::createFromWorld<spook::Prismatic>(9.0 * along, along, telescope.get(), boom.get());
  auto hook = spook::Hinge::createFromWorld<spook::Hinge>(tip, Vec3::UnitX(), load.get(), telescope.get());
  for (spook::Hinge* joint : {luffing.get(), hook.get()}) joint->setCompliance(kCompliance);
  telescopic->setCompliance(kCompliance);
  for (auto* lock : {luffing->getLock1D(), telescopic->getLock1D()}) {
    lock->setEnable(true);
    lock->setPosition(0.0);  // where the joint was created
    lock->setCompliance(kCompliance);
  }
  addJoint(scene, luffing, false);
  addJoint(scene, telescopic, false, true);
  addJoint(scene, hook, mixed);
  return scene;
}

/// The 90° hinge pendulum; `mixed`: its only joint ITERATIVE.
Scene pendulum(bool mixed) {
  Scene scene;
  auto bob = addBody(scene, "bob", 1.0, Vec3::Constant(0.004), Vec3(1, 0, 0));
  scene.energyScale = 1.0 * kG * 1.0;
  addJoint(scene, spook::Hinge::createFromWorld<spook::Hinge>(Vec3::Zero(), Vec3::UnitY(), bob.get()), mixed);
  return scene;
}

// --- Policies ----------------------------------------------------------------

struct Policy {
  std::string name;
  std::function<spook::SolverRef()> make;
  bool mixed = false;  ///< the scene marks its bulk joints ITERATIVE
};

std::vector<Policy> policies() {
  std::vector<Policy> list;
  list.push_back({"direct", [] { return spook::SolverRef(new spook::DirectSolver()); }});
  list.push_back({"direct-nops", [] {
                    spook::SolverRef s = new spook::DirectSolver();
                    s->setEnablePostStabilization(false);
                    return s;
                  }});
  list.push_back({"direct-nops-nogs", [] {
                    spook::SolverRef s = new spook::DirectSolver();
                    s->setEnablePostStabilization(false);
                    s->setEnableGeometricStiffness(false);
                    return s;
                  }});
  list.push_back({"direct+gs0", [] {
                    spook::SolverRef s = new spook::DirectSolver();
                    s->setGeometricStiffnessThreshold(0.0);
                    return s;
                  }});
  for (int n : {4, 16, 64, 256})
    list.push_back({"iterative" + std::to_string(n), [n] {
                      spook::SolverRef s = new spook::IterativeSolver();
                      s->setNumIterations(n);
                      return s;
                    }});
  list.push_back({"hybrid", [] { return spook::SolverRef(new spook::HybridSolver()); }});
  list.push_back({"hybrid-mixed", [] { return spook::SolverRef(new spook::HybridSolver()); }, true});
  return list;
}

// --- Measuring ---------------------------------------------------------------

double gapOf(const Measured& m) {
  const auto* f1 = m.joint->getAttachmentFrame(0);
  const auto* f2 = m.joint->getAttachmentFrame(1);
  Vec3 d = f1->getTranslate() - f2->getTranslate();
  if (m.alongAxisIsFree) {
    const Vec3 axis = f2->getRotate() * Vec3::UnitZ();
    d -= axis * axis.dot(d);
  }
  return d.norm();
}

double energyOf(const Scene& scene) {
  double e = 0.0;
  for (const auto& b : scene.bodies)
    e += b->getKineticEnergy() + b->getMassProperties()->getMass() * kG * b->getCmPosition().z();
  return e;
}

struct Result {
  std::string scene, policy;
  double h = 0, seconds = 0, costUs = 0, cpuUs = 0, gap = 0, energy = 0;
  double brokenAt = -1.0;  ///< s: when the gap first reached kBrokenGap (−1: never)
  long steps = 0;
  bool finite = true;
  std::string verdict;
};

/// Wall-clock and CPU cost per step (µs), each the best of `repeats` runs of
/// the scene alone, so that other processes on a shared machine inflate them less.
struct Cost {
  double wallUs = INFINITY, cpuUs = INFINITY;
};
Cost costOf(const std::function<Scene(bool)>& build, const Policy& policy, double h, int repeats) {
  Cost best;
  for (int i = 0; i < repeats; ++i) {
    Scene scene = build(policy.mixed);
    scene.sim->setTimeStep(h);
    scene.sim->setSolver(policy.make());
    const long steps = std::lround(kDuration / h);
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpuStart = std::clock();
    for (long k = 0; k < steps; ++k) scene.sim->stepForward();
    const double cpu = double(std::clock() - cpuStart) / CLOCKS_PER_SEC;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    best.wallUs = std::min(best.wallUs, 1e6 * wall / double(steps));
    best.cpuUs = std::min(best.cpuUs, 1e6 * cpu / double(steps));
  }
  return best;
}

Result run(const std::string& sceneName, const std::function<Scene(bool)>& build, const Policy& policy, double h) {
  Scene scene = build(policy.mixed);
  scene.sim->setTimeStep(h);
  scene.sim->setSolver(policy.make());
  Result r;
  r.scene = sceneName;
  r.policy = policy.name;
  r.h = h;
  const double e0 = energyOf(scene);
  const long steps = std::lround(kDuration / h);
  double elapsed = 0.0;
  for (long k = 0; k < steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    scene.sim->stepForward();
    elapsed += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const auto& statistics = scene.sim->getStatistics();
    r.finite = r.finite && statistics.solver.nonFiniteIslands == 0 && statistics.frozenBodies.empty();
    for (const Measured& m : scene.joints) {
      const double gap = gapOf(m);
      r.finite = r.finite && std::isfinite(gap);
      if (std::isfinite(gap)) r.gap = std::max(r.gap, gap);
    }
    if (r.brokenAt < 0 && (!r.finite || r.gap >= kBrokenGap)) r.brokenAt = double(k + 1) * h;
    r.steps = k + 1;
  }
  r.seconds = double(r.steps) * h;
  // The measured run, plus two more timed alone (no gap measuring in between).
  const Cost cost = costOf(build, policy, h, 2);
  r.costUs = std::min(1e6 * elapsed / double(r.steps), cost.wallUs);
  r.cpuUs = cost.cpuUs;
  r.energy = (energyOf(scene) - e0) / scene.energyScale;
  r.finite = r.finite && std::isfinite(r.energy);
  r.verdict = !r.finite || r.gap >= kBrokenGap ? "broken" : r.gap >= kOkGap ? "soft" : "ok";
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csvPath = argc > 1 ? argv[1] : "speed_accuracy.csv";
  const std::string only = argc > 2 ? argv[2] : "";  // run only the scenes whose name contains this
  struct NamedScene {
    std::string name;
    std::function<Scene(bool)> build;
  };
  std::vector<NamedScene> scenes;
  for (double ratio : {1.0, 1e2, 1e3, 1e4, 1e6}) {
    char name[32];
    if (ratio == 1.0)
      std::snprintf(name, sizeof name, "chain 1:1");
    else
      std::snprintf(name, sizeof name, "chain 1:1e%.0f", std::log10(ratio));
    scenes.push_back({name, [ratio](bool mixed) { return massRatioChain(ratio, mixed); }});
  }
  scenes.push_back({"crane", crane});
  scenes.push_back({"pendulum", pendulum});
  const std::vector<double> steps = {1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240};

  std::vector<Result> results;
  const auto start = std::chrono::steady_clock::now();
  std::erase_if(scenes, [&](const NamedScene& scene) { return scene.name.find(only) == std::string::npos; });
  for (const NamedScene& scene : scenes)
    for (const Policy& policy : policies())
      for (double h : steps) results.push_back(run(scene.name, scene.build, policy, h));
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("%-11s  %-13s  %5s  %6s  %9s  %9s  %10s  %10s  %6s  %-7s  %s\n", "scene", "policy", "h", "T (s)",
              "us/step", "cpu us", "gap (m)", "dE/E", "finite", "verdict", "broken at (s)");
  std::string previous;
  for (const Result& r : results) {
    if (r.scene != previous && !previous.empty()) std::printf("\n");
    previous = r.scene;
    char brokenAt[16] = "-";
    if (r.brokenAt >= 0) std::snprintf(brokenAt, sizeof brokenAt, "%.2f", r.brokenAt);
    std::printf("%-11s  %-13s  1/%-3.0f  %6.1f  %9.1f  %9.1f  %10.2e  %+10.2e  %6s  %-7s  %s\n", r.scene.c_str(),
                r.policy.c_str(), 1.0 / r.h, r.seconds, r.costUs, r.cpuUs, r.gap, r.energy, r.finite ? "yes" : "NO",
                r.verdict.c_str(), brokenAt);
  }
  std::printf(
      "\ngap: worst translational joint error over the run; dE/E: energy change at the end over the\n"
      "largest releasable potential energy; verdict: ok < %g m <= soft < %g m <= broken (or non-finite);\n"
      "broken at: simulated time when the gap first reached the broken threshold. us/step: wall-clock,\n"
      "best of three runs; cpu us: process CPU time per step, best of two. Every run is the full %g s\n"
      "(none shortened); study wall-clock %.1f s.\n",
      kOkGap, kBrokenGap, kDuration, total);

  std::FILE* csv = std::fopen(csvPath.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csvPath.c_str());
    return 1;
  }
  std::fprintf(csv,
               "scene,policy,h,steps,seconds,cost_us_per_step,cpu_us_per_step,worst_gap_m,energy_error,finite,verdict,"
               "broken_at_s\n");
  for (const Result& r : results)
    std::fprintf(csv, "%s,%s,%.17g,%ld,%.6g,%.6g,%.6g,%.6e,%.6e,%d,%s,%.6g\n", r.scene.c_str(), r.policy.c_str(), r.h,
                 r.steps, r.seconds, r.costUs, r.cpuUs, r.gap, r.energy, r.finite ? 1 : 0, r.verdict.c_str(),
                 r.brokenAt);
  std::fclose(csv);
  std::printf("CSV written to %s (plot: python3 bench/plot_speed_accuracy.py %s)\n", csvPath.c_str(), csvPath.c_str());
  return 0;
}
