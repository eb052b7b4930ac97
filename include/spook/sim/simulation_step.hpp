#pragma once

// The stages of a simulation step (their order: sim/step_stages.hpp): included by
// sim/simulation.hpp where the step is compiled (SPOOK_DEFINES_STEP,
// core/implementation.hpp), with the solver, contact and collision code
// behind it.

#include <cmath>
#include <cstddef>
#include <memory>
#include <numeric>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <spook/collide/continuous.hpp>
#include <spook/core/worker_pool.hpp>
#include <spook/sim/constraint_rows.hpp>
#include <spook/sim/contact_rows.hpp>
#include <spook/sim/simulation.hpp>
#include <spook/sim/step_stages.hpp>
#include <spook/solver/geometric_stiffness.hpp>
#include <spook/solver/integrator.hpp>
#include <spook/solver/island_problem.hpp>
#include <spook/solver/islands.hpp>
#include <spook/solver/row.hpp>
#include <spook/solver/solver.hpp>

namespace spook {

namespace detail {

/// What a simulation keeps from step to step besides its content.
template <Scalar S>
struct SimulationWorkspace {
  std::vector<SolverBody> solverBodies;
  std::vector<char> frozen;  ///< per body: frozen in this step
  std::vector<StepReachT<S>> reach;  ///< per body: how far it may move in the step (speculative contacts)
  /// The step's rows: the constraints', the contacts' from firstContactRow
  /// on, the producers' from firstProducerRow on (producerRowsEnd: where
  /// each producer's end).
  RowSet rows;
  std::size_t firstContactRow = 0, firstProducerRow = 0;
  std::vector<std::size_t> producerRowsEnd;
  ConstraintRows<S> constraintRows;
  ContactRows<S> contactRows;
  IslandStepper islands;
  GeometricStiffness geometricStiffness;
  WorkerPool workers;  ///< SimulationT::setNumThreads
  /// Auto sleep's scratch: body pairs that touch or are jointed, and per
  /// body its island's root and whether the island may sleep.
  std::vector<std::pair<RigidBodyT<S>*, RigidBodyT<S>*>> touching;
  std::vector<int> sleepParent;
  std::vector<char> sleepReady;
};

// Wakes a sleeping body in the middle of a step: from here on the solver
// sees it as dynamic, with its force-driven velocity.
template <Scalar S>
void wakeInStep(RigidBodyT<S>& body, SolverBody& solved, const GravityFieldT<S>& gravity, S h) {
  body.wakeUp();
  solved = BodyIntegrator<S>::solverBody(body, gravity, h);
}

// How many rows and side-table entries a RowSet held.
struct RowCounts {
  explicit RowCounts(const RowSet& set)
      : rows(set.size()), friction(set.friction.size()), arms(set.arms.size()), thirdBodies(set.thirdBodies.size()),
        secondOrder(set.secondOrder.size()) {}
  std::size_t rows, friction, arms, thirdBodies, secondOrder;
};

// Checks the rows and side-table entries a producer wrote since `before`;
// on a fault drops every producer's rows (from `firstProducerRow` on) and
// throws a spook::Error naming it.
inline void checkProducerRows(RowSet& rows, std::size_t firstProducerRow, const RowCounts& before, int numBodies,
                              const std::string& name) {
  const std::size_t row = before.rows;
  const auto fail = [&](std::string_view what, auto value) {
    rows.truncate(firstProducerRow);
    throw makeError("RowProducer", name, what, value);
  };
  const auto ownRow = [&](int i) { return i >= int(row) && i < int(rows.size()); };
  for (std::size_t i = row; i < rows.size(); ++i)
    for (int body : {rows.rows[i].body1, rows.rows[i].body2})
      if (body < -1 || body >= numBodies) fail("wrote a row with a body index out of range", body);
  for (std::size_t k = before.thirdBodies; k < rows.thirdBodies.size(); ++k) {
    const ThirdBody& t = rows.thirdBodies[k];
    if (!ownRow(t.row)) fail("gave a third body to a row that is not its own, row", t.row);
    if (t.body < -1 || t.body >= numBodies) fail("wrote a row with a body index out of range", t.body);
  }
  for (std::size_t k = before.friction; k < rows.friction.size(); ++k) {
    const FrictionLink& f = rows.friction[k];
    if (!ownRow(f.row) || !ownRow(f.normal) || (f.partner != -1 && !ownRow(f.partner)))
      fail("linked a friction row to a row that is not its own, row", f.row);
    if (!(std::isfinite(f.coefficient) && f.coefficient >= 0.0))
      fail("gave a friction row a coefficient that is not finite and >= 0", f.coefficient);
  }
  for (std::size_t k = before.arms; k < rows.arms.size(); ++k) {
    const LeverArms& a = rows.arms[k];
    if (!ownRow(a.row)) fail("gave lever arms to a row that is not its own, row", a.row);
    if (!a.arm1.allFinite() || !a.arm2.allFinite()) fail("gave a row lever arms that are not finite, row", a.row);
  }
  for (std::size_t k = before.secondOrder; k < rows.secondOrder.size(); ++k) {
    const SecondOrder& t = rows.secondOrder[k];
    if (!ownRow(t.row)) fail("gave a second-order term to a row that is not its own, row", t.row);
    if (!std::isfinite(t.curvature)) fail("gave a row a second-order term that is not finite", t.curvature);
  }
}

}  // namespace detail

template <Scalar S>
SimulationT<S>::SimulationT(ref_ptr<SpaceT<S>> space)
    : space_(std::move(space)), work_(std::make_unique<detail::SimulationWorkspace<S>>()) {
  installSpaceRules();
}

template <Scalar S>
SimulationT<S>::~SimulationT() {
  for (auto& c : collections_) setCollectionsSink(*c, nullptr);
}

template <Scalar S>
void SimulationT<S>::forgetPredictions() {
  work_->constraintRows.forgetPredictions();
}

template <Scalar S>
void SimulationT<S>::collide() {
  wakeDisturbed();  // before the space reuses the contacts of sleeping pairs
  work_->workers.resize(numThreads_);
  std::vector<StepReachT<S>>& reach = work_->reach;
  reach.clear();
  if (contactSettings_.speculative) {
    // The free motion |Δx| <= h (|v| + h |a|), a = F/m + g; a push from
    // another contact may add to it (that contact may be born overlapping).
    const S h = timeStep_;
    for (const auto& body : bodies_) {
      StepReachT<S>& r = reach.emplace_back();
      if (body->getMotionControl() == Body::STATIC || body->isSleeping()) continue;
      S acceleration = S(0);
      if (body->getMotionControl() == Body::DYNAMICS) {
        acceleration = gravity_->calculateGravity(body->getCmPosition()).norm();
        if (const S mass = body->getMassProperties()->getMass(); mass > S(0))
          acceleration += body->getForce().norm() / mass;
      }
      r.linear = h * (body->getVelocity().norm() + h * acceleration);
      r.angular = h * body->getAngularVelocity().norm();
    }
  }
  space_->update(bodies_.get(), &work_->workers, reach);
  statistics_.numDroppedContactPoints = space_->getNumDroppedContactPoints();
  notifyContacts();
}

template <Scalar S>
void SimulationT<S>::gatherSolverBodies(const StepContext& step) {
  auto& w = *work_;
  statistics_.frozenBodies.clear();
  statistics_.solver = SolverStatistics{};
  const S h = S(step.getTimeStep());
  w.solverBodies.clear();
  for (const auto& body : bodies_) w.solverBodies.push_back(detail::BodyIntegrator<S>::solverBody(*body, *gravity_, h));
  collectStoreBodies(step);
  w.frozen.assign(bodies_.size(), 0);
}

template <Scalar S>
void SimulationT<S>::gatherRows(const StepContext& step) {
  auto& w = *work_;
  const double h = step.getTimeStep();
  w.rows.clear();
  w.constraintRows.write(constraints_.get(), bodyIndex(), *solver_, h, w.rows);
  w.firstContactRow = w.rows.size();
  w.contactRows.build(space_->getGeometryContacts(), space_->getSpeculativeContacts(), materials_, *gravity_,
                      bodyIndex(), w.solverBodies, h, contactSettings_, w.rows);
  collectProducerRows(step, false);
}

template <Scalar S>
void SimulationT<S>::solveRows(const StepContext& step) {
  auto& w = *work_;
  const double h = step.getTimeStep();
  const bool stiffness = solver_->getEnableGeometricStiffness() && !w.rows.empty();
  if (stiffness)
    w.geometricStiffness.apply(w.rows, w.solverBodies, h, solver_->getGeometricStiffnessThreshold());
  else
    w.geometricStiffness.clear();
  if (w.rows.empty()) return;
  w.islands.solve(w.rows, w.solverBodies, h, *solver_, statistics_.solver, &w.workers);
  // Again while the forces just found need more geometric stiffness than
  // the solve had (geometric_stiffness.hpp).
  for (int solves = 1; stiffness && solves < detail::GeometricStiffness::kMaxSolves &&
                       w.geometricStiffness.refresh(w.rows, w.solverBodies, h, solver_->getGeometricStiffnessThreshold());
       ++solves) {
    SolverStatistics again;
    w.islands.solve(w.rows, w.solverBodies, h, *solver_, again, &w.workers, /*again=*/true);
    statistics_.solver.addResolve(again);
  }
  for (int i : w.islands.getNonFiniteBodies())
    if (std::size_t(i) < bodies_.size()) freeze(std::size_t(i), FreezeReason::NON_FINITE_ISLAND);
}

template <Scalar S>
void SimulationT<S>::readBackImpulses(const StepContext& step) {
  auto& w = *work_;
  const double h = step.getTimeStep();
  const std::span<const double> impulses(w.rows.impulses);
  w.constraintRows.readBack(constraints_.get(), w.rows, w.solverBodies, h, solver_->getEnablePostStabilization());
  w.contactRows.readBack(impulses.subspan(w.firstContactRow, w.firstProducerRow - w.firstContactRow), h);
  for (std::size_t k = 0, begin = w.firstProducerRow; k < producers_.size(); begin = w.producerRowsEnd[k++])
    producers_[k]->readBack(impulses.subspan(begin, w.producerRowsEnd[k] - begin), step);
}

template <Scalar S>
void SimulationT<S>::moveBodies(const StepContext& step) {
  auto& w = *work_;
  const S h = S(step.getTimeStep());
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    Body& body = *bodies_[i];
    if (!w.frozen[i] && !detail::BodyIntegrator<S>::move(body, w.solverBodies[i], h))
      freeze(i, FreezeReason::NON_FINITE_STATE);
    detail::BodyIntegrator<S>::clearForces(body);
  }
  for (std::size_t k = 0, first = bodies_.size(); k < stores_.size(); first += step.sizes_[k++])
    stores_[k]->move(std::span<const detail::SolverBody>(w.solverBodies).subspan(first, step.sizes_[k]), step);
}

