#pragma once

#include <cstddef>
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
  /// Bodies whose state would have become non-finite in the last step; they
  /// were frozen (velocities zeroed, pose kept) instead.
  std::vector<observer_ptr<RigidBodyT<S>>> frozenBodies;
  /// Contact points the last step's collision detection dropped before
  /// contact reduction because their position, normal or depth was not
  /// finite (shapes posed near the largest finite coordinate); they exert
  /// no force.
  std::size_t numDroppedContactPoints = 0;
  /// What the constraint solver did in the last step.
  SolverStatistics solver;
};

}  // namespace spook
