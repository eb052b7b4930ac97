#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <spook/collide/all_shapes.hpp>
#include <spook/collide/broadphase/sweep_and_prune.hpp>
#include <spook/collide/contact_reduction.hpp>
#include <spook/collide/contact_sink.hpp>
#include <spook/collide/geometry.hpp>
#include <spook/collide/geometry_contact.hpp>
#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/worker_pool.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook {

namespace detail {

/// The narrow-phase entry point of a space for one shape list, defined in
/// collide/collide_through.hpp with the colliders: a plain (not inline)
/// function template, so that with SPOOK_EXTERN_TEMPLATES the full shape
/// list's colliders are compiled once (core/implementation.hpp) and a
/// program that uses the default space does not even parse them.
template <Scalar S, class List>
bool collideThrough(const ShapeT<S>& a, const TransformT<S>& X_WA, const ShapeT<S>& b, const TransformT<S>& X_WB,
                    ContactSinkT<S>& sink);

/// Complete where collideThrough is defined (collide/collide_through.hpp).
template <class List>
struct CollidersDefined;

}  // namespace detail

/// How far a body may move within the coming step, for speculative
/// contacts (SpaceT::update): its center of mass by up to `linear` (m), and
/// it turns by up to `angular` (rad), so that a point at distance r from
/// the center of mass moves by up to linear + angular·r.
template <Scalar S>
struct StepReachT {
  S linear = S(0);
  S angular = S(0);
};

#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE)
extern template bool detail::collideThrough<double, AllShapes>(const ShapeT<double>&, const TransformT<double>&,
                                                               const ShapeT<double>&, const TransformT<double>&,
                                                               ContactSinkT<double>&);
#endif
#if defined(SPOOK_EXTERN_TEMPLATES) && !defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
extern template bool detail::collideThrough<float, AllShapes>(const ShapeT<float>&, const TransformT<float>&,
                                                              const ShapeT<float>&, const TransformT<float>&,
                                                              ContactSinkT<float>&);
#endif

/// Collision detection over a set of geometries: a broadphase (sweep and
/// prune), the narrow phase through the collider matrix of a shape list
/// chosen at construction (only those colliders are compiled), contact
/// reduction, and the impact / contact / separation bookkeeping. Usable on
/// its own for queries; a Simulation owns one and feeds it its bodies.
template <Scalar S>
class SpaceT : public Referenced {
 public:
  using Geometry = GeometryT<S>;
  using Body = RigidBodyT<S>;
  using Contact = GeometryContactT<S>;

  /// A space for every shape type.
  SpaceT() : SpaceT(AllShapes{}) {}
  /// A space for the shape types of `List`, e.g. ShapeList<SphereT, PlaneT>.
  /// A program that compiles spook once (SPOOK_EXTERN_TEMPLATES) has the
  /// full list's colliders compiled; for a list of its own it includes
  /// <spook/collide/collide_through.hpp>, which compiles that list's.
  template <template <class> class... Shapes>
  explicit SpaceT(ShapeList<Shapes...>)
      : collide_(&detail::collideThrough<S, ShapeList<Shapes...>>), contains_(&ShapeList<Shapes...>::contains) {
    static_assert(
        std::is_same_v<ShapeList<Shapes...>, AllShapes> ||
            requires { sizeof(detail::CollidersDefined<ShapeList<Shapes...>>); },
        "a Space or Simulation for a ShapeList of its own compiles that list's colliders: with "
        "SPOOK_EXTERN_TEMPLATES, include <spook/collide/collide_through.hpp>");
  }

  // --- Content ---------------------------------------------------------------

  /// Adds a geometry on its own (static, or of a body not in a simulation).
  /// Throws if it is null, already here, or holds a shape type outside this
  /// space's shape list.
  void add(ref_ptr<Geometry> geometry);
  /// Removes a geometry added with add(); false when it is not here.
  bool remove(Geometry* geometry);
  [[nodiscard]] const std::vector<ref_ptr<Geometry>>& getGeometries() const { return geometries_; }