template <Scalar S>
void SimulationT<S>::wakeDisturbed() {
  const bool all =
      !autoSleep_.getEnable() || constraints_.version() != sleptConstraints_ || producers_.version() != sleptProducers_;
  for (const auto& body : bodies_)
    if (body->isSleeping() && (all || detail::BodySleep<S>::disturbed(*body))) body->wakeUp();
}

template <Scalar S>
void SimulationT<S>::wakeBodies(const StepContext& step) {
  auto& w = *work_;
  if (!anySleeping()) return;
  const S h = S(step.getTimeStep());
  const auto wake = [&](Body* body) {
    if (!body || !contains(body) || !body->isSleeping()) return false;
    detail::wakeInStep(*body, w.solverBodies[Membership::indexOf(*body)], *gravity_, h);
    return true;
  };
  for (const auto& pair : space_->getSeparations()) {
    if (pair.first) wake(pair.first->getRigidBody());
    if (pair.second) wake(pair.second->getRigidBody());
  }
  // An awake dynamic or a moving kinematic body in contact with a sleeping
  // one, or jointed to it, wakes it; and so on through the sleeping island.
  const auto active = [&](const Body* body) {
    if (!body || !contains(body) || body->isSleeping()) return false;
    const detail::SolverBody& b = w.solverBodies[Membership::indexOf(*body)];
    return b.dynamic || b.velocity != detail::Vec6d::Zero();
  };
  w.touching.clear();
  for (const auto* contacts : {&space_->getGeometryContacts(), &space_->getSpeculativeContacts()})
    for (const auto& contact : *contacts)
      if (contact.isEnabled() && !contact.isSensor())
        w.touching.emplace_back(contact.rigidBody(0), contact.rigidBody(1));
  for (const auto& c : constraints_)
    if (c->getEnable()) w.touching.emplace_back(c->getBodyAt(0), c->getBodyAt(1));
  for (bool woke = true; woke;) {
    woke = false;
    for (const auto& [a, b] : w.touching) {
      if (a && a->isSleeping() && active(b)) woke = wake(a) || woke;
      if (b && b->isSleeping() && active(a)) woke = wake(b) || woke;
    }
  }
}

