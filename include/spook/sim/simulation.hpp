#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include <spook/collide/space.hpp>
#include <spook/constraints/constraint.hpp>
#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/dynamics/gravity_field.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/auto_sleep.hpp>
#include <spook/sim/collection.hpp>
#include <spook/sim/contact_event_listener.hpp>
#include <spook/sim/contact_settings.hpp>
#include <spook/sim/jointed_pairs.hpp>
#include <spook/sim/material_manager.hpp>
#include <spook/sim/membership.hpp>
#include <spook/sim/roster.hpp>
#include <spook/sim/statistics.hpp>
#include <spook/sim/step_event_listener.hpp>
#include <spook/sim/step_extension.hpp>
#include <spook/solver/solver.hpp>

namespace spook {

namespace detail {
template <Scalar S>
struct SimulationWorkspace;
}  // namespace detail

/// Owns a scene and steps it. Time in seconds; default step 1/60 s; default
/// gravity uniform (0, 0, −9.80665) m/s². An object belongs to at most one
/// simulation; a call that throws leaves the simulation unchanged.
template <Scalar S>
class SimulationT : public Referenced, public detail::ContentSink<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Body = RigidBodyT<S>;
  using Listener = StepEventListenerT<S>;
  using Collection = CollectionT<S>;
  using ContactListener = ContactEventListenerT<S>;
  using Geometry = GeometryT<S>;
  using Constraint = ConstraintT<S>;

  /// A simulation whose space collides every shape type.
  SimulationT() : SimulationT(ref_ptr<SpaceT<S>>(new SpaceT<S>())) {}
  /// A simulation for the shape types of `List` only, e.g.
  /// `Simulation(ShapeList<SphereT, PlaneT>{})`: only the colliders between
  /// them are compiled, and a geometry of another type is refused.
  template <template <class> class... Shapes>
  explicit SimulationT(ShapeList<Shapes...> list) : SimulationT(ref_ptr<SpaceT<S>>(new SpaceT<S>(list))) {}

  // --- Time ------------------------------------------------------------------

  /// Step length h (s), finite and > 0. Set from a listener during a step,
  /// it takes effect from the next step (a step is taken whole with one h).
  [[nodiscard]] S getTimeStep() const { return timeStep_; }
  void setTimeStep(S h);
  /// Simulated time (s), computed as t₀ + n·h rather than summed, so that a
  /// float simulation does not drift by a step every few thousand steps.
  [[nodiscard]] S getTimeStamp() const;

  /// Takes one step:
  /// preCollide listeners → collision detection → contact events → pre
  /// listeners → rows, islands, solve → integrate → continuous collision
  /// (RigidBody::setEnableCCD) → post listeners → last listeners → t += h.
  void stepForward();

  /// Steps until the time stamp reaches `t` (s): round((t − now)/h) steps,
  /// recounted after each step in case a listener changes h. stepTo(now),
  /// or any t less than half a step ahead, takes no step. Throws before
  /// stepping when t is not finite, is in the past, or is more than 2³¹
  /// steps away (1e9 s at 60 Hz would take 6e10 steps).
  void stepTo(S t);

  // --- Solver ----------------------------------------------------------------

  /// The solver policy that solves each island: HybridSolver by default
  /// (rows solved as their constraints ask), DirectSolver or IterativeSolver.
  [[nodiscard]] Solver* getSolver() const { return solver_.get(); }
  void setSolver(ref_ptr<Solver> solver);

  /// Threads a step may use, the calling one included (default 1; at most
  /// kMaxThreads): the narrow phase's geometry pairs and the islands'
  /// solves are spread over them (a pile of bodies in contact is one
  /// island). The results are the same bit for bit for any number of
  /// threads. The threads wait between steps and end with the simulation.
  [[nodiscard]] int getNumThreads() const { return numThreads_; }
  void setNumThreads(int n);
  static constexpr int kMaxThreads = 256;

