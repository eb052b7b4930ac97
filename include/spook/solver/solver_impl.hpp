#pragma once

// The solves of the solver policies (solver.hpp): non-template code, inline
// in a header-only program and compiled once otherwise
// (SPOOK_INLINE, core/implementation.hpp).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <memory>
#include <vector>

#include <spook/solver/direct_solve.hpp>
#include <spook/solver/friction_bounds.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/iterative_solve.hpp>
#include <spook/solver/solver.hpp>

namespace spook {

SPOOK_INLINE Solver::Solver() : direct_(std::make_unique<detail::DirectSolve>()) {}

SPOOK_INLINE Solver::~Solver() = default;

SPOOK_INLINE void Solver::project(detail::IslandProblem& problem, SolverStatistics& statistics) {
  const auto start = std::chrono::steady_clock::now();
  pivotBudget_ = islandPivotBudget();
  workBudget_ = maxDirectWork_;
  islandMatrixKnown_ = false;
  direct(problem, allRows(problem), statistics);
  for (auto& e : problem.rows)
    if (!std::isfinite(e.impulse)) e.impulse = 0.0;
  statistics.solveTime += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SPOOK_INLINE bool Solver::solve(detail::IslandProblem& problem, SolverStatistics& statistics, double workSpent) {
  const auto start = std::chrono::steady_clock::now();
  pivotBudget_ = islandPivotBudget();
  workBudget_ = maxDirectWork_ - workSpent;
  islandMatrixKnown_ = false;
  ++statistics.numIslands;
  statistics.numRows += static_cast<int>(problem.rows.size());
  solveIsland(problem, statistics);
  bool finite = true;
  for (const auto& e : problem.rows) finite = finite && std::isfinite(e.impulse);
  if (!finite) {
    for (auto& e : problem.rows) e.impulse = 0.0;
    ++statistics.nonFiniteIslands;
    statistics.converged = false;
  }
  statistics.complementarityError = std::max(statistics.complementarityError, complementarityError(problem));
  statistics.solveTime += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return finite;
}

SPOOK_INLINE void Solver::direct(detail::IslandProblem& problem, const std::vector<int>& subset, SolverStatistics& statistics) {
  const detail::DirectSolveResult r = direct_->solve(problem, subset, std::clamp(pivotBudget_ - 1, 0, maxPivotSteps_),
                                                     /*safeAnswer=*/true, workBudget_, islandMatrixKnown_);
  islandMatrixKnown_ = true;
  pivotBudget_ -= r.factorizations;
  workBudget_ -= r.work;
  statistics.factorizations += r.factorizations;
  statistics.directWork += r.work;
  statistics.converged = statistics.converged && r.converged;
  statistics.directFallbacks += r.fellBack ? 1 : 0;
}

SPOOK_INLINE bool Solver::directAttempt(detail::IslandProblem& problem, const std::vector<int>& subset,
                                               SolverStatistics& statistics) {
  if (pivotBudget_ <= 0 || workBudget_ <= 0.0) return false;
  const std::vector<detail::IslandProblem::Entry> saved = problem.entries(subset);
  // A solve capped at m pivot steps factorizes up to m + 1 times.
  const detail::DirectSolveResult r = direct_->solve(problem, subset, std::min(pivotBudget_ - 1, maxPivotSteps_),
                                                     /*safeAnswer=*/false, workBudget_, islandMatrixKnown_);
  islandMatrixKnown_ = true;
  pivotBudget_ -= r.factorizations;
  workBudget_ -= r.work;
  statistics.factorizations += r.factorizations;
  statistics.directWork += r.work;
  if (!r.fellBack) return true;
  problem.restore(subset, saved);
  return false;
}

SPOOK_INLINE bool Solver::directWithFriction(detail::IslandProblem& problem, const std::vector<int>& subset,
                                                    SolverStatistics& statistics, const std::vector<char>* keep,
                                                    bool first) {
  std::vector<int> following;
  for (int i : subset) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    if (!e.followsNormal() || (keep && (*keep)[static_cast<std::size_t>(i)])) continue;
    following.push_back(i);
  }
  if (first) {
    const int fallbacks = statistics.directFallbacks;
    direct(problem, subset, statistics);
    // A solve that fell back will fall back again on the next bounds: stop.
    if (statistics.directFallbacks != fallbacks) return false;
  } else if (!directAttempt(problem, subset, statistics)) {
    return false;
  }
  int k = 1;
  for (; k < frictionIterations_ && !following.empty(); ++k) {
    const std::vector<detail::IslandProblem::Entry> before = problem.entries(following);
    double change = detail::updateConeDirections(problem, following);
    change = std::max(change, detail::applyFrictionBounds(problem, following));
    double largest = 0.0;
    for (int i : following) largest = std::max(largest, problem.rows[static_cast<std::size_t>(i)].upper);
    if (change <= frictionTolerance_ * largest) break;
    if (!directAttempt(problem, subset, statistics)) {
      // The budget ran out: the last converged answer stands, with the
      // bounds (and cone directions) it was solved with.
      problem.restore(following, before);
      ++statistics.pivotBudgetCuts;
      break;
    }
  }
  statistics.frictionIterations = std::max(statistics.frictionIterations, k);
  return true;
}

SPOOK_INLINE void Solver::iterative(detail::IslandProblem& problem, const std::vector<int>& subset,
                                    SolverStatistics& statistics, int sweeps) const {
  const detail::IterativeSolveResult r =
      detail::iterativeSolve(problem, subset, sweeps > 0 ? sweeps : iterations_, tolerance_, method_ == JACOBI);
  statistics.iterations = std::max(statistics.iterations, r.iterations);
  statistics.converged = statistics.converged && r.converged;
}

SPOOK_INLINE std::vector<int> Solver::allRows(const detail::IslandProblem& problem) {
  std::vector<int> rows(problem.rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<int>(i);
  return rows;
}

SPOOK_INLINE double Solver::complementarityError(const detail::IslandProblem& problem) {
  const std::vector<detail::Vec6d> dv = problem.velocityChange();
  const auto residual = [&](int i) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    return problem.rowVelocity(i, dv) + e.sigma * e.impulse - e.q;
  };
  double worst = 0.0;
  for (int i = 0; i < static_cast<int>(problem.rows.size()); ++i) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    if (e.frictionBound == detail::FrictionBound::CONE && e.partner >= 0) {
      if (e.partner > i)
        worst = std::max(worst, detail::coneComplementarityError(e, problem.rows[static_cast<std::size_t>(e.partner)],
                                                                 detail::frictionLimit(problem, e), residual(i),
                                                                 residual(e.partner)));
      continue;
    }
    worst = std::max(worst, detail::complementarityError(e, residual(i)));
  }
  return worst;
}