template <Scalar S>
bool SimulationT<S>::anySleeping() const {
  return std::any_of(bodies_.begin(), bodies_.end(), [](const auto& body) { return body->isSleeping(); });
}

template <Scalar S>
void SimulationT<S>::wakeDriven(const StepContext& step) {
  if (!anySleeping()) return;
  auto& w = *work_;
  const int n = static_cast<int>(bodies_.size());
  const S h = S(step.getTimeStep());
  const auto sleeping = [&](int i) { return i >= 0 && i < n && bodies_[std::size_t(i)]->isSleeping(); };
  for (const detail::Row& r : w.rows.rows)
    if (detail::drives(r))
      for (int i : {r.body1, r.body2})
        if (sleeping(i)) detail::wakeInStep(*bodies_[std::size_t(i)], w.solverBodies[std::size_t(i)], *gravity_, h);
}

template <Scalar S>
void SimulationT<S>::sleepResting(const StepContext& step) {
  auto& w = *work_;
  sleptConstraints_ = constraints_.version();
  sleptProducers_ = producers_.version();
  std::size_t asleep = 0;
  if (autoSleep_.getEnable()) {
    // Islands as the solve saw them: dynamic rigid bodies joined by rows. An
    // island sleeps when all of its bodies have rested long enough, and
    // none is a store's body or bound by a producer's row.
    const int n = static_cast<int>(bodies_.size());
    const S h = S(step.getTimeStep());
    std::vector<int>& parent = w.sleepParent;
    std::vector<char>& ready = w.sleepReady;
    parent.resize(std::size_t(n));
    std::iota(parent.begin(), parent.end(), 0);
    ready.assign(std::size_t(n), 0);
    const auto dynamic = [&](int i) { return i >= 0 && i < n && w.solverBodies[std::size_t(i)].dynamic; };
    const auto find = [&](int i) {
      while (parent[std::size_t(i)] != i) i = parent[std::size_t(i)] = parent[std::size_t(parent[std::size_t(i)])];
      return i;
    };
    for (int i = 0; i < n; ++i)
      if (dynamic(i) && !w.frozen[std::size_t(i)])
        ready[std::size_t(i)] = detail::BodySleep<S>::rest(*bodies_[std::size_t(i)], autoSleep_, h);
    for (const detail::Row& r : w.rows.rows)
      if (dynamic(r.body1) && dynamic(r.body2)) parent[std::size_t(find(r.body1))] = find(r.body2);
    for (const detail::ThirdBody& t : w.rows.thirdBodies) {
      const detail::Row& r = w.rows.rows[std::size_t(t.row)];
      for (int other : {r.body1, r.body2})
        if (dynamic(other) && dynamic(t.body)) parent[std::size_t(find(other))] = find(t.body);
    }
    // From here ready[root] says whether the root's island may sleep: not
    // with a body that has not rested long enough, a row that drives it (a
    // motor, a moving surface), a moving kinematic body it touches, a
    // producer's row or a store's body.
    const auto keepAwake = [&](int i) {
      if (dynamic(i)) ready[std::size_t(find(i))] = 0;
    };
    const auto moving = [&](int i) {
      return i >= 0 && i < n && !dynamic(i) && w.solverBodies[std::size_t(i)].velocity != detail::Vec6d::Zero();
    };
    for (int i = 0; i < n; ++i)
      if (dynamic(i) && !ready[std::size_t(i)]) keepAwake(i);
    for (std::size_t k = 0; k < w.rows.size(); ++k) {
      const detail::Row& r = w.rows.rows[k];
      if (k >= w.firstProducerRow || r.body1 >= n || r.body2 >= n || detail::drives(r) || moving(r.body1) ||
          moving(r.body2)) {
        keepAwake(r.body1);
        keepAwake(r.body2);
      }
    }
    for (const detail::ThirdBody& t : w.rows.thirdBodies)
      if (std::size_t(t.row) >= w.firstProducerRow || t.body >= n) {
        keepAwake(w.rows.rows[std::size_t(t.row)].body1);
        keepAwake(w.rows.rows[std::size_t(t.row)].body2);
        keepAwake(t.body);
      }
    for (int i = 0; i < n; ++i)
      if (dynamic(i) && ready[std::size_t(find(i))]) detail::BodySleep<S>::fallAsleep(*bodies_[std::size_t(i)]);
  }
  for (const auto& body : bodies_) asleep += body->isSleeping() ? 1 : 0;
  statistics_.numSleepingBodies = asleep;
}

