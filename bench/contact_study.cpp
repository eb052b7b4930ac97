// Contact scenes against the solver policies (DESIGN.md, promise 1, now with
// contacts), and against Bullet and ODE where they are installed: each
// scene × policy is simulated and the program reports the wall-clock cost
// per step, the contact points, how far the resting bodies drifted, the
// deepest penetration and the kinetic energy left at the end.
// Every contact point is one normal row and two friction rows. It prints an
// aligned table and writes a CSV (argv[1], default contact_study.csv) that
// bench/plot_contact_study.py turns into a cost-vs-drift plot; argv[2], when
// given, runs only the scenes whose name contains it, and argv[3] only the
// policies whose name and friction solve type contain it ("direct", "hybrid
// SPLIT", "bullet"), and argv[4] gives spook's threads per simulation
// (SimulationT::setNumThreads, default 1). `contact_study --scaling [csv]
// [threads]` measures the cost per step against the body count instead
// (scaling() below; bench/plot_contact_scaling.py).
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
//   20-stack 1/60, 20-stack 1/30  20 unit cubes stacked, 10 s at each step
//   20 stacks   20 such stacks 3 m apart on a 4 × 5 grid (20 islands);
//               5 s at h = 1/60
//
// Policies: direct (its defaults, post-stabilization on); hybrid with the
// contact material's friction model (iterative projected cone) solved SPLIT
// (the default: normals direct, friction iterative), DIRECT_AND_ITERATIVE
// and DIRECT; "hybrid sleep", the default hybrid with the simulation's auto
// sleep on (SimulationT::getAutoSleep); iterative (projected Gauss–Seidel,
// cold started) with 16 and 64 sweeps. The direct and iterative policies
// ignore the solve type ("-").
//
// Reference engines, built in when their packages are installed (CMake finds
// them with pkg-config; bench/study_engine_*.cpp), each with its own defaults
// and the same bodies, masses, friction coefficient (pair value 0.5) and no
// restitution: "bullet SI" (btDiscreteDynamicsWorld, sequential impulse, 10
// iterations, sleeping off), "bullet MLCP" (btMLCPSolver with the Dantzig
// LCP; where the LCP fails, Bullet silently redoes the step with sequential
// impulses), "ode quick" (dWorldQuickStep, 20 SOR iterations) and "ode world"
// (dWorldStep, the Dantzig LCP), both with the friction pyramid
// (dContactApprox1) and ODE's ERP 0.2 and CFM (1e-10 in double). Their
// penetration and contact count are those of their own contact points.
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
//               0.67 mm (20 cubes: 210 m g/(4E) = 2.57 mm), the pyramid's
//               apex by about 0.8 mm
//   max pen     the deepest contact penetration (m): over the last second for
//               spheres (the impacts before are transients), over the run for
//               the stack and the pyramid
//   KE          kinetic energy Σ ½vᵀMv + ½ωᵀIω at the end (J)
//   verdict     non-finite: a solve dropped an island, a body froze or a pose
//               went non-finite; too slow: one step took more than 5 s, the
//               run was stopped there (its measures are those of the steps
//               taken, T the simulated time reached); stack and pyramid: ok
//               when drift < 1 mm (a stack's beyond the settling of its
//               contacts' compliance: 0.67 mm for 10 cubes, 2.57 mm for
//               20), soft < 0.1 m, fell beyond; spheres: fell
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
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spook/spook.hpp>

#include "study_engine.hpp"

#ifndef SPOOK_STUDY_BULLET
std::vector<study::ReferenceEngine> study::bulletEngines() { return {}; }
#endif
#ifndef SPOOK_STUDY_ODE
std::vector<study::ReferenceEngine> study::odeEngines() { return {}; }
#endif

