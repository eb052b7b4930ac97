#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <numeric>
#include <span>
#include <typeinfo>
#include <vector>

#include <spook/core/geometric_growth.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/worker_pool.hpp>
#include <spook/solver/body_space_solve.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/row.hpp>
#include <spook/solver/small_dense.hpp>
#include <spook/solver/solver.hpp>
#include <spook/solver/spook_parameters.hpp>

namespace spook::detail {

/// Partitions the rows into islands (dynamic bodies connected through rows;
/// static and kinematic bodies do not join islands), turns each island into
/// an IslandProblem for step h, lets `solver` solve it, and writes the
/// impulses to the array beside the rows and the velocity changes to `bodies`
/// (freeVelocity becomes v⁺). The bodies of an island whose impulses came
/// out non-finite are listed in getNonFiniteBodies().
class IslandStepper {
 public:
  /// Least regularization of a contact's friction rows relative to their
  /// mobility (G M⁻¹ Gᵀ)ᵢᵢ: Σ ≥ 1e-5 (GM⁻¹Gᵀ)ᵢᵢ. A box face's contact has
  /// 8 friction rows (4 corners × 2 tangents) on 3 relative degrees of
  /// freedom; with only a stiff material's compliance (Σ ~ 1e-7 of the
  /// mobility for a 1 kg wooden cube) the LCP's matrix had a condition
  /// number near 1e8, block pivoting cycled on round-off and a 55-cube
  /// brick pyramid fell back on every step (1.6 cm drift, 0.2-1 s steps);
  /// now none does (drift 3.5e-7 m). A sticking contact then creeps at
  /// 1e-5 (GM⁻¹Gᵀ)ᵢᵢ h F under a tangential load F: 8e-7 m/s for a box held
  /// on a 30° incline at 60 Hz. Normal rows keep their material's
  /// compliance: the same floor on them set jointed links whose contact
  /// fights their pin (test_jointed_contacts.cpp) apart by up to 1.4 m.
  static constexpr double kFrictionSofterThan = 1e-5;

  /// Post-stabilization: `rows` evaluated at the new positions with their
  /// target violation in `speed`, bodies with their inverse masses at the new
  /// orientations. Fills each body's displacement (Δx, Δθ) that brings the
  /// rows to their targets.
  void project(const RowSet& set, std::vector<SolverBody>& bodies, double h, Solver& solver,
               SolverStatistics& statistics, WorkerPool* workers = nullptr);
  /// The largest turn (rad) a projection gives a body: beyond ~0.2 rad the
  /// linearized rows overshoot (sin φ against φ: 0.7% at 0.2 rad, 16% at 1),
  /// and a scene with a body spinning at 100 rad/s, its rows violated by
  /// meters, turned it by 2, then 36, then 2e4 rad in successive steps.
  static constexpr double kMostProjectionTurn = 0.2;

  /// The dynamic bodies (indices into `bodies`) of the islands whose
  /// impulses the last solve() dropped as non-finite.
  [[nodiscard]] const std::vector<int>& getNonFiniteBodies() const { return nonFiniteBodies_; }

  /// The rows' impulses: each row's last impulse in (the warm start and the
  /// direct solver's first guess), the solved one out; rows that join no
  /// island (between static bodies) keep theirs. With `workers`, islands
  /// are solved on its threads (each by a worker copy of `solver`, see
  /// Solver::makeWorker), with the same results. `again`: the same rows
  /// solved again in the step (geometric stiffness), whose islands spend
  /// what the step's earlier solves left of their direct work budget.
  void solve(RowSet& set, std::vector<SolverBody>& bodies, double h, Solver& solver, SolverStatistics& statistics,
             WorkerPool* workers = nullptr, bool again = false);

  /// Fewest rows in a step worth spreading its islands over threads (a
  /// thread's wake-up costs about what ~100 rows' solve does).
  static constexpr std::size_t kRowsWorthThreads = 256;