template <Scalar S>
void SimulationT<S>::projectRows(const StepContext& step) {
  if (work_->rows.empty()) return;
  for (int i = 0; i < solver_->getNumPostStabilizationIterations(); ++i) postStabilize(step);
}

template <Scalar S>
StepContext SimulationT<S>::beginExtensions(double h) {
  if (stores_.empty() && producers_.empty()) return StepContext(h, nullptr);
  StepContext step = makeStepContext(h);
  for (const auto& s : stores_) s->beginStep(step);
  for (const auto& p : producers_) p->beginStep(step);
  std::size_t first = bodies_.size();
  for (const auto& s : stores_) {
    step.firstIndex_.emplace_back(s.get(), first);
    step.sizes_.push_back(s->size());
    first += s->size();
  }
  return step;
}

template <Scalar S>
void SimulationT<S>::collectStoreBodies(const StepContext& step) {
  auto& w = *work_;
  std::size_t first = w.solverBodies.size();
  std::size_t total = first;
  for (std::size_t size : step.sizes_) total += size;
  w.solverBodies.resize(total);
  for (std::size_t k = 0; k < stores_.size(); first += step.sizes_[k++]) {
    const std::span<detail::SolverBody> bodies = std::span<detail::SolverBody>(w.solverBodies).subspan(first, step.sizes_[k]);
    stores_[k]->writeSolverBodies(bodies, step);
  }
}