  /// Throws unless every shape of `geometry` (composite children included)
  /// has a type in this space's shape list.
  void requireSupported(const Geometry& geometry) const;

  // --- Filters ---------------------------------------------------------------

  /// Enables or disables collisions between geometries of groups a and b.
  void setEnablePair(std::uint32_t a, std::uint32_t b, bool enable) { setPair(disabledIds_, a, b, enable); }
  void setEnablePair(const std::string& a, const std::string& b, bool enable) { setPair(disabledNames_, a, b, enable); }
  [[nodiscard]] bool getEnablePair(std::uint32_t a, std::uint32_t b) const {
    return !disabledIds_.count(std::minmax(a, b));
  }
  [[nodiscard]] bool getEnablePair(const std::string& a, const std::string& b) const {
    return !disabledNames_.count(std::minmax(a, b));
  }

  /// Vetoes pairs of geometries on two bodies: returns true for a pair that
  /// must not collide. A simulation sets it to leave out the bodies its
  /// constraints join (Constraint::setEnableCollisions).
  using BodyPairFilter = std::function<bool(const Body&, const Body&)>;
  void setBodyPairFilter(BodyPairFilter filter) { bodyPairFilter_ = std::move(filter); }
  /// Pairs of bodies collided without a speculative margin (update's
  /// reach): a simulation leaves out the bodies its constraints join, whose
  /// relative motion about their joint the gap's linear rate misjudges.
  void setSpeculationFilter(BodyPairFilter filter) { speculationFilter_ = std::move(filter); }

  /// True when the pair passes every filter: both enabled and colliding,
  /// not on one body, not both static, not disabled pairwise or by groups,
  /// not vetoed by the body pair filter.
  [[nodiscard]] bool canCollide(const Geometry& a, const Geometry& b) const;

  // --- Contact reduction -----------------------------------------------------

  [[nodiscard]] ContactReductionMode getContactReductionMode() const { return reductionMode_; }
  void setContactReductionMode(ContactReductionMode mode) { reductionMode_ = mode; }
  /// Bin resolution 1, 2 (default, fast) or 3 (higher fidelity).
  [[nodiscard]] int getContactBinResolution() const { return binResolution_; }
  void setContactBinResolution(int resolution);

  /// Overrides the reduction of some geometry pairs: the rule returns the
  /// mode and bin resolution for a pair, or nothing for the space's. A
  /// simulation sets it to follow its explicit contact materials.
  using ReductionRule =
      std::function<std::optional<std::pair<ContactReductionMode, int>>(const Geometry&, const Geometry&)>;
  void setReductionRule(ReductionRule rule) { reductionRule_ = std::move(rule); }

  // --- Collision detection ---------------------------------------------------

  /// Finds the contacts between this space's geometries and those of
  /// `bodies` (a simulation's), reduces them and marks impacts; pairs that
  /// touched before and no longer do are listed in getSeparations().
  /// With `workers`, the pairs are collided on its threads, with the same
  /// contacts in the same order. Two geometries of sleeping bodies
  /// (RigidBody::isSleeping) are not collided again: they keep the contact
  /// they had (nothing of theirs has moved).
  ///
  /// With `reach` (one per body of `bodies`), contacts are speculative: two
  /// geometries are collided with a margin of how far they may come closer
  /// within the step (each one's reach, at most kMaxSpeculativeFraction of
  /// its half-diagonal; none for sensors and for the body pairs of the
  /// speculation filter), and the colliders that support
  /// it (collider.hpp) also write the points where they are apart by less
  /// (negative depths). A pair with only such gap points is not a contact
  /// (no events, not in getGeometryContacts()): it is listed in
  /// getSpeculativeContacts(), for the solver.
  void update(const std::vector<ref_ptr<Body>>& bodies = {}, detail::WorkerPool* workers = nullptr,
              std::span<const StepReachT<S>> reach = {});

