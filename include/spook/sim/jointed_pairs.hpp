#pragma once

#include <algorithm>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <spook/constraints/constraint.hpp>
#include <spook/core/pointer_pair_hash.hpp>
#include <spook/dynamics/rigid_body.hpp>

namespace spook::detail {

/// The body pairs that a simulation's constraints join directly, for the
/// default collision filter: the geometries of two bodies held together by
/// an enabled constraint do not collide with each other unless the
/// constraint asks for it (Constraint::setEnableCollisions), as PhysX's
/// joints and MuJoCo's parent–child filter do. A machine's links overlap at
/// their pins; contacts there would fight the joints. The world (a
/// constraint's missing second body) is no body: a body hinged to the world
/// still collides with the ground.
///
/// Kept up to date as constraints are added and removed (a constraint's
/// bodies never change); whether a pair is filtered is read at query time
/// from its few constraints, so enabling, disabling or switching collisions
/// on a constraint takes effect at once, without a scan of all constraints.
template <Scalar S>
class JointedPairs {
 public:
  using Body = RigidBodyT<S>;
  using Constraint = ConstraintT<S>;

  void add(const Constraint& constraint) {
    if (const auto key = keyOf(constraint)) byPair_[*key].push_back(&constraint);
  }
  void remove(const Constraint& constraint) {
    const auto key = keyOf(constraint);
    if (!key) return;
    const auto it = byPair_.find(*key);
    if (it == byPair_.end()) return;
    std::erase(it->second, &constraint);
    if (it->second.empty()) byPair_.erase(it);
  }

  /// True when an enabled constraint joins `a` and `b`.
  [[nodiscard]] bool joins(const Body* a, const Body* b) const {
    return anyConstraint(a, b, [](const Constraint* c) { return c->getEnable(); });
  }

  /// True when an enabled constraint joins `a` and `b` without allowing
  /// their geometries to collide.
  [[nodiscard]] bool filters(const Body* a, const Body* b) const {
    return anyConstraint(a, b, [](const Constraint* c) { return c->getEnable() && !c->getEnableCollisions(); });
  }

 private:
  using Key = std::pair<const Body*, const Body*>;

  template <class Predicate>
  [[nodiscard]] bool anyConstraint(const Body* a, const Body* b, Predicate predicate) const {
    if (!a || !b || byPair_.empty()) return false;
    const auto it = byPair_.find(std::minmax(a, b));
    return it != byPair_.end() && std::any_of(it->second.begin(), it->second.end(), predicate);
  }

  static std::optional<Key> keyOf(const Constraint& constraint) {
    const Body* a = constraint.getBodyAt(0);
    const Body* b = constraint.getBodyAt(1);
    if (!a || !b) return std::nullopt;
    return std::minmax(a, b);
  }

  std::unordered_map<Key, std::vector<const Constraint*>, PointerPairHash> byPair_;
};

}  // namespace spook::detail
