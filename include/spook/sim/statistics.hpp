#pragma once

#include <cstdint>
#include <vector>

#include <spook/core/observer_ptr.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/solver/solver.hpp>

namespace spook {

/// What the last step did, readable after stepForward().
template <Scalar S>
struct SimulationStatisticsT {
  /// Steps taken since the simulation was created.
  std::uint64_t numSteps = 0;
  /// Steps, since the simulation was created, in which a direct solve did
  /// not converge and fell back to its safe answer (SolverStatistics::directFallbacks).
  std::uint64_t numFallbackSteps = 0;
  /// Bodies whose state would have become non-finite in the last step; they
  /// were frozen (velocities zeroed, pose kept) instead.
  std::vector<observer_ptr<RigidBodyT<S>>> frozenBodies;
  /// What the constraint solver did in the last step.
  SolverStatistics solver;
};

}  // namespace spook