  /// The largest speculative margin of a geometry, as a fraction of its
  /// bounding box's half-diagonal: a body faster than that in a step may
  /// still be found overlapping (continuous collision is the remedy).
  static constexpr double kMaxSpeculativeFraction = 0.25;

  /// Fewest candidate pairs worth spreading over threads.
  static constexpr std::size_t kPairsWorthThreads = 64;

  /// The narrow phase of one pair of placed shapes (shape frame → world)
  /// through this space's colliders: their contact points into `sink`,
  /// normals from a toward b; false when the pair has no collider.
  bool collideShapes(const ShapeT<S>& a, const TransformT<S>& X_WA, const ShapeT<S>& b, const TransformT<S>& X_WB,
                     ContactSinkT<S>& sink) const {
    return collide_(a, X_WA, b, X_WB, sink);
  }

  /// Geometry pairs in contact after the last update(): each has a point of
  /// depth >= 0, and may have gap points too (negative depth).
  [[nodiscard]] std::vector<Contact>& getGeometryContacts() { return contacts_; }
  [[nodiscard]] const std::vector<Contact>& getGeometryContacts() const { return contacts_; }
  /// Geometry pairs apart by less than their speculative margin after the
  /// last update(): gap points only. Not reported as contacts.
  [[nodiscard]] std::vector<Contact>& getSpeculativeContacts() { return speculative_; }
  [[nodiscard]] const std::vector<Contact>& getSpeculativeContacts() const { return speculative_; }
  /// Pairs that were in contact the update before the last and no longer are.
  [[nodiscard]] const std::vector<GeometryPairT<S>>& getSeparations() const { return separations_; }
  /// Contact points the last update() dropped, before reduction, because a
  /// collider produced a non-finite position, normal or depth (e.g. shapes
  /// posed near the largest finite coordinate).
  [[nodiscard]] std::size_t getNumDroppedContactPoints() const { return numDroppedContactPoints_; }

 protected:
  ~SpaceT() override;

 private:
  using Access = detail::GeometryAccess<S>;
  using CollideFunction = bool (*)(const ShapeT<S>&, const TransformT<S>&, const ShapeT<S>&, const TransformT<S>&,
                                   ContactSinkT<S>&);

  static bool isFixed(const Body* body);

  void requireSupported(const Geometry& geometry, const ShapeT<S>& shape) const;

  template <class Key>
  static void setPair(std::set<std::pair<Key, Key>>& disabled, const Key& a, const Key& b, bool enable) {
    if (enable)
      disabled.erase(std::minmax(a, b));
    else
      disabled.insert(std::minmax(a, b));
  }

  /// The geometries to collide. A shape may have joined a geometry (or a
  /// composite) after the geometry was checked on add: it is checked here,
  /// before anything changes, rather than silently colliding with nothing.
  void gather(const std::vector<ref_ptr<Body>>& bodies);
  /// The speculative margin of each active geometry (m) for the bodies'
  /// reach, or none without it.
  void measureMargins(const std::vector<ref_ptr<Body>>& bodies, std::span<const StepReachT<S>> reach);

  /// Collides active_[i] with active_[j] at the poses update() took; a
  /// contact goes to `found`, points dropped as non-finite are counted.
  void narrowPhase(std::size_t i, std::size_t j, std::vector<Contact>& found, std::size_t& dropped) const;
  /// Every candidate pair of pairs_, in order, into contacts_.
  void narrowPhase(detail::WorkerPool* workers);

  // Each pair reduces as its rule says (the space's mode and resolution
  // unless a reduction rule overrides them); REDUCE_ALL pairs pool their
  // points per body pair, at the resolution of the pair's last contact.
  void reduce();

  /// Moves the pairs without a touching point from contacts_ to speculative_.
  void setSpeculativeApart();