  /// Sleeping of islands at rest (off by default; sim/auto_sleep.hpp).
  [[nodiscard]] AutoSleep* getAutoSleep() { return &autoSleep_; }
  [[nodiscard]] const AutoSleep* getAutoSleep() const { return &autoSleep_; }

  // --- Gravity ---------------------------------------------------------------

  [[nodiscard]] GravityFieldT<S>* getGravityField() const { return gravity_.get(); }
  void setGravityField(GravityFieldT<S>* field);
  /// Replaces the field by a uniform one (m/s²).
  void setUniformGravity(const Vec3& g) { setGravityField(new UniformGravityFieldT<S>(g)); }

  // --- Collision detection ---------------------------------------------------

  /// The space that finds this simulation's contacts.
  [[nodiscard]] SpaceT<S>* getSpace() const { return space_.get(); }
  /// The contacts found in the last step (those with isEnabled() false were
  /// removed by a contact listener).
  [[nodiscard]] const std::vector<GeometryContactT<S>>& getGeometryContacts() const {
    return space_->getGeometryContacts();
  }

  // --- Contacts --------------------------------------------------------------

  /// The explicit contact materials (getOrCreateContactMaterial); pairs
  /// without one combine their two materials' implicit values.
  [[nodiscard]] MaterialManagerT<S>* getMaterialManager() { return &materials_; }
  [[nodiscard]] const MaterialManagerT<S>* getMaterialManager() const { return &materials_; }
  /// Approach speed (m/s, >= 0) above which restitution makes a contact
  /// bounce; slower ones come to rest. Default 0.2.
  [[nodiscard]] S getRestitutionThreshold() const { return S(contactSettings_.restitutionThreshold); }
  void setRestitutionThreshold(S speed);
  /// The fastest (m/s, > 0) that contact stabilization separates overlapping
  /// shapes: a box created half inside another leaves it at about this speed
  /// instead of being shot out. Default 1.
  [[nodiscard]] S getMaxDepenetrationSpeed() const;
  void setMaxDepenetrationSpeed(S speed);
  /// Speculative contacts (default on): the space also finds the points
  /// where two shapes are apart by less than they may close within the
  /// step (each body's speed and gravity times the step, SpaceT::update),
  /// and the solver lets such a gap close within the step and no more. A
  /// contact is then born touching, not overlapping by up to its approach
  /// speed times the step, which SPOOK's stabilization would push out over
  /// the following steps (energy a settling pile never loses). Off, shapes
  /// are found only once they touch. A pair that a contact listener
  /// watches (impact or contact) is not speculative: the listener decides
  /// on its contact before the solver sees it. Nor are two bodies that a
  /// constraint joins: their motion about the joint turns the gap at
  /// another rate than the linear one the gap row assumes.
  [[nodiscard]] bool getEnableSpeculativeContacts() const { return contactSettings_.speculative; }
  void setEnableSpeculativeContacts(bool enable) { contactSettings_.speculative = enable; }

  // --- Content ---------------------------------------------------------------

  /// Adds a geometry that stands static in the world (a body's geometries
  /// come with the body).
  void add(ref_ptr<Geometry> geometry);
  /// Removes a static geometry; false when it is not here.
  bool remove(Geometry* geometry) { return space_->remove(geometry); }

  /// Adds a listener of class L, checked at compile time: a member named
  /// like a callback must override it (detail::requireContactCallbacks).
  template <detail::ContactEventListenerClass<S> L>
  void add(const ref_ptr<L>& listener) {
    detail::requireContactCallbacks<L, S>();
    add(ref_ptr<ContactListener>(listener));
  }
  template <detail::ContactEventListenerClass<S> L>
  void add(L* listener) {
    add(ref_ptr<L>(listener));
  }
  void add(ref_ptr<ContactListener> listener);
  void remove(ContactListener* listener);
  [[nodiscard]] const std::vector<ref_ptr<ContactListener>>& getContactEventListeners() const {
    return contactListeners_.get();
  }

