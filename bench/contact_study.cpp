// Contact scenes against the solver policies (DESIGN.md, promise 1, now with
// contacts): each scene × policy is simulated and the program reports the
// wall-clock cost per step, the contact points, how far the resting bodies
// drifted, the deepest penetration and the kinetic energy left at the end.
// Every contact point is one normal row and two friction rows. It prints an
// aligned table and writes a CSV (argv[1], default contact_study.csv) that
// bench/plot_contact_study.py turns into a cost-vs-drift plot; argv[2], when
// given, runs only the scenes whose name contains it.
//
// Scenes (gravity (0, 0, −9.80665) m/s², density 1000 kg/m³, one material
// for every geometry whose contact material has friction coefficient 0.5 and
// the default stiffness (Young's modulus 2e8 Pa for the pair) and damping):
//   spheres     1000 spheres of radius 0.1 m (4.19 kg each) dropped into a
//               2 m × 2 m box open at the top (ground plane, four static wall
//               boxes 4 m tall), started on a jittered 9 × 9 grid of 13
//               layers from 0.1 m to 3.1 m above the floor; 3 s at h = 1/60
//   pyramid     210 unit cubes in a 2D pyramid of base 20 (level L holds
//               20 − L cubes 1.01 m apart, 1 cm gaps, each level offset by
//               half a pitch and resting on the one below); 5 s at h = 1/60
//   stack 1/60  10 unit cubes stacked on the ground; 10 s at h = 1/60
//   stack 1/30  the same at h = 1/30
//
// Policies: direct (its defaults, post-stabilization on); hybrid with the
// contact material's friction model (iterative projected cone) solved SPLIT
// (the default: normals direct, friction iterative), DIRECT_AND_ITERATIVE
// and DIRECT; iterative (projected Gauss–Seidel, cold started) with 16 and 64
// sweeps. The direct and iterative policies ignore the solve type ("-").
//
// Measures:
//   ms/step     wall-clock time of stepForward, mean over the steps of the
//               last simulated second (over every step taken when a run was
//               stopped as too slow); the CSV also has the slowest step
//   contacts    enabled contact points after the last step
//   drift       stack: the worst displacement of the top cube from its start
//               over the run (m); pyramid: the worst displacement of any cube
//               over the run (m); spheres: not measured ("-"). The contacts'
//               compliance alone settles the stack's top by 55 m g/(4E) =
//               0.67 mm, the pyramid's apex by about 0.8 mm
//   max pen     the deepest contact penetration (m): over the last second for
//               spheres (the impacts before are transients), over the run for
//               the stack and the pyramid
//   KE          kinetic energy Σ ½vᵀMv + ½ωᵀIω at the end (J)
//   verdict     non-finite: a solve dropped an island, a body froze or a pose
//               went non-finite; too slow: one step took more than 5 s, the
//               run was stopped there (its measures are those of the steps
//               taken, T the simulated time reached); stack and pyramid: ok
//               when drift < 1 mm, soft < 0.1 m, fell beyond; spheres: fell
//               when a sphere left the box, soft when penetration > 1 cm,
//               unsettled when KE > ½ M (1 cm/s)² = 0.21 J (M = 4189 kg, the
//               total mass), ok otherwise. A stack or pyramid verdict does not
//               look at the penetration, a spheres verdict not at drift
//
// The program runs one policy at a time on one thread; pivoting direct
// solves of hundreds of contacts can take seconds per step, hence the guard.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <spook/spook.hpp>