 private:
  int find(int i) {
    while (parent_[static_cast<std::size_t>(i)] != i) {
      parent_[static_cast<std::size_t>(i)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(i)])];
      i = parent_[static_cast<std::size_t>(i)];
    }
    return i;
  }
  static bool isDynamic(const std::vector<SolverBody>& bodies, int i) {
    return i >= 0 && bodies[static_cast<std::size_t>(i)].dynamic;
  }

  // Per row: its entry in the friction table (when `friction`), the third
  // bodies' and the second-order terms' tables, −1 for none.
  void index(const RowSet& set, bool friction) {
    indexTable(friction ? std::span<const FrictionLink>(set.friction) : std::span<const FrictionLink>(), set.size(),
               frictionOf_);
    indexTable(std::span<const ThirdBody>(set.thirdBodies), set.size(), thirdOf_);
    indexTable(std::span<const SecondOrder>(set.secondOrder), set.size(), secondOrderOf_);
  }
  template <class Entry>
  static void indexTable(std::span<const Entry> table, std::size_t rows, std::vector<int>& entryOf) {
    assignGrowing(entryOf, rows, -1);
    for (std::size_t k = 0; k < table.size(); ++k)
      entryOf[static_cast<std::size_t>(table[k].row)] = static_cast<int>(k);
  }
  [[nodiscard]] const ThirdBody* thirdBodyOf(const RowSet& set, std::size_t row) const {
    const int k = thirdOf_[row];
    return k < 0 ? nullptr : &set.thirdBodies[static_cast<std::size_t>(k)];
  }

  void partition(const RowSet& set, const std::vector<SolverBody>& bodies);

  // What one thread needs to solve an island: its problem, its bodies'
  // local indices and a solver (worker 0: the simulation's own).
  struct Worker {
    std::vector<int> local, islandBodies, rowLocal;
    IslandProblem problem;
    std::vector<Vec6d> velocityChange;
    Solver* solver = nullptr;
    ref_ptr<Solver> copy;  ///< workers after the first: their copy of the simulation's solver
  };

  // Workers for `workers`' threads with solvers like `solver`; how many of
  // them to use (1 when the islands are to be solved one after another).
  int prepareWorkers(const RowSet& set, Solver& solver, WorkerPool* workers);

  // Runs island(k, worker) for every island, on `count` workers.
  template <class F>
  void forEachIsland(WorkerPool* workers, int count, const F& island) {
    if (count > 1)
      workers->forEach(islands_.size(), island);
    else
      for (std::size_t k = 0; k < islands_.size(); ++k) island(k, 0);
  }

  // The island's entries, impulses and guesses zero (index() first).
  void buildProblem(Worker& worker, const RowSet& set, const std::vector<SolverBody>& bodies,
                    const std::vector<int>& island, double h) const;

  // Adds M⁻¹Gᵀ Λ of the worker's impulses to a field of its island's bodies.
  static void addToBodies(Worker& worker, std::vector<SolverBody>& bodies, Vec6d SolverBody::*field) {
    worker.problem.velocityChange(worker.velocityChange);
    for (std::size_t k = 0; k < worker.islandBodies.size(); ++k)
      bodies[static_cast<std::size_t>(worker.islandBodies[k])].*field += worker.velocityChange[k];
  }

  // The inverse of a symmetric 3×3 matrix, NaN when it is not positive definite.
  static Mat3d inverseOf(const Mat3d& m);

  std::vector<int> parent_, islandOfRoot_, nonFiniteBodies_, frictionOf_, thirdOf_, secondOrderOf_;
  std::vector<std::vector<int>> islands_;
  std::vector<std::vector<int>> spareIslands_;  ///< the last step's islands' storage, emptied
  std::vector<Worker> workers_;
  /// Per island of the running solve: its statistics, and its bodies when
  /// its impulses came out non-finite.
  std::vector<SolverStatistics> islandStatistics_;
  std::vector<double> islandWork_;  ///< direct work of each island in this step's solves
  std::vector<std::vector<int>> nonFiniteOf_;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE void IslandStepper::project(const RowSet& set, std::vector<SolverBody>& bodies, double h, Solver& solver,
                                         SolverStatistics& statistics, WorkerPool* workers) {
  const std::vector<Row>& rows = set.rows;
  index(set, false);
  partition(set, bodies);
  const int count = prepareWorkers(set, solver, workers);
  islandStatistics_.assign(islands_.size(), SolverStatistics{});
  forEachIsland(workers, count, [&](std::size_t k, int w) {
    Worker& worker = workers_[static_cast<std::size_t>(w)];
    const std::vector<int>& island = islands_[k];
    buildProblem(worker, set, bodies, island, h);
    for (std::size_t i = 0; i < island.size(); ++i) {
      const Row& r = rows[static_cast<std::size_t>(island[i])];
      IslandProblem::Entry& e = worker.problem.rows[i];
      const double mobility = e.diagonal - e.sigma;
      e.q = r.speed - r.violation;  // speed carries the target violation here
      e.sigma = 1e-9 * mobility;
      e.diagonal = mobility + e.sigma;
      e.lower = -std::numeric_limits<double>::infinity();
      e.upper = std::numeric_limits<double>::infinity();
    }
    worker.solver->project(worker.problem, islandStatistics_[k]);
    worker.problem.velocityChange(worker.velocityChange);
    // The projection is linearized: it turns a body by at most
    // kMostProjectionTurn, all of its island's displacements scaled alike.
    double turn = 0.0;
    for (const Vec6d& change : worker.velocityChange) turn = std::max(turn, change.tail<3>().norm());
    const double share = turn > kMostProjectionTurn ? kMostProjectionTurn / turn : 1.0;
    for (std::size_t b = 0; b < worker.islandBodies.size(); ++b)
      bodies[static_cast<std::size_t>(worker.islandBodies[b])].displacement += share * worker.velocityChange[b];
  });
  for (const SolverStatistics& island : islandStatistics_) statistics.addIsland(island);
}