  void add(ref_ptr<Body> body) override;
  void remove(Body* body) override;

  /// Adds a listener of class L, checked at compile time: a member named
  /// like a callback must override it (detail::requireStepCallbacks).
  template <detail::StepEventListenerClass<S> L>
  void add(const ref_ptr<L>& listener) {
    detail::requireStepCallbacks<L, S>();
    add(ref_ptr<Listener>(listener));
  }
  template <detail::StepEventListenerClass<S> L>
  void add(L* listener) {
    add(ref_ptr<L>(listener));
  }
  void add(ref_ptr<Listener> listener) override;
  void remove(Listener* listener) override;

  /// Adds a collection and everything in it, nested collections included.
  void add(ref_ptr<Collection> collection);
  /// Removes a collection added with add(), and its content.
  void remove(Collection* collection);

  /// Adds a constraint whose bodies are in this simulation already; throws
  /// when a body is elsewhere or when both are static (or static and world).
  /// A constraint whose body is later removed adds no rows.
  void add(ref_ptr<Constraint> constraint) override;
  void remove(Constraint* constraint) override;
  [[nodiscard]] const std::vector<ref_ptr<Constraint>>& getConstraints() const { return constraints_.get(); }
  /// The first constraint with this name, or nullptr.
  [[nodiscard]] Constraint* getConstraint(const std::string& name) const;
  [[nodiscard]] bool contains(const Constraint* constraint) const override {
    return constraints_.contains(constraint, this);
  }

  /// Adds a body store (sim/step_extension.hpp): its bodies are integrated
  /// and solved with the rigid bodies from the next step on.
  void add(ref_ptr<BodyStore> store);
  void remove(BodyStore* store);
  /// Adds a row producer (sim/step_extension.hpp): its rows enter the solve
  /// from the next step on.
  void add(ref_ptr<RowProducer> producer);
  void remove(RowProducer* producer);
  [[nodiscard]] bool contains(const BodyStore* store) const { return stores_.contains(store, this); }
  [[nodiscard]] bool contains(const RowProducer* producer) const { return producers_.contains(producer, this); }
  [[nodiscard]] const std::vector<ref_ptr<BodyStore>>& getBodyStores() const { return stores_.get(); }
  [[nodiscard]] const std::vector<ref_ptr<RowProducer>>& getRowProducers() const { return producers_.get(); }

  [[nodiscard]] const std::vector<ref_ptr<Body>>& getRigidBodies() const { return bodies_.get(); }
  [[nodiscard]] const std::vector<ref_ptr<Listener>>& getEventListeners() const { return listeners_.get(); }
  [[nodiscard]] const std::vector<ref_ptr<Collection>>& getCollections() const { return collections_; }
  /// The first body with this name, or nullptr.
  [[nodiscard]] Body* getRigidBody(const std::string& name) const;
  [[nodiscard]] bool contains(const Body* body) const override { return bodies_.contains(body, this); }
  [[nodiscard]] bool contains(const Listener* listener) const override { return listeners_.contains(listener, this); }
  [[nodiscard]] bool contains(const ContactListener* listener) const;

  [[nodiscard]] const SimulationStatisticsT<S>& getStatistics() const { return statistics_; }

 protected:
  ~SimulationT() override;

 private:
  using Membership = detail::SimulationMembership;

  explicit SimulationT(ref_ptr<SpaceT<S>> space);
  // Post-stabilization's predictions are keyed by row storage that a later
  // constraint may reuse (sim/constraint_rows.hpp).
  void forgetPredictions();
  // A body's solver index in this step, −1 when it is not in the simulation.
  [[nodiscard]] auto bodyIndex() const {
    return [this](const Body* body) { return contains(body) ? int(Membership::indexOf(*body)) : -1; };
  }

  // Pairs with an explicit contact material reduce their points as it says;
  // jointed bodies do not collide unless their constraint asks (jointed_pairs.hpp).
  void installSpaceRules();

