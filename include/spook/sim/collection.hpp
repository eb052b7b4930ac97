#pragma once

#include <algorithm>
#include <string>
#include <unordered_set>
#include <vector>

#include <spook/constraints/constraint.hpp>
#include <spook/core/error.hpp>
#include <spook/core/frame.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/membership.hpp>
#include <spook/sim/step_event_listener.hpp>

namespace spook {

template <Scalar S>
class CollectionT;

namespace detail {
/// What a collection forwards to once it is part of a simulation.
template <Scalar S>
class ContentSink {
 public:
  virtual void add(ref_ptr<RigidBodyT<S>> body) = 0;
  virtual void remove(RigidBodyT<S>* body) = 0;
  [[nodiscard]] virtual bool contains(const RigidBodyT<S>* body) const = 0;
  [[nodiscard]] virtual bool contains(const StepEventListenerT<S>* listener) const = 0;
  virtual void add(ref_ptr<StepEventListenerT<S>> listener) = 0;
  virtual void remove(StepEventListenerT<S>* listener) = 0;
  virtual void add(ref_ptr<ConstraintT<S>> constraint) = 0;
  virtual void remove(ConstraintT<S>* constraint) = 0;
  [[nodiscard]] virtual bool contains(const ConstraintT<S>* constraint) const = 0;
  virtual void addNested(CollectionT<S>& collection) = 0;
  virtual void removeNested(CollectionT<S>& collection) = 0;

 protected:
  ~ContentSink() = default;
};
}  // namespace detail

/// A named group of bodies, constraints, listeners and other collections, added to and
/// removed from a simulation as one. While the collection is in a
/// simulation, what is added to it is added to the simulation too.
template <Scalar S>
class CollectionT : public Referenced {
 public:
  using Body = RigidBodyT<S>;
  using Listener = StepEventListenerT<S>;

  explicit CollectionT(std::string name = "") : name_(std::move(name)) {}

  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  void add(ref_ptr<Body> body);
  /// Adds a listener of class L, checked at compile time as by
  /// SimulationT::add (detail::requireStepCallbacks).
  template <detail::StepEventListenerClass<S> L>
  void add(const ref_ptr<L>& listener) {
    detail::requireStepCallbacks<L, S>();
    add(ref_ptr<Listener>(listener));
  }
  template <detail::StepEventListenerClass<S> L>
  void add(L* listener) {
    add(ref_ptr<L>(listener));
  }
  void add(ref_ptr<Listener> listener);
  /// Adds a constraint; in a simulation, its bodies must be there already.
  void add(ref_ptr<ConstraintT<S>> constraint);
  void add(ref_ptr<CollectionT> child);

  void remove(Body* body);
  void remove(Listener* listener);
  void remove(ConstraintT<S>* constraint);
  void remove(CollectionT* child);

  [[nodiscard]] const std::vector<ref_ptr<Body>>& getRigidBodies() const { return bodies_; }
  [[nodiscard]] const std::vector<ref_ptr<Listener>>& getEventListeners() const { return listeners_; }
  [[nodiscard]] const std::vector<ref_ptr<ConstraintT<S>>>& getConstraints() const { return constraints_; }
  [[nodiscard]] const std::vector<ref_ptr<CollectionT>>& getCollections() const { return children_; }

  /// True when `other` is this collection or nested anywhere inside it.
  [[nodiscard]] bool containsCollection(const CollectionT* other) const;

  /// Calls f on every body of this collection and its nested collections.
  template <class F>
  void forEachRigidBody(F&& f) const {
    for (const auto& b : bodies_) f(*b);
    for (const auto& c : children_) c->forEachRigidBody(f);
  }

 protected:
  ~CollectionT() override = default;

  /// Collects, once each, the bodies and assembly frames that move with this
  /// collection (a body may be reachable through several nested collections).
  virtual void gatherMovable(std::vector<Body*>& bodies, std::vector<FrameT<S>*>& frames,
                             std::unordered_set<const void*>& seen) const;

  [[nodiscard]] virtual const char* kind() const { return "Collection"; }

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError(kind(), name_, what, value);
  }

 private:
  friend struct detail::SimulationMembership;