SPOOK_INLINE void IslandStepper::solve(RowSet& set, std::vector<SolverBody>& bodies, double h, Solver& solver,
                                       SolverStatistics& statistics, WorkerPool* workers, bool again) {
  std::vector<double>& impulses = set.impulses;
  index(set, true);
  partition(set, bodies);
  const int count = prepareWorkers(set, solver, workers);
  islandStatistics_.assign(islands_.size(), SolverStatistics{});
  nonFiniteOf_.resize(islands_.size());
  // The same rows partition into the same islands, in the same order.
  if (!again || islandWork_.size() != islands_.size()) islandWork_.assign(islands_.size(), 0.0);
  const bool warmStart = solver.getEnableWarmStarting();
  const bool contactWarmStart = solver.getEnableContactWarmStarting();
  const double contactFactor = solver.getContactWarmStartingFactor();
  forEachIsland(workers, count, [&](std::size_t k, int w) {
    Worker& worker = workers_[static_cast<std::size_t>(w)];
    const std::vector<int>& island = islands_[k];
    buildProblem(worker, set, bodies, island, h);
    for (std::size_t i = 0; i < island.size(); ++i) {
      IslandProblem::Entry& e = worker.problem.rows[i];
      e.guess = std::clamp(impulses[static_cast<std::size_t>(island[i])], e.lower, e.upper);
      if (warmStart)
        e.impulse = e.guess;
      else if (contactWarmStart && e.constraint < 0 && e.bounded())
        e.impulse = std::clamp(contactFactor * e.guess, e.lower, e.upper);
      else
        e.impulse = std::clamp(0.0, e.lower, e.upper);
    }
    nonFiniteOf_[k].clear();
    if (!worker.solver->solve(worker.problem, islandStatistics_[k], islandWork_[k]))
      nonFiniteOf_[k] = worker.islandBodies;
    islandWork_[k] += islandStatistics_[k].directWork;
    for (std::size_t i = 0; i < island.size(); ++i)
      impulses[static_cast<std::size_t>(island[i])] = worker.problem.rows[i].impulse;
    addToBodies(worker, bodies, &SolverBody::freeVelocity);
  });
  nonFiniteBodies_.clear();
  for (std::size_t k = 0; k < islands_.size(); ++k) {
    statistics.addIsland(islandStatistics_[k]);
    nonFiniteBodies_.insert(nonFiniteBodies_.end(), nonFiniteOf_[k].begin(), nonFiniteOf_[k].end());
  }
}

