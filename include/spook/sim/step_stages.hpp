#pragma once

// One step of a simulation, stage by stage, in order. Each stage is a
// member of SimulationT defined in sim/simulation_step.hpp; body stores and
// row producers (sim/step_extension.hpp) take part in the stages of
// integrate(). Compiled where the step is (sim/simulation_step.hpp).

#include <atomic>

#include <spook/collide/continuous.hpp>
#include <spook/sim/simulation.hpp>

namespace spook {

template <Scalar S>
void SimulationT<S>::stepForward() {
  if (stepping_) throw error("stepForward called from inside a step", getTimeStamp());
  applyPendingTimeStep();  // left over when a listener threw in the last step
  stepping_ = true;
  struct ResetOnExit {
    bool& flag;
    ~ResetOnExit() { flag = false; }
  } reset{stepping_};

  notify(Listener::PRE_COLLIDE);
  collide();  // sleeping bodies disturbed wake; broadphase, narrow phase, contact events
  notify(Listener::PRE_STEP);
  integrate(timeStep_);
  if (const auto ccd = detail::ccdStage<S>.load(std::memory_order_relaxed))  // continuous collision, opt-in per body
    ccd(bodies_.get(), *space_, timeStep_);
  notify(Listener::POST_STEP);
  notify(Listener::LAST_STEP);

  ++stepsSinceBase_;
  ++statistics_.numSteps;
  if (statistics_.solver.directFallbacks > 0) ++statistics_.numFallbackSteps;
  stepping_ = false;
  applyPendingTimeStep();
}

template <Scalar S>
void SimulationT<S>::integrate(S h) {
  const StepContext step = beginExtensions(double(h));  // stores and producers may add or remove bodies
  gatherSolverBodies(step);  // v, v* = v + hM⁻¹f, M⁻¹: rigid bodies, then each store's
  wakeBodies(step);          // sleeping bodies that awake ones touch or are jointed to (getAutoSleep)
  gatherRows(step);          // joints, contacts, then each producer's rows, with their last impulses
  wakeDriven(step);          // sleeping bodies a row drives (a motor's speed, a moving surface)
  solveRows(step);           // islands under the solver policy; geometric stiffness
  readBackImpulses(step);    // joint forces and predictions, contact forces and persistence, producers
  moveBodies(step);          // positions from v⁺
  sleepResting(step);        // islands at rest fall asleep (getAutoSleep)
  projectRows(step);         // post-stabilization of the joints and producers' projection rows
}

}  // namespace spook
