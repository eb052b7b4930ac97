#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <spook/core/error.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/sim/membership.hpp>

namespace spook::detail {

/// The objects of one kind in a simulation (bodies, constraints, listeners,
/// stores, producers): the checks every kind shares (null, added twice, in
/// another simulation, never added), the object's membership fields, and
/// their release when the simulation goes. A kind's own rules (a body's
/// shapes, a constraint's bodies) stay with its add(); a new kind is one
/// more roster.
///
/// kIndexed: the object keeps its position (simulationIndex_) for O(1)
/// removal, which swaps the last object into its place; otherwise removal
/// keeps the order (listeners are called, stores indexed, in that order).
template <class T, bool kIndexed = false>
class Roster {
 public:
  using Membership = SimulationMembership;

  explicit Roster(const char* kind) : kind_(kind) {}
  Roster(const Roster&) = delete;
  Roster& operator=(const Roster&) = delete;
  ~Roster() {
    for (const auto& object : objects_) Membership::simulationOf(*object) = nullptr;
  }

  /// Throws unless `object` can join `owner`; `kind` names it in the error
  /// (default: the roster's kind).
  void checkAddable(const T* object, const void* owner, const char* kind = nullptr) const {
    kind = kind ? kind : kind_;
    if (!object) throw makeError("Simulation", "", std::string("cannot add a null ") + kind, "nullptr");
    const void* current = Membership::simulationOf(*object);
    if (current == owner) throw makeError(kind, nameOf(*object), "already added to this simulation");
    if (current) throw makeError(kind, nameOf(*object), "already belongs to another simulation");
  }
  void checkRemovable(const T* object, const void* owner, const char* kind = nullptr) const {
    kind = kind ? kind : kind_;
    if (!object) throw makeError("Simulation", "", std::string("cannot remove a null ") + kind, "nullptr");
    if (Membership::simulationOf(*object) != owner)
      throw makeError(kind, nameOf(*object), "was never added to this simulation");
  }

  /// Adds a checked object (checkAddable and the kind's own checks passed).
  template <class Owner>
  void add(ref_ptr<T> object, Owner* owner) {
    if constexpr (kIndexed) Membership::indexOf(*object) = objects_.size();
    Membership::simulationOf(*object) = owner;
    objects_.push_back(std::move(object));
    ++version_;
  }
  /// Removes a checked object (checkRemovable passed).
  void remove(T* object) {
    ref_ptr<T> keep = object;
    if constexpr (kIndexed) {
      const std::size_t index = Membership::indexOf(*object);
      std::swap(objects_[index], objects_.back());
      Membership::indexOf(*objects_[index]) = index;
      objects_.pop_back();
    } else {
      objects_.erase(std::find_if(objects_.begin(), objects_.end(), [&](const auto& o) { return o.get() == object; }));
    }
    Membership::simulationOf(*object) = nullptr;
    ++version_;
  }
  [[nodiscard]] bool contains(const T* object, const void* owner) const {
    return object && Membership::simulationOf(*object) == owner;
  }

  [[nodiscard]] const std::vector<ref_ptr<T>>& get() const { return objects_; }
  [[nodiscard]] std::size_t size() const { return objects_.size(); }
  /// Counts the adds and removes.
  [[nodiscard]] std::uint64_t version() const { return version_; }
  [[nodiscard]] bool empty() const { return objects_.empty(); }
  [[nodiscard]] const ref_ptr<T>& operator[](std::size_t i) const { return objects_[i]; }
  [[nodiscard]] auto begin() const { return objects_.begin(); }
  [[nodiscard]] auto end() const { return objects_.end(); }

 private:
  static std::string nameOf(const T& object) {
    if constexpr (requires { object.getName(); })
      return object.getName();
    else
      return "";
  }

  const char* kind_;
  std::vector<ref_ptr<T>> objects_;
  std::uint64_t version_ = 0;
};

}  // namespace spook::detail
