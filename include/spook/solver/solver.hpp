#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/solver/row.hpp>

namespace spook {

namespace detail {
struct IslandProblem;
class DirectSolve;
}  // namespace detail

/// What the solver did in the last step, summed or maximized over islands.
struct SolverStatistics {
  int numIslands = 0;
  int numRows = 0;
  int numDirectRows = 0;     ///< rows that went through a direct solve
  int numIterativeRows = 0;  ///< rows that went through projected Gauss–Seidel
  int iterations = 0;        ///< most Gauss–Seidel (or Jacobi) sweeps in one island
  /// Pivoting steps of the direct solves, each a solve of its free rows: a
  /// sparse factorization, or the last one's factor where the step changed
  /// few rows of its matrix (free_set_update.hpp, body_space_solve.hpp).
  int factorizations = 0;
  /// Multiply-adds of those factorizations, as their symbolic analysis
  /// counts them (a factor updated instead is counted as factorized), plus
  /// in row space the rows' work in each pivot step
  /// (Solver::kDirectRowWork): what Solver::setMaxDirectWork bounds.
  double directWork = 0.0;
  /// Most friction iterations of one direct solve (getNumFrictionIterations);
  /// reaching the maximum means its bounds had not settled to the tolerance.
  int frictionIterations = 0;
  /// Largest complementarity error over all rows (m/s or rad/s): |w| for a
  /// row inside its bounds, the wrong-signed part of w at a bound, with
  /// w = (S+Σ)Λ − q (PHYSICS.md §2.1). Zero to round-off for a direct solve.
  double complementarityError = 0.0;
  bool converged = true;   ///< every pivoting solve found its solution, every sweep met the tolerance
  /// Direct solves whose pivoting reached getMaxPivotSteps and that fell back
  /// to the safe answer (direct_solve.hpp): the best iterate or no impulse,
  /// refined by Gauss–Seidel.
  int directFallbacks = 0;
  double solveTime = 0.0;  ///< wall-clock time spent solving (s)
  /// Islands whose impulses were not finite and were dropped; the
  /// simulation freezes their bodies (SimulationStatisticsT::frozenBodies).
  int nonFiniteIslands = 0;
  /// Friction iterations and hybrid coupling passes left out because the
  /// island's pivot budget (Solver::getMaxPivotSteps) ran out.
  int pivotBudgetCuts = 0;
  /// Solves repeated because the geometric stiffness of the forces found
  /// exceeded the one solved with (geometric_stiffness.hpp).
  int geometricStiffnessResolves = 0;

  /// Takes in a repeated solve of the same rows: its work adds up, its
  /// answer's figures replace the last ones.
  void addResolve(const SolverStatistics& again) {
    iterations = std::max(iterations, again.iterations);
    factorizations += again.factorizations;
    directWork += again.directWork;
    frictionIterations = std::max(frictionIterations, again.frictionIterations);
    complementarityError = again.complementarityError;
    converged = again.converged;
    directFallbacks += again.directFallbacks;
    pivotBudgetCuts += again.pivotBudgetCuts;
    solveTime += again.solveTime;
    nonFiniteIslands = again.nonFiniteIslands;
    ++geometricStiffnessResolves;
  }

  /// Takes in another island's solve of the same step: counts add up,
  /// maxima stay maxima.
  void addIsland(const SolverStatistics& island) {
    numIslands += island.numIslands;
    numRows += island.numRows;
    numDirectRows += island.numDirectRows;
    numIterativeRows += island.numIterativeRows;
    iterations = std::max(iterations, island.iterations);
    factorizations += island.factorizations;
    directWork += island.directWork;
    frictionIterations = std::max(frictionIterations, island.frictionIterations);
    complementarityError = std::max(complementarityError, island.complementarityError);
    converged = converged && island.converged;
    directFallbacks += island.directFallbacks;
    solveTime += island.solveTime;
    nonFiniteIslands += island.nonFiniteIslands;
    pivotBudgetCuts += island.pivotBudgetCuts;
    geometricStiffnessResolves += island.geometricStiffnessResolves;
  }
};

/// Solves the rows of an island: the simulation's solver policy. Subclasses
/// choose how (DirectSolver, IterativeSolver, HybridSolver); the settings of
/// the iterative and pivoting parts are common.
class Solver : public Referenced {
 public:
  enum IterativeMethod { GAUSS_SEIDEL, JACOBI };