  void trackEvents();

  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError("Space", "", what, value);
  }

  CollideFunction collide_;
  bool (*contains_)(ShapeType);
  std::vector<ref_ptr<Geometry>> geometries_;
  std::set<std::pair<std::uint32_t, std::uint32_t>> disabledIds_;
  std::set<std::pair<std::string, std::string>> disabledNames_;
  ContactReductionMode reductionMode_ = ContactReductionMode::REDUCE_GEOMETRY;
  ReductionRule reductionRule_;
  BodyPairFilter bodyPairFilter_, speculationFilter_;
  int binResolution_ = 2;

  std::vector<Geometry*> active_;
  /// Per active geometry: where its shapes' world poses of this update
  /// begin in shapePoses_ (one frame chain walk per geometry and step, not
  /// one per pair).
  std::vector<std::size_t> firstShapePose_;
  std::vector<TransformT<S>> shapePoses_;
  std::vector<BoundingBoxT<S>> boxes_;
  std::vector<S> margins_;  ///< per active geometry (m)
  detail::SweepAndPrune<S> broadphase_;
  /// The broad phase's pairs that may collide (canCollide), in its order.
  std::vector<std::pair<std::size_t, std::size_t>> pairs_;
  /// The last update's contacts, and (while a body sleeps) where each
  /// pair's stands among them, sorted by the pair's ids: what two sleeping
  /// bodies keep.
  std::vector<Contact> lastContacts_;
  std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, std::size_t>> lastContactOf_;
  /// Per piece of pairs_ on the threads: its contacts and dropped points.
  std::vector<std::vector<Contact>> piecesFound_;
  std::vector<std::size_t> piecesDropped_;
  std::vector<Contact> contacts_, speculative_;
  /// The pairs in contact after the last update(), sorted by their ids.
  std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, GeometryPairT<S>>> touching_, nowTouching_;
  std::vector<GeometryPairT<S>> separations_;
  std::size_t numDroppedContactPoints_ = 0;
};

template <Scalar S>
void SpaceT<S>::add(ref_ptr<Geometry> geometry) {
  if (!geometry) throw error("cannot add a null Geometry", "nullptr");
  if (Access::space(*geometry) == this)
    throw detail::makeError("Geometry", geometry->getName(), "already in this space");
  if (Access::space(*geometry)) throw detail::makeError("Geometry", geometry->getName(), "already in another space");
  requireSupported(*geometry);
  Access::space(*geometry) = this;
  geometries_.push_back(std::move(geometry));
}

template <Scalar S>
bool SpaceT<S>::remove(Geometry* geometry) {
  const auto it = std::find_if(geometries_.begin(), geometries_.end(), [&](const auto& g) { return g == geometry; });
  if (it == geometries_.end()) return false;
  Access::space(**it) = nullptr;
  geometries_.erase(it);
  return true;
}

template <Scalar S>
void SpaceT<S>::requireSupported(const Geometry& geometry) const {
  for (const auto& entry : geometry.getShapes()) requireSupported(geometry, *entry.shape);
}

template <Scalar S>
bool SpaceT<S>::canCollide(const Geometry& a, const Geometry& b) const {
  if (&a == &b || !a.getEnable() || !b.getEnable() || !a.getEnableCollisions() || !b.getEnableCollisions())
    return false;
  const Body* bodyA = a.getRigidBody();
  const Body* bodyB = b.getRigidBody();
  if (bodyA && bodyA == bodyB) return false;
  if (isFixed(bodyA) && isFixed(bodyB)) return false;
  if (!a.getEnableCollisions(&b)) return false;
  for (const auto id : a.getGroupIds())
    for (const auto other : b.getGroupIds())
      if (disabledIds_.count(std::minmax(id, other))) return false;
  for (const auto& name : a.getGroupNames())
    for (const auto& other : b.getGroupNames())
      if (disabledNames_.count(std::minmax(name, other))) return false;
  return !(bodyA && bodyB && bodyPairFilter_ && bodyPairFilter_(*bodyA, *bodyB));
}