namespace {

using Vec3 = spook::Vec3;
constexpr double kFriction = 0.5;
constexpr double kOkDrift = 1e-3;          // m
constexpr double kFellDrift = 0.1;         // m
constexpr double kSoftPenetration = 0.01;  // m, spheres
constexpr double kSettledSpeed = 0.01;     // m/s, spheres: KE < ½ M v² counts as settled
constexpr double kTooSlowStep = 5.0;       // s of wall-clock for one step
constexpr double kGravity = 9.80665;       // m/s²
constexpr double kPairYoungsModulus = 2e8;  // Pa: spook's default contact material for two default materials
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// --- Scenes ------------------------------------------------------------------

enum class Kind { SPHERES, PYRAMID, STACK };

/// A scene without an engine and the dynamic bodies whose displacement is
/// its drift.
struct StudyScene {
  study::SceneDescription description;
  std::vector<std::size_t> tracked;  ///< dynamic-body indices
  double halfWidth = 1.0;            ///< m, spheres: a sphere farther out than this left the box
  /// m, stack: how far the contacts' compliance alone lowers the top cube
  /// (the verdict judges the drift beyond it).
  double elasticSettle = 0.0;
};

study::BodySpec ground() {
  study::BodySpec spec;
  spec.shape = study::ShapeType::PLANE;
  spec.dynamic = false;
  return spec;
}

study::BodySpec box(const study::Point& halfExtents, const study::Point& position, bool dynamic) {
  study::BodySpec spec;
  spec.shape = study::ShapeType::BOX;
  spec.halfExtents = halfExtents;
  spec.position = position;
  spec.dynamic = dynamic;
  return spec;
}

study::BodySpec sphere(double radius, const study::Point& position) {
  study::BodySpec spec;
  spec.shape = study::ShapeType::SPHERE;
  spec.radius = radius;
  spec.position = position;
  return spec;
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

/// `count` spheres of radius 0.1 m poured from a jittered square grid of
/// about 13 layers into a box that fits the grid (2.2 m wide for the
/// 1,000 of the table's scene).
StudyScene spheres(int count) {
  constexpr double kRadius = 0.1, kPitch = 0.22, kLayerPitch = 0.25;  // m
  constexpr double kWallHalf = 2.0;                                   // m: walls 4 m tall
  const int grid = std::max(1, int(std::ceil(std::sqrt(count / 13.0))));
  const double inner = grid * kPitch / 2.0 + 0.01;  // m: the walls' inner faces
  StudyScene scene;
  scene.halfWidth = inner;
  auto& bodies = scene.description.bodies;
  bodies.push_back(ground());
  for (double side : {-1.0, 1.0}) {
    bodies.push_back(box({0.1, inner + 0.2, kWallHalf}, {(inner + 0.1) * side, 0, kWallHalf}, false));
    bodies.push_back(box({inner + 0.2, 0.1, kWallHalf}, {0, (inner + 0.1) * side, kWallHalf}, false));
  }
  // Neighbours 2 cm apart on the grid, so a jitter of ±8 mm keeps them apart;
  // the outermost stay 1.2 cm inside the walls.
  for (int i = 0; i < count; ++i) {
    const int layer = i / (grid * grid), column = i % grid, row = (i / grid) % grid;
    const std::uint32_t slot = std::uint32_t(i);
    bodies.push_back(sphere(kRadius, {(column - (grid - 1) / 2.0) * kPitch + 0.008 * jitter(slot, 0),
                                      (row - (grid - 1) / 2.0) * kPitch + 0.008 * jitter(slot, 1),
                                      2.0 * kRadius + layer * kLayerPitch + 0.02 * jitter(slot, 2)}));
  }
  return scene;
}

StudyScene pyramid(int base) {
  constexpr double kPitch = 1.01;  // m: unit cubes with 1 cm gaps
  StudyScene scene;
  scene.description.bodies.push_back(ground());
  std::size_t index = 0;
  for (int level = 0; level < base; ++level) {
    const int count = base - level;
    for (int i = 0; i < count; ++i) {
      scene.description.bodies.push_back(box({0.5, 0.5, 0.5}, {(i - (count - 1) / 2.0) * kPitch, 0.0, 0.5 + level}, true));
      scene.tracked.push_back(index++);
    }
  }
  return scene;
}

/// Contact k from the top of a stack of `count` unit cubes (1000 kg)
/// carries k cubes on 4 points of compliance 1/E each: the top settles by
/// Σk m g/(4E) (m).
double elasticSettle(int count) { return count * (count + 1) / 2.0 * 1000.0 * kGravity / (4.0 * kPairYoungsModulus); }

StudyScene stack(int count) {
  StudyScene scene;
  scene.description.bodies.push_back(ground());
  for (int i = 0; i < count; ++i) scene.description.bodies.push_back(box({0.5, 0.5, 0.5}, {0, 0, 0.5 + i}, true));
  scene.tracked.push_back(std::size_t(count - 1));  // the top cube
  scene.elasticSettle = elasticSettle(count);
  return scene;
}

// 20 stacks of 10 unit cubes, 3 m apart on a 4 × 5 grid: 20 islands, which
// a simulation's threads solve side by side.
StudyScene stacks() {
  constexpr int kStacks = 20, kCount = 10;
  StudyScene scene;
  scene.description.bodies.push_back(ground());
  for (int s = 0; s < kStacks; ++s)
    for (int i = 0; i < kCount; ++i) {
      scene.description.bodies.push_back(box({0.5, 0.5, 0.5}, {3.0 * (s % 4), 3.0 * (s / 4), 0.5 + i}, true));
      if (i == kCount - 1) scene.tracked.push_back(scene.description.bodies.size() - 2);  // a top cube
    }
  scene.elasticSettle = elasticSettle(kCount);
  return scene;
}

struct SceneSpec {
  std::string name;
  Kind kind;
  double h, duration;  ///< s
  std::function<StudyScene()> build;
  /// Wall-clock (s) after which a run stops, as one too slow step stops it.
  double budget = std::numeric_limits<double>::infinity();
};

// --- Engines -----------------------------------------------------------------

/// The scene in spook under one solver policy. Every geometry shares one
/// material whose contact material with itself has the scene's friction
/// coefficient and a projected-cone friction model solved as
/// `frictionSolveType` (the hybrid policy's choice; the others ignore it).
class SpookEngine final : public study::Engine {
 public:
  SpookEngine(const study::SceneDescription& scene, spook::SolverRef solver, spook::SolveType frictionSolveType,
              int threads, bool sleep) {
    sim_->setUniformGravity(Vec3(0, 0, scene.gravity));
    material_->getBulkMaterial()->setDensity(scene.density);
    auto* cm = sim_->getMaterialManager()->getOrCreateContactMaterial(material_.get(), material_.get());
    spook::FrictionModelRef model = new spook::IterativeProjectedConeFriction();
    model->setSolveType(frictionSolveType);
    cm->setFrictionModel(model);
    cm->setFrictionCoefficient(scene.friction);
    for (std::size_t i = 0; i < scene.bodies.size(); ++i) add(scene.bodies[i], "body " + std::to_string(i));
    sim_->setTimeStep(scene.timeStep);
    sim_->setSolver(solver);
    sim_->setNumThreads(threads);
    sim_->getAutoSleep()->setEnable(sleep);
  }

  void step() override {
    sim_->stepForward();
    const spook::SolverStatistics& solver = sim_->getStatistics().solver;
    cost_.seconds += solver.solveTime;
    cost_.rowUpdates += double(solver.numIterativeRows) * double(solver.iterations);
    cost_.sweepsOnly = cost_.sweepsOnly && solver.numDirectRows == 0;
  }

  // The solve's wall-clock (SolverStatistics::solveTime: packing the rows,
  // the sweeps, the residual of the statistics) against the rows swept
  // times the most sweeps of an island (exact for one island).
  study::SolverCost solverCost() const override { return cost_; }

  study::Point position(std::size_t i) const override {
    const Vec3 p = bodies_[i]->getPosition();
    return {p.x(), p.y(), p.z()};
  }

  double kineticEnergy() const override {
    double e = 0.0;
    for (const auto& b : bodies_) e += b->getKineticEnergy();
    return e;
  }

  study::ContactSummary contacts() const override {
    study::ContactSummary summary;
    for (const auto& c : sim_->getGeometryContacts()) {
      if (!c.isEnabled() || c.isSensor()) continue;
      for (const auto& p : c.points())
        if (p.enabled) {
          ++summary.points;
          summary.deepest = std::max(summary.deepest, p.depth);
        }
    }
    return summary;
  }

  bool healthy() const override {
    const auto& statistics = sim_->getStatistics();
    return statistics.solver.nonFiniteIslands == 0 && statistics.frozenBodies.empty();
  }

  const spook::SolverStatistics& solverStatistics() const { return sim_->getStatistics().solver; }

 private:
  void add(const study::BodySpec& spec, const std::string& name) {
    spook::ShapeT<double>* shape = nullptr;
    switch (spec.shape) {
      case study::ShapeType::PLANE:
        shape = new spook::Plane(Vec3::UnitZ());
        break;
      case study::ShapeType::BOX:
        shape = new spook::Box(Vec3(spec.halfExtents[0], spec.halfExtents[1], spec.halfExtents[2]));
        break;
      case study::ShapeType::SPHERE:
        shape = new spook::Sphere(spec.radius);
        break;
    }
    spook::GeometryRef geometry = new spook::Geometry(shape, spook::Transform::Identity(), name);
    geometry->setMaterial(material_);
    const Vec3 position(spec.position[0], spec.position[1], spec.position[2]);
    if (!spec.dynamic) {
      geometry->setPosition(position);
      sim_->add(geometry);
      return;
    }
    spook::RigidBodyRef body = new spook::RigidBody(name);
    body->add(geometry);
    body->setPosition(position);
    sim_->add(body);
    bodies_.push_back(body);
  }

  spook::SimulationRef sim_ = new spook::Simulation();
  spook::MaterialRef material_ = new spook::Material("wood");
  study::SolverCost cost_;
  std::vector<spook::RigidBodyRef> bodies_;
};

// --- Policies ----------------------------------------------------------------

struct Policy {
  std::string name, friction;  ///< friction: the hybrid's friction solve type, "-" where it does not apply
  std::function<std::unique_ptr<study::Engine>(const study::SceneDescription&)> make;
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

Policy spookPolicy(std::string name, std::function<spook::SolverRef()> solver, std::optional<spook::SolveType> type,
                   int threads, bool sleep = false) {
  return {std::move(name), type ? solveTypeName(*type) : "-",
          [solver, type, threads, sleep](const study::SceneDescription& scene) -> std::unique_ptr<study::Engine> {
            return std::make_unique<SpookEngine>(scene, solver(), type.value_or(spook::SolveType::SPLIT), threads,
                                                 sleep);
          }};
}

std::vector<Policy> policies(int threads) {
  std::vector<Policy> list;
  list.push_back(
      spookPolicy("direct", [] { return spook::SolverRef(new spook::DirectSolver()); }, std::nullopt, threads));
  for (spook::SolveType type :
       {spook::SolveType::SPLIT, spook::SolveType::DIRECT_AND_ITERATIVE, spook::SolveType::DIRECT})
    list.push_back(spookPolicy("hybrid", [] { return spook::SolverRef(new spook::HybridSolver()); }, type, threads));
  list.push_back(spookPolicy(
      "hybrid sleep", [] { return spook::SolverRef(new spook::HybridSolver()); }, spook::SolveType::SPLIT, threads,
      true));
  for (int n : {16, 64})
    list.push_back(spookPolicy(
        "iterative" + std::to_string(n),
        [n] {
          spook::SolverRef s = new spook::IterativeSolver();
          s->setNumIterations(n);
          return s;
        },
        std::nullopt, threads));
  for (const auto& engines : {study::bulletEngines(), study::odeEngines()})
    for (const study::ReferenceEngine& engine : engines) list.push_back({engine.name, "-", engine.make});
  return list;
}

// --- Measuring ---------------------------------------------------------------

struct Result {
  std::string scene, policy, friction;
  double h = 0, seconds = 0, msPerStep = 0, slowestMs = 0, drift = 0, penetration = 0, kineticEnergy = 0, wall = 0;
  /// The solver's time per row update over the last simulated second (ns);
  /// NaN where the engine does not tell or solved rows otherwise.
  double nsPerRowUpdate = 0;
  long steps = 0;
  std::size_t contacts = 0;
  bool finite = true, tooSlow = false, escaped = false;
  std::optional<spook::SolverStatistics> solver;  ///< spook's, of the last step
  std::string verdict;
};

double totalMassOf(const study::SceneDescription& scene) {
  double volume = 0.0;
  for (const auto& b : scene.bodies)
    if (b.dynamic) volume += study::volumeOf(b);
  return scene.density * volume;
}

std::size_t dynamicCountOf(const study::SceneDescription& scene) {
  return std::size_t(std::count_if(scene.bodies.begin(), scene.bodies.end(), [](const auto& b) { return b.dynamic; }));
}

double distance(const study::Point& a, const study::Point& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

std::string verdictOf(const Result& r, Kind kind, double settledEnergy, double elasticSettle) {
  if (!r.finite) return "non-finite";
  if (r.tooSlow) return "too slow";
  if (kind == Kind::SPHERES) {
    if (r.escaped) return "fell";
    if (r.penetration > kSoftPenetration) return "soft";
    if (r.kineticEnergy > settledEnergy) return "unsettled";
    return "ok";
  }
  if (r.drift >= kFellDrift) return "fell";
  return std::abs(r.drift - elasticSettle) >= kOkDrift ? "soft" : "ok";
}

Result run(const SceneSpec& spec, const Policy& policy) {
  StudyScene scene = spec.build();
  scene.description.timeStep = spec.h;
  const std::unique_ptr<study::Engine> engine = policy.make(scene.description);
  const std::size_t dynamicCount = dynamicCountOf(scene.description);
  std::vector<study::Point> starts;
  for (std::size_t i = 0; i < dynamicCount; ++i) starts.push_back(engine->position(i));
  Result r;
  r.scene = spec.name;
  r.policy = policy.name;
  r.friction = policy.friction;
  r.h = spec.h;
  const long steps = std::lround(spec.duration / spec.h);
  const long lastSecond = steps - std::lround(1.0 / spec.h);  // the first step of the last simulated second
  double timed = 0.0, all = 0.0;
  study::SolverCost costBefore;
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < steps; ++k) {
    if (k == lastSecond) costBefore = engine->solverCost();
    const auto stepStart = std::chrono::steady_clock::now();
    engine->step();
    const double step = std::chrono::duration<double>(std::chrono::steady_clock::now() - stepStart).count();
    all += step;
    r.slowestMs = std::max(r.slowestMs, 1e3 * step);
    if (k >= lastSecond) timed += step;
    r.steps = k + 1;
    r.finite = r.finite && engine->healthy();
    if (spec.kind != Kind::SPHERES || k >= lastSecond) r.penetration = std::max(r.penetration, engine->contacts().deepest);
    for (std::size_t i : scene.tracked) {
      const double moved = distance(engine->position(i), starts[i]);
      r.finite = r.finite && std::isfinite(moved);
      if (std::isfinite(moved)) r.drift = std::max(r.drift, moved);
    }
    if (step > kTooSlowStep ||
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > spec.budget) {
      r.tooSlow = true;
      break;
    }
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.seconds = double(r.steps) * spec.h;
  r.msPerStep = r.steps > lastSecond ? 1e3 * timed / double(r.steps - lastSecond) : 1e3 * all / double(r.steps);
  const study::SolverCost cost = engine->solverCost();
  const double updates = cost.rowUpdates - costBefore.rowUpdates;
  r.nsPerRowUpdate = cost.sweepsOnly && updates > 0.0 && r.steps > lastSecond
                         ? 1e9 * (cost.seconds - costBefore.seconds) / updates
                         : kNaN;
  r.contacts = engine->contacts().points;
  r.kineticEnergy = engine->kineticEnergy();
  r.finite = r.finite && std::isfinite(r.kineticEnergy);
  if (const auto* spookEngine = dynamic_cast<const SpookEngine*>(engine.get())) r.solver = spookEngine->solverStatistics();
  if (spec.kind == Kind::SPHERES) {
    r.drift = kNaN;
    if (r.steps <= lastSecond) r.penetration = kNaN;  // stopped before the last second
    for (std::size_t i = 0; i < dynamicCount; ++i) {
      const study::Point p = engine->position(i);
      r.finite = r.finite && std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
      r.escaped = r.escaped || std::abs(p[0]) > scene.halfWidth || std::abs(p[1]) > scene.halfWidth || p[2] < 0.0;
    }
  }
  const double settledEnergy = 0.5 * totalMassOf(scene.description) * kSettledSpeed * kSettledSpeed;
  r.verdict = verdictOf(r, spec.kind, settledEnergy, scene.elasticSettle);
  return r;
}

std::string format(double value, const char* spec) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, spec, value);
  return text;
}

}  // namespace

// --- Scaling -----------------------------------------------------------------

/// Cost per step against body count (`contact_study --scaling [csv]
/// [threads]`): pyramids of base 10–50 (55–1,275 cubes) and 100–10,000
/// poured spheres, 2 s at h = 1/60 each (ms/step: the mean over the last
/// second), under the default policy, iterative 16 and the reference
/// engines, each run stopped after 120 s of wall-clock (then "too slow", its
/// cost that of the steps taken). bench/plot_contact_scaling.py plots it.
int scaling(const std::string& csvPath, int threads) {
  struct Size {
    std::string scene;
    Kind kind;
    int n;
  };
  std::vector<Size> sizes;
  for (int base : {10, 20, 30, 40, 50}) sizes.push_back({"pyramid", Kind::PYRAMID, base});
  for (int count : {100, 300, 1000, 3000, 10000}) sizes.push_back({"spheres", Kind::SPHERES, count});
  std::FILE* csv = std::fopen(csvPath.c_str(), "w");
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", csvPath.c_str());
    return 1;
  }
  std::fprintf(csv,
               "scene,bodies,policy,friction_solve_type,steps,ms_per_step,body_steps_per_s,drift_m,"
               "max_penetration_m,verdict\n");
  std::printf("%-8s  %6s  %-12s  %-6s  %9s  %13s  %9s  %9s  %-10s\n", "scene", "bodies", "policy", "fric.", "ms/step",
              "body-steps/s", "drift (m)", "max pen", "verdict");
  for (const Size& size : sizes) {
    const SceneSpec spec{size.scene,
                         size.kind,
                         1.0 / 60,
                         2.0,
                         [size] { return size.kind == Kind::PYRAMID ? pyramid(size.n) : spheres(size.n); },
                         120.0};
    const std::size_t bodies = dynamicCountOf(spec.build().description);
    for (const Policy& policy : policies(threads)) {
      const std::string name = policy.name + " " + policy.friction;
      if (name != "hybrid SPLIT" && name != "iterative16 -" && name != "bullet SI -" && name != "ode quick -") continue;
      const Result r = run(spec, policy);
      const double rate = 1e3 * double(bodies) / r.msPerStep;
      std::printf("%-8s  %6zu  %-12s  %-6s  %9.2f  %13.3g  %9s  %9s  %-10s\n", size.scene.c_str(), bodies,
                  r.policy.c_str(), r.friction.c_str(), r.msPerStep, rate, format(r.drift, "%.2e").c_str(),
                  format(r.penetration, "%.2e").c_str(), r.verdict.c_str());
      std::fflush(stdout);
      std::fprintf(csv, "%s,%zu,%s,%s,%ld,%.6g,%.6g,%.6e,%.6e,%s\n", size.scene.c_str(), bodies, r.policy.c_str(),
                   r.friction.c_str(), r.steps, r.msPerStep, rate, r.drift, r.penetration, r.verdict.c_str());
    }
  }
  std::fclose(csv);
  std::printf("CSV written to %s (plot: python3 bench/plot_contact_scaling.py %s)\n", csvPath.c_str(), csvPath.c_str());
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--scaling")
    return scaling(argc > 2 ? argv[2] : "contact_scaling.csv", argc > 3 ? std::atoi(argv[3]) : 1);
  const std::string csvPath = argc > 1 ? argv[1] : "contact_study.csv";
  const std::string only = argc > 2 ? argv[2] : "";          // run only the scenes whose name contains this
  const std::string onlyPolicy = argc > 3 ? argv[3] : "";    // and only the policies whose "name friction" contains this
  const int threads = argc > 4 ? std::atoi(argv[4]) : 1;     // spook's SimulationT::setNumThreads
  std::vector<SceneSpec> scenes = {
      {"spheres", Kind::SPHERES, 1.0 / 60, 3.0, [] { return spheres(1000); }},
      {"pyramid", Kind::PYRAMID, 1.0 / 60, 5.0, [] { return pyramid(20); }},
      {"stack 1/60", Kind::STACK, 1.0 / 60, 10.0, [] { return stack(10); }},
      {"stack 1/30", Kind::STACK, 1.0 / 30, 10.0, [] { return stack(10); }},
      {"20-stack 1/60", Kind::STACK, 1.0 / 60, 10.0, [] { return stack(20); }},
      {"20-stack 1/30", Kind::STACK, 1.0 / 30, 10.0, [] { return stack(20); }},
      {"20 stacks", Kind::STACK, 1.0 / 60, 5.0, stacks},
  };
  std::erase_if(scenes, [&](const SceneSpec& scene) { return scene.name.find(only) == std::string::npos; });