template <Scalar S>
void SimulationT<S>::collectProducerRows(const StepContext& step, bool projection) {
  auto& w = *work_;
  w.firstProducerRow = w.rows.size();
  w.producerRowsEnd.clear();
  RowWriter writer(w.rows);
  const int numBodies = int(w.solverBodies.size());
  for (const auto& p : producers_) {
    const detail::RowCounts counts(w.rows);
    if (projection)
      p->writeProjectionRows(writer, step);
    else
      p->writeRows(writer, step);
    detail::checkProducerRows(w.rows, w.firstProducerRow, counts, numBodies, p->getName());
    w.producerRowsEnd.push_back(w.rows.size());
  }
  for (std::size_t i = w.firstProducerRow; i < w.rows.size(); ++i) w.rows.rows[i].constraint = -1;
}

template <Scalar S>
void SimulationT<S>::postStabilize(const StepContext& step) {
  const double h = step.getTimeStep();
  auto& w = *work_;
  w.rows.clear();
  w.constraintRows.writeProjectionRows(constraints_.get(), bodyIndex(), *solver_, w.rows.rows);
  if (w.rows.empty() && producers_.empty()) return;
  w.rows.impulses.assign(w.rows.size(), 0.0);
  w.solverBodies.clear();
  for (const auto& body : bodies_) w.solverBodies.push_back(detail::BodyIntegrator<S>::massAndVelocity(*body, S(h)));
  collectStoreBodies(step);
  collectProducerRows(step, true);
  if (w.rows.empty()) return;
  w.geometricStiffness.addInertia(w.solverBodies);
  // Frozen bodies stand still, like static ones.
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (w.frozen[i]) w.solverBodies[i] = detail::SolverBody{};
  w.islands.project(w.rows, w.solverBodies, h, *solver_, statistics_.solver, &w.workers);
  for (std::size_t i = 0; i < bodies_.size(); ++i)
    if (!detail::BodyIntegrator<S>::displace(*bodies_[i], w.solverBodies[i], S(h)))
      freeze(i, FreezeReason::NON_FINITE_STATE);
  for (std::size_t k = 0, first = bodies_.size(); k < stores_.size(); first += step.sizes_[k++])
    stores_[k]->displace(std::span<const detail::SolverBody>(w.solverBodies).subspan(first, step.sizes_[k]));
}

template <Scalar S>
void SimulationT<S>::freeze(std::size_t i, FreezeReason reason) {
  auto& w = *work_;
  detail::BodyIntegrator<S>::freeze(*bodies_[i]);
  w.solverBodies[i].freeVelocity.setZero();  // as the rows' predictions (predictViolations) should see it
  if (std::exchange(w.frozen[i], char(1))) return;
  statistics_.frozenBodies.push_back({bodies_[i].get(), reason});
}

#if defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE)
template class SimulationT<double>;
#endif
#if defined(SPOOK_IMPLEMENT_SIMULATION_FLOAT)
template class SimulationT<float>;
#endif

}  // namespace spook