  // round((t − now)/h), in double so that neither the quotient nor its
  // rounding overflows; more than 2³¹ steps are refused.
  [[nodiscard]] long long stepsTo(S t) const;

  void applyPendingTimeStep();

  // The SPOOK step for every body: force-driven velocities, the rows of the
  // enabled constraints, islands solved by the policy, then the poses.
  void integrate(S h);

  // Projects the direct solver's equality rows back onto their manifold
  // (Solver::getEnablePostStabilization).
  void postStabilize(const StepContext& step);

  // Keeps body i as it was before the step (pose kept, velocities zeroed)
  // and reports it, once per step.
  void freeze(std::size_t i, FreezeReason reason);

  // The stages of a step (their order: sim/step_stages.hpp).
  void collide();
  void gatherSolverBodies(const StepContext& step);
  void gatherRows(const StepContext& step);
  void solveRows(const StepContext& step);
  void readBackImpulses(const StepContext& step);
  void moveBodies(const StepContext& step);
  void projectRows(const StepContext& step);
  void wakeDisturbed();
  void wakeBodies(const StepContext& step);
  void wakeDriven(const StepContext& step);
  [[nodiscard]] bool anySleeping() const;
  void sleepResting(const StepContext& step);

  // The stores' and producers' part of a step (sim/step_extension.hpp).
  StepContext beginExtensions(double h);
  // What stores and producers see of this simulation: h, gravity, the
  // solver indices of its rigid bodies.
  [[nodiscard]] StepContext makeStepContext(double h) const;
  void collectStoreBodies(const StepContext& step);
  void collectProducerRows(const StepContext& step, bool projection);

  // Calls the listeners selected by `stage`, highest priority first, over a
  // snapshot, so that callbacks may add and remove objects freely.
  void notify(typename Listener::ActivationMask stage);

  // Impact and contact callbacks per contact, in the order the listeners
  // were added, over a snapshot; a REMOVE_CONTACT disables the contact for
  // the solver, and the listeners after it see it disabled (seed 000). Then
  // the separations.
  void notifyContacts();

  // Collections: validate the whole tree, then register it, so that a failed
  // add changes nothing.
  void addNested(Collection& collection) override;
  void removeNested(Collection& collection) override;
  void validateTree(const Collection& collection, std::unordered_set<const void*>& seen) const;
  // After the whole tree is known: a constraint's bodies are in this
  // simulation or in the tree.
  void validateConstraints(const Collection& collection, const std::unordered_set<const void*>& seen) const;
  void checkBodiesOf(const Constraint& c, const std::unordered_set<const void*>* arriving) const;
  // Bodies and listeners of the whole tree first, so that every constraint
  // finds its bodies.
  void registerTree(Collection& collection);
  void registerMembers(Collection& collection);
  void registerConstraints(Collection& collection);
  void setCollectionsSink(Collection& collection, detail::ContentSink<S>* sink);

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError("Simulation", "", what, value);
  }

  S timeStep_ = S(1) / S(60);
  std::optional<S> pendingTimeStep_;
  S timeBase_ = S(0);
  std::uint64_t stepsSinceBase_ = 0;
  bool stepping_ = false;
  int numThreads_ = 1;
  AutoSleep autoSleep_;
  /// The constraints' and producers' roster versions when the last step
  /// ended: an add or remove since wakes every sleeping body.
  std::uint64_t sleptConstraints_ = 0, sleptProducers_ = 0;
  ref_ptr<GravityFieldT<S>> gravity_ = new UniformGravityFieldT<S>();
  detail::Roster<Body, true> bodies_{"RigidBody"};
  detail::Roster<Listener> listeners_{"StepEventListener"};
  detail::Roster<ContactListener> contactListeners_{"ContactEventListener"};
  ref_ptr<SpaceT<S>> space_;
  std::vector<ref_ptr<Collection>> collections_;
  detail::Roster<Constraint, true> constraints_{"Constraint"};
  detail::Roster<BodyStore> stores_{"BodyStore"};
  detail::Roster<RowProducer> producers_{"RowProducer"};
  detail::JointedPairs<S> jointedPairs_;
  SimulationStatisticsT<S> statistics_;
  ref_ptr<Solver> solver_ = new HybridSolver();
  MaterialManagerT<S> materials_;
  detail::ContactSettings contactSettings_;
  /// The step's own state (rows, solver bodies, contact history,
  /// predictions: sim/simulation_step.hpp), out of sight of a program that
  /// compiles spook once.
  std::unique_ptr<detail::SimulationWorkspace<S>> work_;
};