  [[nodiscard]] virtual const char* getName() const = 0;

  /// Sweeps of projected Gauss–Seidel per step (default 16, AGX's resting iterations).
  [[nodiscard]] int getNumIterations() const { return iterations_; }
  void setNumIterations(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "number of iterations must be >= 1", n);
    iterations_ = n;
  }
  /// Sweeps stop early when no impulse changes by more than this, measured
  /// as a velocity (m/s or rad/s). Default 1e-10.
  [[nodiscard]] double getTolerance() const { return tolerance_; }
  void setTolerance(double tolerance) {
    if (!(tolerance >= 0.0)) throw detail::makeError("Solver", getName(), "tolerance must be >= 0 (m/s)", tolerance);
    tolerance_ = tolerance;
  }
  /// Start each solve from the last step's impulses (default off). It saves
  /// sweeps on slowly changing systems, but with few sweeps on stiff, badly
  /// conditioned joints (a light body with small inertia far from its joint)
  /// the stale impulses feed energy into the system and it can blow up;
  /// AGX leaves warm starting off by default too (PHYSICS.md §2.2).
  [[nodiscard]] bool getEnableWarmStarting() const { return warmStarting_; }
  void setEnableWarmStarting(bool enable) { warmStarting_ = enable; }
  /// Start the contacts' rows (a contact point's normal and friction rows:
  /// the bounded rows outside any constraint) from the impulses their
  /// persisting points carried in the last step, scaled by
  /// getContactWarmStartingFactor (default on). A resting contact's force
  /// changes little from step to step, and Gauss–Seidel settles a pile's
  /// contacts from there instead of building them up again from zero every
  /// step: at 64 sweeps it holds a 210-cube pyramid to 2.9 cm where it slid
  /// 16 cm cold (README); the hybrid solver's Gauss–Seidel friction (SPLIT)
  /// starts warm too, which halves its direct solves on that pyramid. Joint
  /// rows are not affected (setEnableWarmStarting).
  [[nodiscard]] bool getEnableContactWarmStarting() const { return contactWarmStarting_; }
  void setEnableContactWarmStarting(bool enable) { contactWarmStarting_ = enable; }
  /// The share of the last step's contact impulses a solve starts from, in
  /// [0, 1] (default 0.85). Below 1 the start forgets the friction a jammed
  /// or statically indeterminate contact set locked in, by a factor per step
  /// (0.85: to a tenth in 14 steps); a full start let a motor-driven crank
  /// jammed against its coupler tear its joints open (tests).
  [[nodiscard]] double getContactWarmStartingFactor() const { return contactWarmStartingFactor_; }
  void setContactWarmStartingFactor(double factor) {
    if (!(factor >= 0.0 && factor <= 1.0))
      throw detail::makeError("Solver", getName(), "contact warm starting factor must be in [0, 1]", factor);
    contactWarmStartingFactor_ = factor;
  }
  /// Geometric stiffness (default on): the turning of the joint forces with
  /// the bodies is taken implicitly, from the last step's forces, for every
  /// body whose explicit step would be unstable. It keeps light bodies pulled
  /// by heavy ones stable (a 1 kg link holding 1e6 kg at 60 Hz), at the price
  /// of backward Euler's damping of the swing those bodies take part in
  /// (geometric_stiffness.hpp). Bodies below the threshold are untouched.
  [[nodiscard]] bool getEnableGeometricStiffness() const { return geometricStiffness_; }
  void setEnableGeometricStiffness(bool enable) { geometricStiffness_ = enable; }
  /// ρ₀ of the geometric stiffness: a body whose (hω)² from its joint forces
  /// exceeds ρ₀ gets the implicit term with weight 1 − ρ₀/(hω)². Default 1
  /// (the explicit step is stable to (hω)² = 4); 0 applies it to every body
  /// at full weight, which tracks the joints of a swinging chain closest.
  [[nodiscard]] double getGeometricStiffnessThreshold() const { return geometricStiffnessThreshold_; }
  void setGeometricStiffnessThreshold(double threshold) {
    if (!(threshold >= 0.0 && std::isfinite(threshold)))
      throw detail::makeError("Solver", getName(), "geometric stiffness threshold must be finite and >= 0", threshold);
    geometricStiffnessThreshold_ = threshold;
  }
  [[nodiscard]] IterativeMethod getIterativeMethod() const { return method_; }
  void setIterativeMethod(IterativeMethod method) {
    if (method != GAUSS_SEIDEL && method != JACOBI)
      throw detail::makeError("Solver", getName(), "unknown iterative method", static_cast<int>(method));
    method_ = method;
  }
  /// Pivoting steps (factorizations) of one direct solve (default 80); an
  /// island's solves in a step take 1.5 times as many in all: its first
  /// solve, its friction iterations and the hybrid's coupling passes
  /// (islandPivotBudget). A first solve that reaches the cap falls back to
  /// its safe answer (direct_solve.hpp), counted in
  /// SolverStatistics::directFallbacks; a later one that would exceed the
  /// budget is dropped and the last converged answer stands, with the
  /// friction bounds it was solved with (SolverStatistics::pivotBudgetCuts).
  /// Converging solves of a 210-cube pyramid take 3-10 steps; in float its
  /// eight friction iterations took up to 211 factorizations in a step
  /// (0.59 s) before the budget bounded them at 121 (0.39 s, the same
  /// 1.1e-6 m of drift; bench/brick_pyramids).
  [[nodiscard]] int getMaxPivotSteps() const { return maxPivotSteps_; }
  void setMaxPivotSteps(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "maximum pivot steps must be >= 1", n);
    maxPivotSteps_ = n;
  }
  /// The work of a direct pivot step in row space (chains, wires, jointed
  /// islands) beyond its factorization, counted in multiply-adds a row:
  /// the residuals, bounds and solves over its rows and the sparse
  /// bookkeeping. A chain's factor takes ~40 multiply-adds a row, its
  /// pivot step 300-700 ns a row (Release, 2026-12-06): counted by its
  /// factor alone, a 1,715-node wire ran 0.28 s a step on 2.3e7
  /// multiply-adds, 30 times a 3D pile's time for the same count. In body
  /// space (piles, pyramids) the factor of 6x6 blocks outweighs the rows
  /// and is counted alone.
  static constexpr double kDirectRowWork = 256.0;
  /// The work the direct solves of one island may do in a step's solve
  /// (its geometric-stiffness re-solves share it; the post-stabilization's
  /// projection has one of its own), in multiply-adds of their
  /// factorizations as the symbolic analysis counts them plus, in row
  /// space, kDirectRowWork a row for each pivot step
  /// (SolverStatistics::directWork), default 3e8: 0.15-0.6 s of one 2026
  /// x86 core at most (0.46-2.1 ns a counted multiply-add, measured on 3D
  /// piles, pyramids, a 1,715-node wire and chains of 10-400 hinged links,
  /// whose fixed costs a solve weigh most). It bounds the cost of a step
  /// where the pivot steps alone do not: a factorization's cost grows with
  /// the fill of its matrix, about as the square of the bodies in a 3D
  /// pile (1,000 spheres poured into a box: 2-4e8 each, and the pivoting
  /// did not converge within 1e9, at up to 1 s a step; 80 steps took 8
  /// s). A first solve that cannot afford another factorization falls back
  /// to its safe answer (SolverStatistics::directFallbacks), a later one is
  /// dropped as at the pivot budget (pivotBudgetCuts). Deterministic,
  /// unlike a limit on wall-clock time.
  [[nodiscard]] double getMaxDirectWork() const { return maxDirectWork_; }
  void setMaxDirectWork(double multiplyAdds) {
    if (!(multiplyAdds > 0.0))
      throw detail::makeError("Solver", getName(), "maximum direct work must be > 0 (multiply-adds)", multiplyAdds);
    maxDirectWork_ = multiplyAdds;
  }

  /// Outer iterations of a direct solve over the friction bounds that follow
  /// the normal forces (scaled box and cone friction; PHYSICS.md §2.4's
  /// non-linear iterations): each solves the LCP exactly, then moves the
  /// bounds to μΛn of the new normal impulses and, for a cone, onto the
  /// direction of sliding. Default 8.
  [[nodiscard]] int getNumFrictionIterations() const { return frictionIterations_; }
  void setNumFrictionIterations(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "number of friction iterations must be >= 1", n);
    frictionIterations_ = n;
  }
  /// The friction iterations stop when no bound moves by more than this
  /// fraction of the largest one. Default 1e-6.
  [[nodiscard]] double getFrictionTolerance() const { return frictionTolerance_; }
  void setFrictionTolerance(double tolerance) {
    if (!(tolerance >= 0.0 && std::isfinite(tolerance)))
      throw detail::makeError("Solver", getName(), "friction tolerance must be finite and >= 0", tolerance);
    frictionTolerance_ = tolerance;
  }
  /// Hybrid solver: the most (iterative, direct) passes that couple the two
  /// subsystems of an island; they stop once the direct impulses change by
  /// less than getCouplingTolerance() of the largest. Default 16: the
  /// coupling converges linearly, and a box resting on a 30° incline under
  /// SPLIT friction creeps 4.7 mm in 2 s after AGX's 7 dry-friction
  /// iterations, 0.05 mm after 16.
  [[nodiscard]] int getNumCouplingIterations() const { return couplingIterations_; }
  void setNumCouplingIterations(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "number of coupling iterations must be >= 1", n);
    couplingIterations_ = n;
  }
  /// Hybrid solver: the coupling passes stop once no direct impulse changes
  /// by more than this fraction of the largest. Default 1e-4: at 1e-6 the
  /// 210-cube pyramid took 4.4 direct solves a step instead of 2.5, for the
  /// same drift (1.24 mm in 5 s).
  [[nodiscard]] double getCouplingTolerance() const { return couplingTolerance_; }
  void setCouplingTolerance(double tolerance) {
    if (!(tolerance >= 0.0 && std::isfinite(tolerance)))
      throw detail::makeError("Solver", getName(), "coupling tolerance must be finite and >= 0", tolerance);
    couplingTolerance_ = tolerance;
  }
  /// Hybrid solver: Gauss–Seidel sweeps of each coupling pass after the
  /// first, which start from the pass before (the first sweeps
  /// getNumIterations() times). Default 2: the passes converge together, and
  /// full sweeps in every pass spent a quarter of a settling pile's step.
  [[nodiscard]] int getNumCouplingSweeps() const { return couplingSweeps_; }
  void setNumCouplingSweeps(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "number of coupling sweeps must be >= 1", n);
    couplingSweeps_ = n;
  }

  /// Post-stabilization (on by default for DirectSolver and HybridSolver,
  /// off for IterativeSolver; one Newton iteration): after the positions
  /// are advanced, the directly solved equality rows (and slack rows held
  /// at an end) are
  /// projected, mass-weighted, onto the violation their second-order
  /// prediction gives, g* = g + h(G v⁺ + hκ) (SecondOrder::curvature):
  /// Δq = M⁻¹Gᵀδ with G M⁻¹Gᵀ δ = g* − g(q⁺), and the velocities take Δq/h.
  /// This removes the drift of the velocity-level step beyond second order,
  /// which grows with angular speed and mass ratio, and leaves the rows'
  /// compliance and damping alone: the joint catalogue holds within 1e-6 m
  /// (3e-7 m at the default compliance) where the plain step drifts
  /// 1e-4..5e-3 m. Costs one more row assembly and factorization per step.
  /// Iterative rows are not projected.
  [[nodiscard]] bool getEnablePostStabilization() const { return postStabilization_; }
  void setEnablePostStabilization(bool enable) { postStabilization_ = enable; }
  [[nodiscard]] int getNumPostStabilizationIterations() const { return postStabilization_ ? projectionIterations_ : 0; }
  void setNumPostStabilizationIterations(int n) {
    if (n < 1) throw detail::makeError("Solver", getName(), "post-stabilization iterations must be >= 1", n);
    projectionIterations_ = n;
  }
  /// Whether rows of this solve type are projected.
  [[nodiscard]] virtual bool projects(SolveType type) const { return postStabilization_ && type != SolveType::ITERATIVE; }

  /// Solves a projection island (unbounded rows) directly.
  void project(detail::IslandProblem& problem, SolverStatistics& statistics);

  /// Solves one island in place and accumulates the statistics. Impulses that
  /// come out non-finite are dropped (set to zero) and counted; false then.
  /// `workSpent`: the direct work earlier solves of the island did in this
  /// step (a re-solve's share of getMaxDirectWork is what they left).
  bool solve(detail::IslandProblem& problem, SolverStatistics& statistics, double workSpent = 0.0);

  /// A solver of the same policy and settings with a workspace of its own,
  /// for another thread's islands (SimulationT::setNumThreads); null where
  /// the policy has none (a subclass of a user's: its islands are then
  /// solved one after another). The workspace caches only what it would
  /// compute again from the same island, so either solver gives the same
  /// answer bit for bit.
  [[nodiscard]] virtual ref_ptr<Solver> makeWorker() const { return nullptr; }
  /// Takes every setting of `other` (not its workspace).
  void copySettings(const Solver& other);

 protected:
  Solver();
  // Its virtual members are declared SPOOK_INLINE, as in its subclasses: a
  // class whose virtual functions are all inline has no key function, so a
  // header-only translation unit emits the virtual table, and the solves
  // behind it, only where a solver is constructed, not in every file that
  // includes spook.
  SPOOK_INLINE ~Solver() override;
  virtual void solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) = 0;

  /// The island's first direct solve: up to getMaxPivotSteps pivot steps
  /// (fewer if the budget has less left), falling back at that cap.
  void direct(detail::IslandProblem& problem, const std::vector<int>& subset, SolverStatistics& statistics);
  /// The pivot steps of all of an island's direct solves in a step.
  [[nodiscard]] int islandPivotBudget() const { return maxPivotSteps_ + maxPivotSteps_ / 2; }
  /// A later direct solve (a friction iteration, a coupling pass): when the
  /// pivot budget runs out it leaves the rows as they were and returns false.
  bool directAttempt(detail::IslandProblem& problem, const std::vector<int>& subset, SolverStatistics& statistics);
  /// A direct solve repeated over the friction bounds that follow the normal
  /// impulses (getNumFrictionIterations); rows flagged in `keep` keep theirs.
  /// `first`: the island's first direct solve (else its first solve is an
  /// attempt). False when the first solve fell back or was not made.
  bool directWithFriction(detail::IslandProblem& problem, const std::vector<int>& subset,
                          SolverStatistics& statistics, const std::vector<char>* keep = nullptr, bool first = true);
  /// Gauss–Seidel (or Jacobi) over the subset: `sweeps` at most, getNumIterations() when 0.
  void iterative(detail::IslandProblem& problem, const std::vector<int>& subset, SolverStatistics& statistics,
                 int sweeps = 0) const;
  static std::vector<int> allRows(const detail::IslandProblem& problem);

 private:
  static double complementarityError(const detail::IslandProblem& problem);

  int iterations_ = 16;
  double tolerance_ = 1e-10;
  IterativeMethod method_ = GAUSS_SEIDEL;
  int maxPivotSteps_ = 80;
  int pivotBudget_ = 0;  ///< pivot steps left to the island being solved
  double maxDirectWork_ = 3e8;
  double workBudget_ = 0.0;  ///< multiply-adds left to the island being solved
  bool postStabilization_ = false;
  bool warmStarting_ = false;
  bool contactWarmStarting_ = true;
  double contactWarmStartingFactor_ = 0.85;
  bool geometricStiffness_ = true;
  double geometricStiffnessThreshold_ = 1.0;
  int projectionIterations_ = 1;
  int frictionIterations_ = 8;
  double frictionTolerance_ = 1e-6;
  int couplingIterations_ = 16;
  double couplingTolerance_ = 1e-4;
  int couplingSweeps_ = 2;
  std::unique_ptr<detail::DirectSolve> direct_;  ///< the pivoting solver's workspace
  /// The island being solved (solve, project) has had a direct solve: its
  /// rows' matrix, which only their impulses and bounds change within the
  /// island's solve, is the one direct_ assembled for the same rows.
  bool islandMatrixKnown_ = false;
};