SPOOK_INLINE void Solver::copySettings(const Solver& other) {
  iterations_ = other.iterations_;
  tolerance_ = other.tolerance_;
  method_ = other.method_;
  maxPivotSteps_ = other.maxPivotSteps_;
  maxDirectWork_ = other.maxDirectWork_;
  postStabilization_ = other.postStabilization_;
  warmStarting_ = other.warmStarting_;
  contactWarmStarting_ = other.contactWarmStarting_;
  contactWarmStartingFactor_ = other.contactWarmStartingFactor_;
  geometricStiffness_ = other.geometricStiffness_;
  geometricStiffnessThreshold_ = other.geometricStiffnessThreshold_;
  projectionIterations_ = other.projectionIterations_;
  frictionIterations_ = other.frictionIterations_;
  frictionTolerance_ = other.frictionTolerance_;
  couplingIterations_ = other.couplingIterations_;
  couplingTolerance_ = other.couplingTolerance_;
  couplingSweeps_ = other.couplingSweeps_;
}

namespace detail {
template <class Policy>
ref_ptr<Solver> workerLike(const Policy& policy) {
  ref_ptr<Solver> worker = new Policy();
  worker->copySettings(policy);
  return worker;
}
}  // namespace detail

SPOOK_INLINE ref_ptr<Solver> DirectSolver::makeWorker() const { return detail::workerLike(*this); }
SPOOK_INLINE ref_ptr<Solver> IterativeSolver::makeWorker() const { return detail::workerLike(*this); }
SPOOK_INLINE ref_ptr<Solver> HybridSolver::makeWorker() const { return detail::workerLike(*this); }