template <Scalar S>
void SimulationT<S>::setTimeStep(S h) {
  if (!(std::isfinite(h) && h > S(0))) throw error("time step must be finite and > 0 s", h);
  if (stepping_) {
    pendingTimeStep_ = h;
    return;
  }
  timeBase_ = getTimeStamp();
  stepsSinceBase_ = 0;
  timeStep_ = h;
}

template <Scalar S>
S SimulationT<S>::getTimeStamp() const {
  return timeBase_ + S(stepsSinceBase_) * timeStep_;
}

template <Scalar S>
void SimulationT<S>::stepTo(S t) {
  if (!std::isfinite(t)) throw error("stepTo time must be finite (s)", t);
  const S now = getTimeStamp();
  if (t < now) throw error("stepTo time must not be in the past (now " + std::to_string(now) + " s)", t);
  while (stepsTo(t) > 0) stepForward();
}

template <Scalar S>
void SimulationT<S>::setSolver(ref_ptr<Solver> solver) {
  if (!solver) throw error("solver must not be null", "nullptr");
  solver_ = std::move(solver);
}

template <Scalar S>
void SimulationT<S>::setNumThreads(int n) {
  if (n < 1 || n > kMaxThreads) throw error("number of threads must be in [1, " + std::to_string(kMaxThreads) + "]", n);
  numThreads_ = n;
}

template <Scalar S>
void SimulationT<S>::setGravityField(GravityFieldT<S>* field) {
  if (!field) throw error("gravity field must not be null", "nullptr");
  gravity_ = field;
}

template <Scalar S>
void SimulationT<S>::setRestitutionThreshold(S speed) {
  if (!(std::isfinite(speed) && speed >= S(0))) throw error("restitution threshold must be finite and >= 0 m/s", speed);
  contactSettings_.restitutionThreshold = double(speed);
}

template <Scalar S>
S SimulationT<S>::getMaxDepenetrationSpeed() const {
  return S(contactSettings_.maxDepenetrationSpeed);
}

template <Scalar S>
void SimulationT<S>::setMaxDepenetrationSpeed(S speed) {
  if (!(std::isfinite(speed) && speed > S(0)))
    throw error("maximum depenetration speed must be finite and > 0 m/s", speed);
  contactSettings_.maxDepenetrationSpeed = double(speed);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<Geometry> geometry) {
  if (geometry && geometry->getRigidBody())
    throw detail::makeError("Geometry", geometry->getName(), "belongs to a body; add the body instead");
  space_->add(std::move(geometry));
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<ContactListener> listener) {
  contactListeners_.checkAddable(listener.get(), this);
  contactListeners_.add(std::move(listener), this);
}

template <Scalar S>
void SimulationT<S>::remove(ContactListener* listener) {
  contactListeners_.checkRemovable(listener, this);
  contactListeners_.remove(listener);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<Body> body) {
  bodies_.checkAddable(body.get(), this);
  for (const auto& g : body->getGeometries()) space_->requireSupported(*g);
  bodies_.add(std::move(body), this);
}

template <Scalar S>
void SimulationT<S>::remove(Body* body) {
  bodies_.checkRemovable(body, this);
  bodies_.remove(body);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<Listener> listener) {
  listeners_.checkAddable(listener.get(), this);
  listeners_.add(std::move(listener), this);
}