template <Scalar S>
void SpaceT<S>::setContactBinResolution(int resolution) {
  if (resolution < 1 || resolution > 3) throw error("contact bin resolution must be 1, 2 or 3", resolution);
  binResolution_ = resolution;
}

template <Scalar S>
void SpaceT<S>::update(const std::vector<ref_ptr<Body>>& bodies, detail::WorkerPool* workers,
                       std::span<const StepReachT<S>> reach) {
  gather(bodies);
  boxes_.clear();
  firstShapePose_.clear();
  shapePoses_.clear();
  for (const Geometry* g : active_) {
    const TransformT<S> X_WG = g->getTransform();
    firstShapePose_.push_back(shapePoses_.size());
    for (const auto& e : g->getShapes()) shapePoses_.push_back(X_WG * e.transform);
    // Grown by the touching gap, within which the colliders count shapes as
    // touching: a box resting on another, its settling depth lost to float
    // round-off, stays a pair.
    boxes_.push_back(g->getBoundingBox(X_WG).grownBy(S(detail::kTouchingGap)));
  }
  measureMargins(bodies, reach);
  for (std::size_t k = 0; k < boxes_.size(); ++k)
    if (margins_[k] > S(0)) {
      boxes_[k].min.array() -= margins_[k];
      boxes_[k].max.array() += margins_[k];
    }
  pairs_.clear();
  broadphase_.findPairs(boxes_, [&](std::size_t i, std::size_t j) {
    if (canCollide(*active_[i], *active_[j])) pairs_.emplace_back(i, j);
  });
  std::swap(contacts_, lastContacts_);
  lastContactOf_.clear();
  if (std::any_of(active_.begin(), active_.end(),
                  [](const Geometry* g) { return g->getRigidBody() && g->getRigidBody()->isSleeping(); })) {
    for (std::size_t k = 0; k < lastContacts_.size(); ++k)
      lastContactOf_.emplace_back(
          std::make_pair(lastContacts_[k].geometry(0)->getId(), lastContacts_[k].geometry(1)->getId()), k);
    std::sort(lastContactOf_.begin(), lastContactOf_.end());
  }
  narrowPhase(workers);
  reduce();
  setSpeculativeApart();
  trackEvents();
}

template <Scalar S>
void SpaceT<S>::measureMargins(const std::vector<ref_ptr<Body>>& bodies, std::span<const StepReachT<S>> reach) {
  margins_.assign(active_.size(), S(0));
  if (reach.empty()) return;
  if (reach.size() != bodies.size()) throw error("needs one step reach per body, not", reach.size());
  // active_ lists this space's own geometries, then those of each enabled body in order (gather).
  std::size_t k = geometries_.size();
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const Body& body = *bodies[b];
    if (!body.getEnable()) continue;
    const StepReachT<S>& r = reach[b];
    for (std::size_t n = body.getGeometries().size(); n > 0; --n, ++k) {
      const BoundingBoxT<S>& box = boxes_[k];
      const S size = box.halfExtents().norm();
      const S arm = (box.center() - body.getCmPosition()).norm() + size;
      const S margin = std::min(r.linear + r.angular * arm, S(kMaxSpeculativeFraction) * size);
      if (std::isfinite(margin) && margin > S(0)) margins_[k] = margin;
    }
  }
}

template <Scalar S>
void SpaceT<S>::setSpeculativeApart() {
  speculative_.clear();
  std::size_t kept = 0;
  for (std::size_t k = 0; k < contacts_.size(); ++k) {
    const auto& points = contacts_[k].points();
    const bool touching = std::any_of(points.begin(), points.end(), [](const auto& p) { return p.depth >= S(0); });
    if (!touching)
      speculative_.push_back(std::move(contacts_[k]));
    else if (kept++ != k)
      contacts_[kept - 1] = std::move(contacts_[k]);
  }
  contacts_.erase(contacts_.begin() + std::ptrdiff_t(kept), contacts_.end());
}

template <Scalar S>
SpaceT<S>::~SpaceT() {
  for (auto& g : geometries_) Access::space(*g) = nullptr;
}