  std::vector<Result> results;
  const auto start = std::chrono::steady_clock::now();
  for (const SceneSpec& scene : scenes)
    for (const Policy& policy : policies(threads)) {
      if ((policy.name + " " + policy.friction).find(onlyPolicy) == std::string::npos) continue;
      results.push_back(run(scene, policy));
      const Result& r = results.back();
      std::fprintf(stderr, "%s, %s %s: %.1f s wall, %s\n", r.scene.c_str(), r.policy.c_str(), r.friction.c_str(),
                   r.wall, r.verdict.c_str());
    }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("%-13s  %-11s  %-20s  %9s  %8s  %9s  %9s  %9s  %-10s  %5s  %9s  %8s  %6s\n", "scene", "policy",
              "friction", "ms/step", "contacts", "drift (m)", "max pen", "KE (J)", "verdict", "T (s)", "slowest",
              "wall (s)", "ns/row");
  std::string previous;
  for (const Result& r : results) {
    if (r.scene != previous && !previous.empty()) std::printf("\n");
    previous = r.scene;
    std::printf("%-13s  %-11s  %-20s  %9.2f  %8zu  %9s  %9s  %9.2e  %-10s  %5.2f  %9.1f  %8.1f  %6s\n", r.scene.c_str(),
                r.policy.c_str(), r.friction.c_str(), r.msPerStep, r.contacts, format(r.drift, "%.2e").c_str(),
                format(r.penetration, "%.2e").c_str(), r.kineticEnergy, r.verdict.c_str(), r.seconds, r.slowestMs,
                r.wall, format(r.nsPerRowUpdate, "%.1f").c_str());
  }
  std::printf(
      "\nms/step: wall-clock of stepForward, mean over the last simulated second; contacts: enabled points at the\n"
      "end; drift: worst displacement from the start over the run (stack: top cube, pyramid: any cube); max pen:\n"
      "deepest penetration (spheres: last second); KE: kinetic energy at the end. verdict: stack and pyramid ok\n"
      "< %g m (a stack's beyond its contacts' elastic settling) <= soft < %g m <= fell; spheres fell (left the box), "
      "soft (pen > %g m), unsettled (KE > 1/2 M\n"
      "(%g m/s)^2), ok; too slow: a step took > %g s and the run stopped there, its measures are those of the\n"
      "steps taken. T: simulated time reached; slowest: the slowest step (ms); wall: the run's wall-clock;\n"
      "ns/row: the iterative solver's time per row update (rows x sweeps) over the last second, spook's\n"
      "iterative policy (packing, sweeps, residual) and Bullet's sequential impulses (sweeps only);\n"
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
               "finite,verdict,run_wall_s,ns_per_row_update\n");
  for (const Result& r : results) {
    const spook::SolverStatistics solver = r.solver.value_or(spook::SolverStatistics{});
    std::fprintf(csv, "%s,%s,%s,%.17g,%ld,%.6g,%.6g,%.6g,%zu,%.6e,%.6e,%.6e,%d,%d,%d,%.6e,%d,%d,%s,%.6g,%.6g\n",
                 r.scene.c_str(), r.policy.c_str(), r.friction.c_str(), r.h, r.steps, r.seconds, r.msPerStep,
                 r.slowestMs, r.contacts, r.drift, r.penetration, r.kineticEnergy, solver.numRows, solver.iterations,
                 solver.factorizations, r.solver ? solver.complementarityError : kNaN, solver.converged ? 1 : 0,
                 r.finite ? 1 : 0, r.verdict.c_str(), r.wall, r.nsPerRowUpdate);
  }
  std::fclose(csv);
  std::printf("CSV written to %s (plot: python3 bench/plot_contact_study.py %s)\n", csvPath.c_str(), csvPath.c_str());
  return 0;
}