template <Scalar S>
void SimulationT<S>::remove(Listener* listener) {
  listeners_.checkRemovable(listener, this);
  listeners_.remove(listener);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<Collection> collection) {
  if (!collection) throw error("cannot add a null Collection", "nullptr");
  addNested(*collection);
  collections_.push_back(std::move(collection));
}

template <Scalar S>
void SimulationT<S>::remove(Collection* collection) {
  auto it =
      std::find_if(collections_.begin(), collections_.end(), [&](const auto& c) { return c.get() == collection; });
  if (it == collections_.end())
    throw error("Collection was never added", collection ? collection->getName() : std::string("nullptr"));
  ref_ptr<Collection> keep = collection;
  collections_.erase(it);
  removeNested(*collection);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<Constraint> constraint) {
  constraints_.checkAddable(constraint.get(), this, constraint ? constraint->getKind() : nullptr);
  checkBodiesOf(*constraint, nullptr);
  jointedPairs_.add(*constraint);
  constraints_.add(std::move(constraint), this);
}

template <Scalar S>
void SimulationT<S>::remove(Constraint* constraint) {
  constraints_.checkRemovable(constraint, this, constraint ? constraint->getKind() : nullptr);
  ref_ptr<Constraint> keep = constraint;
  constraints_.remove(constraint);
  jointedPairs_.remove(*constraint);
  forgetPredictions();
}

template <Scalar S>
auto SimulationT<S>::getConstraint(const std::string& name) const -> Constraint* {
  for (const auto& c : constraints_)
    if (c->getName() == name) return c.get();
  return nullptr;
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<BodyStore> store) {
  stores_.checkAddable(store.get(), this);
  stores_.add(std::move(store), this);
}

template <Scalar S>
void SimulationT<S>::remove(BodyStore* store) {
  stores_.checkRemovable(store, this);
  stores_.remove(store);
}

template <Scalar S>
void SimulationT<S>::add(ref_ptr<RowProducer> producer) {
  producers_.checkAddable(producer.get(), this);
  producer->prepare(makeStepContext(double(timeStep_)));
  if (BodyStore* owned = producer->getOwnedStore()) {
    stores_.checkAddable(owned, this);
    stores_.add(ref_ptr<BodyStore>(owned), this);
  }
  producers_.add(std::move(producer), this);
}

template <Scalar S>
StepContext SimulationT<S>::makeStepContext(double h) const {
  StepContext step(h, [gravity = gravity_](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(gravity->calculateGravity(p.cast<S>()).template cast<double>());
  });
  step.bodyIndex_ = [index = bodyIndex()](const void* body) { return index(static_cast<const Body*>(body)); };
  step.bodyScalarSize_ = sizeof(S);
  step.simulation_ = this;
  return step;
}

template <Scalar S>
void SimulationT<S>::remove(RowProducer* producer) {
  producers_.checkRemovable(producer, this);
  if (BodyStore* owned = producer->getOwnedStore(); stores_.contains(owned, this)) stores_.remove(owned);
  producers_.remove(producer);
}

template <Scalar S>
auto SimulationT<S>::getRigidBody(const std::string& name) const -> Body* {
  for (const auto& b : bodies_)
    if (b->getName() == name) return b.get();
  return nullptr;
}

template <Scalar S>
bool SimulationT<S>::contains(const ContactListener* listener) const {
  return contactListeners_.contains(listener, this);
}

template <Scalar S>
void SimulationT<S>::installSpaceRules() {
  space_->setBodyPairFilter([this](const Body& a, const Body& b) { return jointedPairs_.filters(&a, &b); });
  space_->setSpeculationFilter([this](const Body& a, const Body& b) { return jointedPairs_.joins(&a, &b); });
  space_->setReductionRule([this](const Geometry& a, const Geometry& b) {
    std::optional<std::pair<ContactReductionMode, int>> rule;
    if (const auto* cm = materials_.getContactMaterial(a.getMaterial(), b.getMaterial()))
      rule.emplace(cm->getContactReductionMode(), cm->getContactReductionBinResolution());
    return rule;
  });
}