template <Scalar S>
bool SpaceT<S>::isFixed(const Body* body) {
  return !body || body->getMotionControl() == Body::STATIC;
}

template <Scalar S>
void SpaceT<S>::requireSupported(const Geometry& geometry, const ShapeT<S>& shape) const {
  if (!contains_(shape.getType()))
    throw detail::makeError("Geometry", geometry.getName(), "shape type not in this space's shape list",
                            std::string(shapeTypeName(shape.getType())));
  if (shape.getType() == ShapeType::COMPOSITE)
    for (const auto& child : static_cast<const CompositeT<S>&>(shape).getChildren())
      requireSupported(geometry, *child.shape);
}

template <Scalar S>
void SpaceT<S>::gather(const std::vector<ref_ptr<Body>>& bodies) {
  active_.clear();
  for (const auto& g : geometries_) active_.push_back(g.get());
  for (const auto& body : bodies)
    if (body->getEnable())
      for (const auto& g : body->getGeometries()) active_.push_back(g.get());
  for (const Geometry* g : active_) requireSupported(*g);
}

template <Scalar S>
void SpaceT<S>::narrowPhase(detail::WorkerPool* workers) {
  contacts_.clear();
  numDroppedContactPoints_ = 0;
  const int threads = workers ? workers->size() : 1;
  if (threads < 2 || pairs_.size() < kPairsWorthThreads) {
    for (const auto& [i, j] : pairs_) narrowPhase(i, j, contacts_, numDroppedContactPoints_);
    return;
  }
  // Contiguous pieces, a few per thread so that one slow piece (a trimesh
  // pair) does not hold the others up; joined in order.
  const std::size_t pieces = std::min<std::size_t>(4 * std::size_t(threads), pairs_.size() / 16);
  piecesFound_.resize(pieces);
  piecesDropped_.assign(pieces, 0);
  workers->forEach(pieces, [&](std::size_t piece, int) {
    piecesFound_[piece].clear();
    for (std::size_t k = pairs_.size() * piece / pieces, end = pairs_.size() * (piece + 1) / pieces; k < end; ++k)
      narrowPhase(pairs_[k].first, pairs_[k].second, piecesFound_[piece], piecesDropped_[piece]);
  });
  for (std::size_t piece = 0; piece < pieces; ++piece) {
    std::move(piecesFound_[piece].begin(), piecesFound_[piece].end(), std::back_inserter(contacts_));
    piecesFound_[piece].clear();
    numDroppedContactPoints_ += piecesDropped_[piece];
  }
}

template <Scalar S>
void SpaceT<S>::narrowPhase(std::size_t i, std::size_t j, std::vector<Contact>& found, std::size_t& dropped) const {
  // One order per pair, so that normals and event keys are stable.
  if (active_[i]->getId() > active_[j]->getId()) std::swap(i, j);
  Geometry* first = active_[i];
  Geometry* second = active_[j];
  const RigidBodyT<S>* body1 = first->getRigidBody();
  const RigidBodyT<S>* body2 = second->getRigidBody();
  if (body1 && body2 && body1->isSleeping() && body2->isSleeping()) {
    const auto key = std::make_pair(first->getId(), second->getId());
    const auto it = std::lower_bound(lastContactOf_.begin(), lastContactOf_.end(), std::make_pair(key, std::size_t(0)));
    if (it != lastContactOf_.end() && it->first == key) {
      // As the colliders gave it: every point enabled, reduced again below.
      Contact kept = lastContacts_[it->second];
      kept.setEnable(true);
      for (auto& point : kept.points()) point.enabled = true;
      found.push_back(std::move(kept));
    }
    return;
  }
  Contact contact(first, second);
  const bool speculative = !(first->isSensor() || second->isSensor() ||
                             (body1 && body2 && speculationFilter_ && speculationFilter_(*body1, *body2)));
  const S margin = speculative ? margins_[i] + margins_[j] : S(0);
  ContactSinkT<S> sink(contact.points(), false, margin);
  const auto& shapes1 = first->getShapes();
  const auto& shapes2 = second->getShapes();
  for (std::size_t k1 = 0; k1 < shapes1.size(); ++k1)
    for (std::size_t k2 = 0; k2 < shapes2.size(); ++k2)
      collide_(*shapes1[k1].shape, shapePoses_[firstShapePose_[i] + k1], *shapes2[k2].shape,
               shapePoses_[firstShapePose_[j] + k2], sink);
  dropped += sink.getNumDropped();
  if (!contact.points().empty()) found.push_back(std::move(contact));
}