SPOOK_INLINE int IslandStepper::prepareWorkers(const RowSet& set, Solver& solver, WorkerPool* workers) {
  const bool worthIt = workers && workers->size() > 1 && islands_.size() > 1 && set.size() >= kRowsWorthThreads;
  const std::size_t count = worthIt ? std::size_t(workers->size()) : 1;
  if (workers_.size() < count) workers_.resize(count);
  workers_[0].solver = &solver;
  for (std::size_t w = 1; w < count; ++w) {
    ref_ptr<Solver>& copy = workers_[w].copy;
    if (const Solver* kept = copy.get(); !kept || typeid(*kept) != typeid(solver)) copy = solver.makeWorker();
    if (!copy) return 1;  // a policy without worker copies
    copy->copySettings(solver);
    workers_[w].solver = copy.get();
  }
  return int(count);
}

SPOOK_INLINE void IslandStepper::partition(const RowSet& set, const std::vector<SolverBody>& bodies) {
  const std::vector<Row>& rows = set.rows;
  resizeGrowing(parent_, bodies.size());
  std::iota(parent_.begin(), parent_.end(), 0);
  const auto join = [&](int a, int b) {
    if (isDynamic(bodies, a) && isDynamic(bodies, b)) parent_[static_cast<std::size_t>(find(a))] = find(b);
  };
  for (const Row& r : rows) join(r.body1, r.body2);
  for (const ThirdBody& t : set.thirdBodies) {
    const Row& r = rows[static_cast<std::size_t>(t.row)];
    join(r.body1, t.body);
    join(r.body2, t.body);
  }
  assignGrowing(islandOfRoot_, bodies.size(), -1);
  for (std::vector<int>& island : islands_) {
    island.clear();
    spareIslands_.push_back(std::move(island));
  }
  islands_.clear();
  for (int i = 0; i < static_cast<int>(rows.size()); ++i) {
    const Row& r = rows[static_cast<std::size_t>(i)];
    const ThirdBody* third = thirdBodyOf(set, static_cast<std::size_t>(i));
    const int body3 = third ? third->body : -1;
    const int body = isDynamic(bodies, r.body1)   ? r.body1
                     : isDynamic(bodies, r.body2) ? r.body2
                     : isDynamic(bodies, body3)   ? body3
                                                  : -1;
    if (body < 0) continue;
    int& island = islandOfRoot_[static_cast<std::size_t>(find(body))];
    if (island < 0) {
      island = static_cast<int>(islands_.size());
      if (spareIslands_.empty()) {
        islands_.emplace_back();
      } else {
        islands_.push_back(std::move(spareIslands_.back()));
        spareIslands_.pop_back();
      }
    }
    islands_[static_cast<std::size_t>(island)].push_back(i);
  }
}