template <Scalar S>
auto SimulationT<S>::stepsTo(S t) const -> long long {
  const double steps = std::round((double(t) - double(getTimeStamp())) / double(timeStep_));
  if (steps > 2147483648.0)
    throw error("stepTo time is more than 2^31 steps of " + std::to_string(timeStep_) + " s away", t);
  return static_cast<long long>(steps);
}

template <Scalar S>
void SimulationT<S>::applyPendingTimeStep() {
  if (pendingTimeStep_) setTimeStep(*std::exchange(pendingTimeStep_, std::nullopt));
}

template <Scalar S>
void SimulationT<S>::notify(typename Listener::ActivationMask stage) {
  if (listeners_.empty()) return;
  std::vector<ref_ptr<Listener>> snapshot;
  for (const auto& l : listeners_)
    if (l->getMask() & stage) snapshot.push_back(l);
  std::stable_sort(snapshot.begin(), snapshot.end(),
                   [](const auto& a, const auto& b) { return a->getPriority() > b->getPriority(); });
  const S time = getTimeStamp();
  for (const auto& l : snapshot) {
    if (l->getSimulation() != this || !l->getEnable() || !(l->getMask() & stage)) continue;
    switch (stage) {
      case Listener::PRE_COLLIDE:
        l->preCollide(time);
        break;
      case Listener::PRE_STEP:
        l->pre(time);
        break;
      case Listener::POST_STEP:
        l->post(time);
        break;
      case Listener::LAST_STEP:
        l->last(time);
        break;
      default:
        break;
    }
  }
}

template <Scalar S>
void SimulationT<S>::notifyContacts() {
  if (contactListeners_.empty()) return;
  const std::vector<ref_ptr<ContactListener>> snapshot = contactListeners_.get();
  const S time = getTimeStamp();
  for (auto& contact : space_->getGeometryContacts()) {
    const auto stage = contact.isImpact() ? ContactListener::IMPACT : ContactListener::CONTACT;
    for (const auto& l : snapshot) {
      if (l->getSimulation() != this || !l->getEnable() || !(l->getMask() & stage) ||
          !l->matches(contact.geometry(0), contact.geometry(1)))
        continue;
      const auto policy = contact.isImpact() ? l->impact(time, &contact) : l->contact(time, &contact);
      if (policy == ContactListener::REMOVE_CONTACT) contact.setEnable(false);
    }
  }
  // A pair that a listener watches acts only once the listener has seen it
  // touch (and kept it): its speculative contact is left out.
  for (auto& contact : space_->getSpeculativeContacts())
    for (const auto& l : snapshot)
      if (l->getSimulation() == this && l->getEnable() &&
          (l->getMask() & (ContactListener::IMPACT | ContactListener::CONTACT)) &&
          l->matches(contact.geometry(0), contact.geometry(1))) {
        contact.setEnable(false);
        break;
      }
  for (auto pair : space_->getSeparations())
    for (const auto& l : snapshot)
      if (l->getSimulation() == this && l->getEnable() && (l->getMask() & ContactListener::SEPARATION) &&
          l->matches(pair.first.get(), pair.second.get()))
        l->separation(time, pair);
}

template <Scalar S>
void SimulationT<S>::addNested(Collection& collection) {
  std::unordered_set<const void*> seen;
  validateTree(collection, seen);
  validateConstraints(collection, seen);
  registerTree(collection);
}

template <Scalar S>
void SimulationT<S>::removeNested(Collection& collection) {
  ref_ptr<Collection> keep = &collection;
  for (const auto& b : collection.getRigidBodies())
    if (contains(b.get())) remove(b.get());
  for (const auto& l : collection.getEventListeners())
    if (l->getSimulation() == this) remove(l.get());
  for (const auto& c : collection.getConstraints())
    if (contains(c.get())) remove(c.get());
  Membership::simulationOf(collection) = nullptr;
  for (const auto& c : collection.getCollections()) removeNested(*c);
}