/// Every row by the direct solver: exact to round-off, whatever the mass
/// ratios and stiffness; O(n) for chains and trees, more where loops and
/// contacts fill in the factor.
class DirectSolver final : public Solver {
 public:
  DirectSolver() { setEnablePostStabilization(true); }
  [[nodiscard]] const char* getName() const override { return "direct"; }
  [[nodiscard]] bool projects(SolveType) const override { return getEnablePostStabilization(); }

  [[nodiscard]] SPOOK_INLINE ref_ptr<Solver> makeWorker() const override;

 protected:
  SPOOK_INLINE void solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) override;
};

/// Every row by projected Gauss–Seidel (or Jacobi), optionally warm-started
/// from the last step: cheap per sweep, approximate; stiff joints and large
/// mass ratios come out softer than they are.
class IterativeSolver final : public Solver {
 public:
  [[nodiscard]] const char* getName() const override { return "iterative"; }
  [[nodiscard]] bool projects(SolveType) const override { return false; }

  [[nodiscard]] SPOOK_INLINE ref_ptr<Solver> makeWorker() const override;

 protected:
  SPOOK_INLINE void solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) override;
};

/// Each row as its constraint or friction model asks (setSolveType): DIRECT
/// rows by the direct solver, ITERATIVE rows by Gauss–Seidel,
/// DIRECT_AND_ITERATIVE rows by both, coupling the two subsystems (seed 001
/// §12.17), and SPLIT contacts with their normals direct and their friction
/// iterative. An island without iterative-only rows is solved directly
/// (DIRECT_AND_ITERATIVE then means DIRECT). Otherwise: a direct pass
/// (iterative rows at their warm start), then up to getNumCouplingIterations
/// passes of Gauss–Seidel (direct-only rows fixed) followed by a direct solve
/// with the iterative impulses, in which DIRECT_AND_ITERATIVE friction keeps
/// the bounds the iterative pass found (PHYSICS.md §2.5). Where a direct
/// solve ends the passes, the iterative friction is then scaled back within
/// μ times the normal impulses it found (detail::clampFrictionToNormals);
/// where one falls back or the island's budget cuts it short, the step ends
/// with Gauss–Seidel over every row, from the answer it has.
class HybridSolver final : public Solver {
 public:
  HybridSolver() { setEnablePostStabilization(true); }
  [[nodiscard]] const char* getName() const override { return "hybrid"; }

  [[nodiscard]] SPOOK_INLINE ref_ptr<Solver> makeWorker() const override;

 protected:
  SPOOK_INLINE void solveIsland(detail::IslandProblem& problem, SolverStatistics& statistics) override;
};

using SolverRef = ref_ptr<Solver>;

}  // namespace spook

// The solves themselves are compiled once (solver_impl.hpp): inline in a
// header-only program, in the translation unit that implements the double
// simulation otherwise (core/implementation.hpp).
#if defined(SPOOK_DEFINES_NON_TEMPLATES)
#include <spook/solver/solver_impl.hpp>
#endif