namespace {

using Vec3 = spook::Vec3<>;
constexpr double kFriction = 0.5;
constexpr double kOkDrift = 1e-3;          // m
constexpr double kFellDrift = 0.1;         // m
constexpr double kSoftPenetration = 0.01;  // m, spheres
constexpr double kSettledSpeed = 0.01;     // m/s, spheres: KE < ½ M v² counts as settled
constexpr double kTooSlowStep = 5.0;       // s of wall-clock for one step
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// --- Scenes ------------------------------------------------------------------

enum class Kind { SPHERES, PYRAMID, STACK };

struct Scene {
  spook::SimulationRef sim = new spook::Simulation();
  spook::MaterialRef material = new spook::Material("wood");
  std::vector<spook::RigidBodyRef> bodies;
  std::vector<Vec3> starts;          ///< the bodies' initial positions (m, world)
  std::vector<std::size_t> tracked;  ///< the bodies whose displacement is the drift
};

/// The shared material's contact material with itself: μ = 0.5 and a
/// projected-cone friction model solved as `solveType` (hybrid only).
void setFriction(Scene& scene, spook::SolveType solveType) {
  auto* cm = scene.sim->getMaterialManager()->getOrCreateContactMaterial(scene.material.get(), scene.material.get());
  spook::FrictionModelRef model = new spook::IterativeProjectedConeFriction();
  model->setSolveType(solveType);
  cm->setFrictionModel(model);
  cm->setFrictionCoefficient(kFriction);
}

void addStatic(Scene& scene, spook::ShapeT<double>* shape, const Vec3& position, const char* name) {
  spook::GeometryRef geometry = new spook::Geometry(shape, spook::Transform<double>::Identity(), name);
  geometry->setPosition(position);
  geometry->setMaterial(scene.material);
  scene.sim->add(geometry);
}

void addBody(Scene& scene, spook::ShapeT<double>* shape, const Vec3& position, const std::string& name) {
  spook::GeometryRef geometry = new spook::Geometry(shape, spook::Transform<double>::Identity(), name);
  geometry->setMaterial(scene.material);
  spook::RigidBodyRef body = new spook::RigidBody(name);
  body->add(geometry);
  body->setPosition(position);
  scene.sim->add(body);
  scene.bodies.push_back(body);
  scene.starts.push_back(position);
}

/// A reproducible jitter in [−1, 1] for slot `i`, component `axis` (an
/// integer hash, so that every platform builds the same scene).
double jitter(std::uint32_t i, std::uint32_t axis) {
  std::uint32_t x = i * 73856093u ^ (axis + 1u) * 19349663u;
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return double(x) / double(UINT32_MAX) * 2.0 - 1.0;
}

void spheres(Scene& scene) {
  constexpr int kCount = 1000, kGrid = 9;
  constexpr double kRadius = 0.1, kPitch = 0.22, kLayerPitch = 0.25;  // m
  constexpr double kWallHalf = 2.0;                                   // m: walls 4 m tall
  addStatic(scene, new spook::Plane(Vec3::UnitZ()), Vec3::Zero(), "ground");
  for (int side : {-1, 1}) {
    addStatic(scene, new spook::Box(Vec3(0.1, 1.2, kWallHalf)), Vec3(1.1 * side, 0, kWallHalf), "wall x");
    addStatic(scene, new spook::Box(Vec3(1.2, 0.1, kWallHalf)), Vec3(0, 1.1 * side, kWallHalf), "wall y");
  }
  // Neighbours 2 cm apart on the grid, so a jitter of ±8 mm keeps them apart;
  // the outermost stay 1.2 cm inside the walls.
  for (int i = 0; i < kCount; ++i) {
    const int layer = i / (kGrid * kGrid), column = i % kGrid, row = (i / kGrid) % kGrid;
    const std::uint32_t slot = std::uint32_t(i);
    const Vec3 p((column - (kGrid - 1) / 2.0) * kPitch + 0.008 * jitter(slot, 0),
                 (row - (kGrid - 1) / 2.0) * kPitch + 0.008 * jitter(slot, 1),
                 2.0 * kRadius + layer * kLayerPitch + 0.02 * jitter(slot, 2));
    addBody(scene, new spook::Sphere(kRadius), p, "sphere " + std::to_string(i));
  }
}

void pyramid(Scene& scene) {
  constexpr int kBase = 20;
  constexpr double kPitch = 1.01;  // m: unit cubes with 1 cm gaps
  addStatic(scene, new spook::Plane(Vec3::UnitZ()), Vec3::Zero(), "ground");
  for (int level = 0; level < kBase; ++level) {
    const int count = kBase - level;
    for (int i = 0; i < count; ++i) {
      const Vec3 p((i - (count - 1) / 2.0) * kPitch, 0.0, 0.5 + level);
      addBody(scene, new spook::Box(Vec3::Constant(0.5)), p, "cube " + std::to_string(level) + "." + std::to_string(i));
      scene.tracked.push_back(scene.bodies.size() - 1);
    }
  }
}

void stack(Scene& scene) {
  constexpr int kCount = 10;
  addStatic(scene, new spook::Plane(Vec3::UnitZ()), Vec3::Zero(), "ground");
  for (int i = 0; i < kCount; ++i)
    addBody(scene, new spook::Box(Vec3::Constant(0.5)), Vec3(0, 0, 0.5 + i), "cube " + std::to_string(i));
  scene.tracked.push_back(scene.bodies.size() - 1);  // the top cube
}

struct SceneSpec {
  std::string name;
  Kind kind;
  double h, duration;  ///< s
  std::function<void(Scene&)> build;
};

// --- Policies ----------------------------------------------------------------

struct Policy {
  std::string name;
  std::function<spook::SolverRef()> make;
  std::optional<spook::SolveType> frictionSolveType;  ///< hybrid only; the others ignore it
};

const char* solveTypeName(spook::SolveType type) {
  switch (type) {
    case spook::SolveType::DIRECT:
      return "DIRECT";
    case spook::SolveType::ITERATIVE:
      return "ITERATIVE";
    case spook::SolveType::DIRECT_AND_ITERATIVE:
      return "DIRECT_AND_ITERATIVE";
    case spook::SolveType::SPLIT:
      return "SPLIT";
  }
  return "?";
}

std::vector<Policy> policies() {
  std::vector<Policy> list;
  list.push_back({"direct", [] { return spook::SolverRef(new spook::DirectSolver()); }, std::nullopt});
  for (spook::SolveType type :
       {spook::SolveType::SPLIT, spook::SolveType::DIRECT_AND_ITERATIVE, spook::SolveType::DIRECT})
    list.push_back({"hybrid", [] { return spook::SolverRef(new spook::HybridSolver()); }, type});
  for (int n : {16, 64})
    list.push_back({"iterative" + std::to_string(n),
                    [n] {
                      spook::SolverRef s = new spook::IterativeSolver();
                      s->setNumIterations(n);
                      return s;
                    },
                    std::nullopt});
  return list;
}

// --- Measuring ---------------------------------------------------------------

struct Result {
  std::string scene, policy, friction;
  double h = 0, seconds = 0, msPerStep = 0, slowestMs = 0, drift = 0, penetration = 0, kineticEnergy = 0, wall = 0;
  long steps = 0;
  std::size_t contacts = 0;
  bool finite = true, tooSlow = false, escaped = false;
  spook::SolverStatistics solver;  ///< of the last step
  std::string verdict;
};

/// Enabled contact points and the deepest of them (m) after the last step.
std::pair<std::size_t, double> contactsOf(const spook::Simulation& sim) {
  std::size_t count = 0;
  double deepest = 0.0;
  for (const auto& c : sim.getGeometryContacts()) {
    if (!c.isEnabled() || c.isSensor()) continue;
    for (const auto& p : c.points())
      if (p.enabled) {
        ++count;
        deepest = std::max(deepest, p.depth);
      }
  }
  return {count, deepest};
}

double kineticEnergyOf(const Scene& scene) {
  double e = 0.0;
  for (const auto& b : scene.bodies) e += b->getKineticEnergy();
  return e;
}

double totalMassOf(const Scene& scene) {
  double m = 0.0;
  for (const auto& b : scene.bodies) m += b->getMassProperties()->getMass();
  return m;
}

std::string verdictOf(const Result& r, Kind kind, double settledEnergy) {
  if (!r.finite) return "non-finite";
  if (r.tooSlow) return "too slow";
  if (kind == Kind::SPHERES) {
    if (r.escaped) return "fell";
    if (r.penetration > kSoftPenetration) return "soft";
    if (r.kineticEnergy > settledEnergy) return "unsettled";
    return "ok";
  }
  return r.drift >= kFellDrift ? "fell" : r.drift >= kOkDrift ? "soft" : "ok";
}

Result run(const SceneSpec& spec, const Policy& policy) {
  Scene scene;
  spec.build(scene);
  setFriction(scene, policy.frictionSolveType.value_or(spook::SolveType::SPLIT));
  scene.sim->setTimeStep(spec.h);
  scene.sim->setSolver(policy.make());
  Result r;
  r.scene = spec.name;
  r.policy = policy.name;
  r.friction = policy.frictionSolveType ? solveTypeName(*policy.frictionSolveType) : "-";
  r.h = spec.h;
  const long steps = std::lround(spec.duration / spec.h);
  const long lastSecond = steps - std::lround(1.0 / spec.h);  // the first step of the last simulated second
  double timed = 0.0, all = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    const auto stepStart = std::chrono::steady_clock::now();
    scene.sim->stepForward();
    const double step = std::chrono::duration<double>(std::chrono::steady_clock::now() - stepStart).count();
    all += step;
    r.slowestMs = std::max(r.slowestMs, 1e3 * step);
    if (k >= lastSecond) timed += step;
    r.steps = k + 1;
    const auto& statistics = scene.sim->getStatistics();
    r.finite = r.finite && statistics.solver.nonFiniteIslands == 0 && statistics.frozenBodies.empty();
    if (spec.kind != Kind::SPHERES || k >= lastSecond)
      r.penetration = std::max(r.penetration, contactsOf(*scene.sim).second);
    for (std::size_t i : scene.tracked) {
      const double moved = (scene.bodies[i]->getPosition() - scene.starts[i]).norm();
      r.finite = r.finite && std::isfinite(moved);
      if (std::isfinite(moved)) r.drift = std::max(r.drift, moved);
    }
    if (step > kTooSlowStep) {
      r.tooSlow = true;
      break;
    }
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.seconds = double(r.steps) * spec.h;
  r.msPerStep = r.steps > lastSecond ? 1e3 * timed / double(r.steps - lastSecond) : 1e3 * all / double(r.steps);
  r.contacts = contactsOf(*scene.sim).first;
  r.kineticEnergy = kineticEnergyOf(scene);
  r.finite = r.finite && std::isfinite(r.kineticEnergy);
  r.solver = scene.sim->getStatistics().solver;
  if (spec.kind == Kind::SPHERES) {
    r.drift = kNaN;
    if (r.steps <= lastSecond) r.penetration = kNaN;  // stopped before the last second
    for (const auto& b : scene.bodies) {
      const Vec3 p = b->getPosition();
      r.finite = r.finite && p.allFinite();
      r.escaped = r.escaped || std::abs(p.x()) > 1.0 || std::abs(p.y()) > 1.0 || p.z() < 0.0;
    }
  }
  const double settledEnergy = 0.5 * totalMassOf(scene) * kSettledSpeed * kSettledSpeed;
  r.verdict = verdictOf(r, spec.kind, settledEnergy);
  return r;
}

std::string format(double value, const char* spec) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, spec, value);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string csvPath = argc > 1 ? argv[1] : "contact_study.csv";
  const std::string only = argc > 2 ? argv[2] : "";  // run only the scenes whose name contains this
  std::vector<SceneSpec> scenes = {
      {"spheres", Kind::SPHERES, 1.0 / 60, 3.0, spheres},
      {"pyramid", Kind::PYRAMID, 1.0 / 60, 5.0, pyramid},
      {"stack 1/60", Kind::STACK, 1.0 / 60, 10.0, stack},
      {"stack 1/30", Kind::STACK, 1.0 / 30, 10.0, stack},
  };
  std::erase_if(scenes, [&](const SceneSpec& scene) { return scene.name.find(only) == std::string::npos; });

  std::vector<Result> results;
  const auto start = std::chrono::steady_clock::now();
  for (const SceneSpec& scene : scenes)
    for (const Policy& policy : policies()) {
      results.push_back(run(scene, policy));
      const Result& r = results.back();
      std::fprintf(stderr, "%s, %s %s: %.1f s wall, %s\n", r.scene.c_str(), r.policy.c_str(), r.friction.c_str(),
                   r.wall, r.verdict.c_str());
    }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("%-10s  %-11s  %-20s  %9s  %8s  %9s  %9s  %9s  %-10s  %5s  %9s  %8s\n", "scene", "policy", "friction",
              "ms/step", "contacts", "drift (m)", "max pen", "KE (J)", "verdict", "T (s)", "slowest", "wall (s)");
  std::string previous;
  for (const Result& r : results) {
    if (r.scene != previous && !previous.empty()) std::printf("\n");
    previous = r.scene;
    std::printf("%-10s  %-11s  %-20s  %9.2f  %8zu  %9s  %9s  %9.2e  %-10s  %5.2f  %9.1f  %8.1f\n", r.scene.c_str(),
                r.policy.c_str(), r.friction.c_str(), r.msPerStep, r.contacts, format(r.drift, "%.2e").c_str(),
                format(r.penetration, "%.2e").c_str(), r.kineticEnergy, r.verdict.c_str(), r.seconds, r.slowestMs,
                r.wall);
  }
  std::printf(
      "\nms/step: wall-clock of stepForward, mean over the last simulated second; contacts: enabled points at the\n"
      "end; drift: worst displacement from the start over the run (stack: top cube, pyramid: any cube); max pen:\n"
      "deepest penetration (spheres: last second); KE: kinetic energy at the end. verdict: stack and pyramid ok\n"
      "< %g m <= soft < %g m <= fell; spheres fell (left the box), soft (pen > %g m), unsettled (KE > 1/2 M\n"
      "(%g m/s)^2), ok; too slow: a step took > %g s and the run stopped there, its measures are those of the\n"
      "steps taken. T: simulated time reached; slowest: the slowest step (ms); wall: the run's wall-clock;\n"
      "study wall-clock %.1f s.\n",
      kOkDrift, kFellDrift, kSoftPenetration, kSettledSpeed, kTooSlowStep, total);

  std::FILE* csv = std::fopen(csvPath.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csvPath.c_str());
    return 1;
  }
  std::fprintf(csv,
               "scene,policy,friction_solve_type,h,steps,seconds,ms_per_step,slowest_step_ms,contact_points,drift_m,"
               "max_penetration_m,end_kinetic_energy_j,rows,iterations,factorizations,complementarity_error,converged,"
               "finite,verdict,run_wall_s\n");
  for (const Result& r : results)
    std::fprintf(csv, "%s,%s,%s,%.17g,%ld,%.6g,%.6g,%.6g,%zu,%.6e,%.6e,%.6e,%d,%d,%d,%.6e,%d,%d,%s,%.6g\n",
                 r.scene.c_str(), r.policy.c_str(), r.friction.c_str(), r.h, r.steps, r.seconds, r.msPerStep,
                 r.slowestMs, r.contacts, r.drift, r.penetration, r.kineticEnergy, r.solver.numRows,
                 r.solver.iterations, r.solver.factorizations, r.solver.complementarityError,
                 r.solver.converged ? 1 : 0, r.finite ? 1 : 0, r.verdict.c_str(), r.wall);
  std::fclose(csv);
  std::printf("CSV written to %s (plot: python3 bench/plot_contact_study.py %s)\n", csvPath.c_str(), csvPath.c_str());
  return 0;
}