template <Scalar S>
void SimulationT<S>::validateTree(const Collection& collection, std::unordered_set<const void*>& seen) const {
  if (Membership::simulationOf(collection)) throw error("Collection is already in a simulation", collection.getName());
  if (!seen.insert(&collection).second) throw error("Collection appears twice", collection.getName());
  for (const auto& b : collection.getRigidBodies()) {
    bodies_.checkAddable(b.get(), this);
    for (const auto& g : b->getGeometries()) space_->requireSupported(*g);
    if (!seen.insert(b.get()).second) throw error("RigidBody appears twice in the collection", b->getName());
  }
  for (const auto& l : collection.getEventListeners()) {
    listeners_.checkAddable(l.get(), this);
    if (!seen.insert(l.get()).second)
      throw error("StepEventListener appears twice in the collection", collection.getName());
  }
  for (const auto& c : collection.getConstraints()) {
    constraints_.checkAddable(c.get(), this, c ? c->getKind() : nullptr);
    if (!seen.insert(c.get()).second)
      throw detail::makeError(c->getKind(), c->getName(), "appears twice in the collection");
  }
  for (const auto& c : collection.getCollections()) validateTree(*c, seen);
}

template <Scalar S>
void SimulationT<S>::validateConstraints(const Collection& collection,
                                         const std::unordered_set<const void*>& seen) const {
  for (const auto& c : collection.getConstraints()) checkBodiesOf(*c, &seen);
  for (const auto& child : collection.getCollections()) validateConstraints(*child, seen);
}

template <Scalar S>
void SimulationT<S>::checkBodiesOf(const Constraint& c, const std::unordered_set<const void*>* arriving) const {
  for (int i = 0; i < 2; ++i) {
    const Body* body = c.getBodyAt(i);
    if (body && !contains(body) && !(arriving && arriving->count(body)))
      throw detail::makeError(c.getKind(), c.getName(), "body not in this simulation; add the bodies first",
                              body->getName());
  }
  const auto movable = [](const Body* b) { return b && b->getMotionControl() != Body::STATIC; };
  if (!movable(c.getBodyAt(0)) && !movable(c.getBodyAt(1)))
    throw detail::makeError(c.getKind(), c.getName(), "needs at least one body that is not static",
                            c.getBodyAt(0)->getName());
}

template <Scalar S>
void SimulationT<S>::registerTree(Collection& collection) {
  registerMembers(collection);
  registerConstraints(collection);
}

template <Scalar S>
void SimulationT<S>::registerMembers(Collection& collection) {
  for (const auto& b : collection.getRigidBodies()) add(b);
  for (const auto& l : collection.getEventListeners()) add(l);
  Membership::simulationOf(collection) = this;
  for (const auto& c : collection.getCollections()) registerMembers(*c);
}

template <Scalar S>
void SimulationT<S>::registerConstraints(Collection& collection) {
  for (const auto& c : collection.getConstraints()) add(c);
  for (const auto& c : collection.getCollections()) registerConstraints(*c);
}

template <Scalar S>
void SimulationT<S>::setCollectionsSink(Collection& collection, detail::ContentSink<S>* sink) {
  Membership::simulationOf(collection) = sink;
  for (const auto& c : collection.getCollections()) setCollectionsSink(*c, sink);
}

#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE)
extern template class SimulationT<double>;
#endif
#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_SIMULATION_FLOAT)
extern template class SimulationT<float>;
#endif

using Simulation = SimulationT<double>;
using SimulationRef = ref_ptr<Simulation>;
namespace f32 {
using Simulation = SimulationT<float>;
using SimulationRef = ref_ptr<Simulation>;
}  // namespace f32

}  // namespace spook

// The step's definitions: in every translation unit of a header-only
// program, only where a simulation part is implemented otherwise
// (core/implementation.hpp).
#if defined(SPOOK_DEFINES_STEP)
#include <spook/sim/simulation_step.hpp>
#endif
