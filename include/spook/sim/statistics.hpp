#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <spook/core/observer_ptr.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/solver/solver.hpp>

namespace spook {

/// Why a body was frozen in a step (SimulationStatisticsT::frozenBodies).
enum class FreezeReason {
  /// Its own new position, orientation or velocity would not have been finite.
  NON_FINITE_STATE,
  /// The constraint and contact impulses of its island (the bodies joined to
  /// it by constraints and contacts) came out non-finite: they were dropped,
  /// and every body of the island was frozen rather than moved without them.
  NON_FINITE_ISLAND
};

/// What the last step did, readable after stepForward().
template <Scalar S>
struct SimulationStatisticsT {
  /// A body frozen in the last step and why.
  struct FrozenBody {
    observer_ptr<RigidBodyT<S>> body;
    FreezeReason reason;
  };

  /// Steps taken since the simulation was created.
  std::uint64_t numSteps = 0;
  /// Bodies frozen in the last step: their state was kept as it was before
  /// the step (pose kept, velocities zeroed) instead of becoming non-finite
  /// or moving without their constraints. Each body appears once.
  std::vector<FrozenBody> frozenBodies;
  /// Steps, since the simulation was created, in which a direct solve did
  /// not converge and fell back to its safe answer (SolverStatistics::directFallbacks).
  std::uint64_t numFallbackSteps = 0;
  /// Contact points the last step's collision detection dropped before
  /// contact reduction because their position, normal or depth was not
  /// finite (shapes posed near the largest finite coordinate); they exert
  /// no force.
  std::size_t numDroppedContactPoints = 0;
  /// Bodies asleep after the last step (SimulationT::getAutoSleep).
  std::size_t numSleepingBodies = 0;
  /// What the constraint solver did in the last step.
  SolverStatistics solver;
};

}  // namespace spook