  template <class T>
  static auto find(std::vector<ref_ptr<T>>& items, const T* item) {
    return std::find_if(items.begin(), items.end(), [&](const auto& p) { return p.get() == item; });
  }
  template <class T>
  static bool contains(const std::vector<ref_ptr<T>>& items, const T* item) {
    return std::any_of(items.begin(), items.end(), [&](const auto& p) { return p.get() == item; });
  }

  std::string name_;
  std::vector<ref_ptr<Body>> bodies_;
  std::vector<ref_ptr<Listener>> listeners_;
  std::vector<ref_ptr<ConstraintT<S>>> constraints_;
  std::vector<ref_ptr<CollectionT>> children_;
  detail::ContentSink<S>* simulation_ = nullptr;
};

template <Scalar S>
void CollectionT<S>::add(ref_ptr<Body> body) {
  if (!body) throw error("cannot add a null RigidBody", "nullptr");
  if (contains(bodies_, body.get())) throw error("RigidBody already added", body->getName());
  if (simulation_) simulation_->add(body);
  bodies_.push_back(std::move(body));
}

template <Scalar S>
void CollectionT<S>::add(ref_ptr<Listener> listener) {
  if (!listener) throw error("cannot add a null StepEventListener", "nullptr");
  if (contains(listeners_, listener.get())) throw error("StepEventListener already added", "listener");
  if (simulation_) simulation_->add(listener);
  listeners_.push_back(std::move(listener));
}

template <Scalar S>
void CollectionT<S>::add(ref_ptr<ConstraintT<S>> constraint) {
  if (!constraint) throw error("cannot add a null Constraint", "nullptr");
  if (contains(constraints_, constraint.get())) throw error("Constraint already added", constraint->getName());
  if (simulation_) simulation_->add(constraint);
  constraints_.push_back(std::move(constraint));
}

template <Scalar S>
void CollectionT<S>::add(ref_ptr<CollectionT> child) {
  if (!child) throw error("cannot add a null Collection", "nullptr");
  if (contains(children_, child.get())) throw error("Collection already added", child->getName());
  if (child.get() == this || child->containsCollection(this))
    throw error("Collection would contain itself", child->getName());
  if (simulation_) simulation_->addNested(*child);
  children_.push_back(std::move(child));
}

template <Scalar S>
void CollectionT<S>::remove(Body* body) {
  auto it = find(bodies_, body);
  if (it == bodies_.end()) throw error("RigidBody was never added", body ? body->getName() : "nullptr");
  if (simulation_ && simulation_->contains(body)) simulation_->remove(body);
  bodies_.erase(it);
}

template <Scalar S>
void CollectionT<S>::remove(Listener* listener) {
  auto it = find(listeners_, listener);
  if (it == listeners_.end()) throw error("StepEventListener was never added", "listener");
  if (simulation_ && simulation_->contains(listener)) simulation_->remove(listener);
  listeners_.erase(it);
}

template <Scalar S>
void CollectionT<S>::remove(ConstraintT<S>* constraint) {
  auto it = find(constraints_, constraint);
  if (it == constraints_.end())
    throw error("Constraint was never added", constraint ? constraint->getName() : "nullptr");
  if (simulation_ && simulation_->contains(constraint)) simulation_->remove(constraint);
  constraints_.erase(it);
}

template <Scalar S>
void CollectionT<S>::remove(CollectionT* child) {
  auto it = find(children_, child);
  if (it == children_.end()) throw error("Collection was never added", child ? child->getName() : "nullptr");
  if (simulation_) simulation_->removeNested(*child);
  children_.erase(it);
}

template <Scalar S>
bool CollectionT<S>::containsCollection(const CollectionT* other) const {
  if (other == this) return true;
  return std::any_of(children_.begin(), children_.end(), [&](const auto& c) { return c->containsCollection(other); });
}

template <Scalar S>
void CollectionT<S>::gatherMovable(std::vector<Body*>& bodies, std::vector<FrameT<S>*>& frames,
                                   std::unordered_set<const void*>& seen) const {
  for (const auto& b : bodies_)
    if (seen.insert(b.get()).second) bodies.push_back(b.get());
  for (const auto& c : children_) c->gatherMovable(bodies, frames, seen);
}

SPOOK_COMPILED_ONCE(class, CollectionT)

using Collection = CollectionT<double>;
using CollectionRef = ref_ptr<Collection>;
namespace f32 {
using Collection = CollectionT<float>;
using CollectionRef = ref_ptr<Collection>;
}  // namespace f32

}  // namespace spook