SPOOK_INLINE void IslandStepper::buildProblem(Worker& worker, const RowSet& set, const std::vector<SolverBody>& bodies,
                                              const std::vector<int>& island, double h) const {
  std::vector<int>& local = worker.local;
  std::vector<int>& islandBodies = worker.islandBodies;
  std::vector<int>& rowLocal = worker.rowLocal;
  IslandProblem& problem = worker.problem;
  const std::vector<Row>& rows = set.rows;
  resizeGrowing(local, bodies.size(), -1);
  islandBodies.clear();
  auto localIndex = [&](int body) {
    if (!isDynamic(bodies, body)) return -1;
    int& l = local[static_cast<std::size_t>(body)];
    if (l < 0) {
      l = static_cast<int>(islandBodies.size());
      islandBodies.push_back(body);
    }
    return l;
  };
  resizeGrowing(rowLocal, rows.size(), -1);
  for (std::size_t k = 0; k < island.size(); ++k) rowLocal[static_cast<std::size_t>(island[k])] = static_cast<int>(k);
  const auto localRow = [&](int i) { return i < 0 ? -1 : rowLocal[static_cast<std::size_t>(i)]; };
  resizeGrowing(problem.rows, island.size());
  problem.extraBodies.clear();
  for (std::size_t k = 0; k < island.size(); ++k) {
    const Row& r = rows[static_cast<std::size_t>(island[k])];
    const int link = frictionOf_[static_cast<std::size_t>(island[k])];
    const FrictionLink* f = link < 0 ? nullptr : &set.friction[static_cast<std::size_t>(link)];
    const ThirdBody* third = thirdBodyOf(set, static_cast<std::size_t>(island[k]));
    IslandProblem::Entry& e = problem.rows[k];
    e.body1 = e.body2 = e.extra = -1;
    // G v and G v* over every body (kinematic ones move too), M⁻¹Gᵀ over
    // the dynamic ones.
    double speed = 0.0, freeSpeed = 0.0;
    const std::array<std::pair<int, const Vec6d*>, 3> blocks{
        {{r.body1, &r.J1}, {r.body2, &r.J2}, {third ? third->body : -1, third ? &third->J : nullptr}}};
    for (const auto& [body, J] : blocks) {
      if (body < 0) continue;
      const SolverBody& b = bodies[static_cast<std::size_t>(body)];
      speed += J->dot(b.velocity);
      freeSpeed += J->dot(b.freeVelocity);
      if (b.dynamic) problem.addBody(e, localIndex(body), *J, b.inverseMass, b.inverseInertia);
    }
    const double mobility = problem.mobility(e);
    if (r.holonomic) {
      const SpookParameters spook = SpookParameters::holonomic(r.compliance, r.damping, h);
      // Second order in h (row.hpp): the b' term reads the rate at which
      // the last step moved g (G v − hκ when not kept); the step aims G v⁺
      // at SPOOK's target minus the drift hκ its motion will add.
      const int term = secondOrderOf_[static_cast<std::size_t>(island[k])];
      const SecondOrder second = term < 0 ? SecondOrder{} : set.secondOrder[static_cast<std::size_t>(term)];
      const double rate = std::isnan(second.lastRate) ? speed - h * second.curvature : second.lastRate;
      e.q = -spook.a * r.violation + spook.b * rate - h * second.curvature - freeSpeed;
      e.sigma = spook.sigma;
    } else {
      e.q = r.speed - freeSpeed;
      e.sigma = SpookParameters::velocitySigma(r.compliance, h);
    }
    // A floor far below any physical compliance keeps redundant rigid rows
    // (compliance 0) positive definite; contact friction rows get a
    // higher one (kFrictionSofterThan).
    e.sigma = std::max(e.sigma, (f && f->normal >= 0 && !f->exact ? kFrictionSofterThan : 1e-12) * mobility);
    e.diagonal = mobility + e.sigma;
    e.lower = r.lower * h;
    e.upper = r.upper * h;
    e.guess = 0.0;
    e.impulse = 0.0;
    e.solveType = r.solveType;
    e.constraint = localRow(r.constraint);
    e.normal = f ? localRow(f->normal) : -1;
    e.partner = f ? localRow(f->partner) : -1;
    e.mu = f ? f->coefficient : 0.0;
    e.frictionBound = f ? f->bound : FrictionBound::FIXED;
    e.coneShare = 1.0;
  }
  problem.numBodies = static_cast<int>(islandBodies.size());
  // Mass matrices only where a direct solve may go through body space.
  resizeGrowing(problem.mass, BodySpaceSolve::outnumbers(island.size(), islandBodies.size()) ? islandBodies.size() : 0);
  for (std::size_t k = 0; k < problem.mass.size(); ++k) {
    const SolverBody& b = bodies[static_cast<std::size_t>(islandBodies[k])];
    Mat6d& M = problem.mass[k];
    M.setZero();
    M.topLeftCorner<3, 3>() = inverseOf(b.inverseMass);
    M.bottomRightCorner<3, 3>() = inverseOf(b.inverseInertia);
  }
  for (int body : islandBodies) local[static_cast<std::size_t>(body)] = -1;
}

SPOOK_INLINE Mat3d IslandStepper::inverseOf(const Mat3d& m) {
  Mat3d inverse;
  if (!invertByCholesky<3>(m, inverse)) return Mat3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return inverse;
}
#endif

}  // namespace spook::detail