SPOOK_INLINE void DirectSolver::solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) {
  const std::vector<int> rows = allRows(problem);
  statistics.numDirectRows += static_cast<int>(rows.size());
  directWithFriction(problem, rows, statistics);
}

SPOOK_INLINE void IterativeSolver::solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) {
  const std::vector<int> rows = allRows(problem);
  statistics.numIterativeRows += static_cast<int>(rows.size());
  iterative(problem, rows, statistics);
}

SPOOK_INLINE void HybridSolver::solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) {
  std::vector<int> directRows, iterativeRows;
  std::vector<char> keep(problem.rows.size(), 0);
  bool anyIterativeOnly = false;
  for (int i = 0; i < static_cast<int>(problem.rows.size()); ++i) {
    const auto& e = problem.rows[static_cast<std::size_t>(i)];
    const bool friction = e.normal >= 0;
    const bool split = e.solveType == SolveType::SPLIT;
    const bool inDirect = e.solveType != SolveType::ITERATIVE && !(split && friction);
    const bool inIterative = e.solveType != SolveType::DIRECT && !(split && !friction);
    if (inDirect) directRows.push_back(i);
    if (inIterative) iterativeRows.push_back(i);
    anyIterativeOnly = anyIterativeOnly || (inIterative && !inDirect);
    keep[static_cast<std::size_t>(i)] = friction && e.solveType == SolveType::DIRECT_AND_ITERATIVE;
  }
  statistics.numDirectRows += static_cast<int>(directRows.size());
  if (!anyIterativeOnly) {
    directWithFriction(problem, directRows, statistics);
    return;
  }
  statistics.numIterativeRows += static_cast<int>(iterativeRows.size());
  if (directRows.empty()) {
    iterative(problem, iterativeRows, statistics);
    return;
  }
  bool directHeld = directWithFriction(problem, directRows, statistics);
  std::vector<double> previous(directRows.size());
  // A direct pass that fell back (its pivoting cap reached), or that the
  // pivot budget cut short (the last pass's answer then stands), would only
  // repeat at the next coupling pass: the step then ends with one
  // iterative pass over every row, which bounds its cost. It sweeps the
  // direct rows too: their last answer was solved against the friction
  // before it, and the friction moved since (a pile of 1,000 spheres whose
  // every step ran out of its work budget sank 18 mm deep with the normals
  // held; 16 sweeps of iterative alone hold it to 5 mm).
  for (int pass = 0; directHeld && pass < getNumCouplingIterations(); ++pass) {
    iterative(problem, iterativeRows, statistics, pass == 0 ? 0 : getNumCouplingSweeps());
    detail::freezeConeShares(problem, iterativeRows, keep);
    detail::applyFrictionBounds(problem, iterativeRows);
    double largest = 0.0;
    for (std::size_t k = 0; k < directRows.size(); ++k) {
      previous[k] = problem.rows[static_cast<std::size_t>(directRows[k])].impulse;
      largest = std::max(largest, std::abs(previous[k]));
    }
    directHeld = directWithFriction(problem, directRows, statistics, &keep, false);
    if (!directHeld) ++statistics.pivotBudgetCuts;
    double change = 0.0;
    for (std::size_t k = 0; k < directRows.size(); ++k)
      change = std::max(change, std::abs(problem.rows[static_cast<std::size_t>(directRows[k])].impulse - previous[k]));
    if (change <= getCouplingTolerance() * largest) break;
  }
  if (!directHeld) {
    std::vector<int> every;
    std::set_union(directRows.begin(), directRows.end(), iterativeRows.begin(), iterativeRows.end(),
                   std::back_inserter(every));
    iterative(problem, every, statistics);
    return;
  }
  // The direct pass moved the normals after the Gauss–Seidel friction.
  detail::clampFrictionToNormals(problem, iterativeRows);
}

}  // namespace spook