template <Scalar S>
void SpaceT<S>::reduce() {
  std::vector<ContactPointT<S>*> points;
  std::map<std::pair<const void*, const void*>, std::pair<int, std::vector<ContactPointT<S>*>>> byBodies;
  for (auto& contact : contacts_) {
    ContactReductionMode mode = reductionMode_;
    int resolution = binResolution_;
    if (reductionRule_)
      if (const auto rule = reductionRule_(*contact.geometry(0), *contact.geometry(1)))
        std::tie(mode, resolution) = *rule;
    if (mode == ContactReductionMode::REDUCE_NONE) continue;
    if (mode == ContactReductionMode::REDUCE_GEOMETRY) {
      points.clear();
      for (auto& p : contact.points()) points.push_back(&p);
      detail::reduceContacts<S>(points, resolution);
      continue;
    }
    // Per body pair: a static geometry counts as its own "body".
    const void* k1 = contact.rigidBody(0) ? static_cast<const void*>(contact.rigidBody(0)) : contact.geometry(0);
    const void* k2 = contact.rigidBody(1) ? static_cast<const void*>(contact.rigidBody(1)) : contact.geometry(1);
    auto& [pairResolution, list] = byBodies[std::minmax(k1, k2)];
    pairResolution = resolution;
    for (auto& p : contact.points()) list.push_back(&p);
  }
  for (auto& [key, entry] : byBodies) detail::reduceContacts<S>(entry.second, entry.first);
}

template <Scalar S>
void SpaceT<S>::trackEvents() {
  const auto keyBelow = [](const auto& entry, const auto& key) { return entry.first < key; };
  const auto contains = [&](const auto& sorted, const auto& key) {
    const auto it = std::lower_bound(sorted.begin(), sorted.end(), key, keyBelow);
    return it != sorted.end() && it->first == key;
  };
  nowTouching_.clear();
  for (auto& contact : contacts_) {
    const auto key = std::make_pair(contact.geometry(0)->getId(), contact.geometry(1)->getId());
    contact.setImpact(!contains(touching_, key));
    nowTouching_.emplace_back(key, GeometryPairT<S>{contact.geometry(0), contact.geometry(1)});
  }
  const auto byKey = [](const auto& a, const auto& b) { return a.first < b.first; };
  std::sort(nowTouching_.begin(), nowTouching_.end(), byKey);
  nowTouching_.erase(std::unique(nowTouching_.begin(), nowTouching_.end(),
                                 [](const auto& a, const auto& b) { return a.first == b.first; }),
                     nowTouching_.end());
  separations_.clear();
  for (const auto& [key, pair] : touching_)
    if (!contains(nowTouching_, key)) separations_.push_back(pair);
  std::swap(touching_, nowTouching_);
}

SPOOK_COMPILED_ONCE(class, SpaceT)

using Space = SpaceT<double>;
using SpaceRef = ref_ptr<Space>;
namespace f32 {
using Space = SpaceT<float>;
using SpaceRef = ref_ptr<Space>;
}  // namespace f32

}  // namespace spook

// The colliders behind collideThrough: in every translation unit of a
// header-only program, only where a collider part is implemented otherwise.
#if !defined(SPOOK_EXTERN_TEMPLATES) || defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE) || \
    defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
#include <spook/collide/collide_through.hpp>
#endif
