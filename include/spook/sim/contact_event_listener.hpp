#pragma once

#include <concepts>
#include <cstdint>

#include <spook/collide/geometry_contact.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/time_stamp.hpp>
#include <spook/sim/listener_callbacks.hpp>

namespace spook {

template <Scalar S>
class SimulationT;
namespace detail {
struct SimulationMembership;
}

/// User code called on contact events after collision detection, before
/// the `pre` step listeners: impact (the first pass in which two geometries
/// touch), contact (each later pass while they touch) and separation (the
/// first pass after). Returning REMOVE_CONTACT from impact or contact
/// removes the contact from the solver (no rows, no forces); the other
/// listeners still see it, with isEnabled() false. An execution filter of
/// one or two geometries restricts the events to contacts involving them.
/// Listeners are called in the order added. Override the callbacks as
/// `KeepContactPolicy impact(const spook::TimeStamp& t, spook::GeometryContact* contact) override`;
/// adding a class whose member named like a callback does not override it,
/// or that overrides none of them, fails to compile.
template <Scalar S>
class ContactEventListenerT : public Referenced {
 public:
  enum ActivationMask : std::uint32_t {
    IMPACT = 1u << 0,
    CONTACT = 1u << 1,
    SEPARATION = 1u << 2,
    DEFAULT = IMPACT | CONTACT | SEPARATION
  };
  enum KeepContactPolicy { KEEP_CONTACT, REMOVE_CONTACT };
  using TimeStamp = TimeStampT<S>;

  explicit ContactEventListenerT(std::uint32_t mask = DEFAULT) : mask_(mask) {}

  virtual KeepContactPolicy impact(const TimeStamp& /*t*/, GeometryContactT<S>* /*contact*/) { return KEEP_CONTACT; }
  virtual KeepContactPolicy contact(const TimeStamp& /*t*/, GeometryContactT<S>* /*contact*/) { return KEEP_CONTACT; }
  virtual void separation(const TimeStamp& /*t*/, GeometryPairT<S>& /*pair*/) {}

  [[nodiscard]] std::uint32_t getMask() const { return mask_; }
  void setMask(std::uint32_t mask) { mask_ = mask; }
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  /// Events only for contacts of `first` (with anything), or of `first`
  /// with `second` when both are given; nullptr for both clears the filter.
  void setFilter(GeometryT<S>* first, GeometryT<S>* second = nullptr) {
    filterFirst_ = first;
    filterSecond_ = second;
    filtered_ = first || second;
  }
  /// True when the filter lets a contact between a and b through. A
  /// filter geometry that has been deleted matches nothing.
  [[nodiscard]] bool matches(const GeometryT<S>* a, const GeometryT<S>* b) const {
    if (!filtered_) return true;
    const GeometryT<S>* first = filterFirst_.get();
    const GeometryT<S>* second = filterSecond_.get();
    if (!first && !second) return false;
    if (first && second) return (a == first && b == second) || (a == second && b == first);
    const GeometryT<S>* one = first ? first : second;
    return a == one || b == one;
  }

  /// The simulation this listener is added to, or nullptr.
  [[nodiscard]] SimulationT<S>* getSimulation() const { return simulation_; }

 protected:
  ~ContactEventListenerT() override = default;

 private:
  friend struct detail::SimulationMembership;
  std::uint32_t mask_;
  bool enable_ = true;
  bool filtered_ = false;
  observer_ptr<GeometryT<S>> filterFirst_;
  observer_ptr<GeometryT<S>> filterSecond_;
  SimulationT<S>* simulation_ = nullptr;
};

namespace detail {
/// The callbacks of a ContactEventListener subclass L as `&L::name` shows them.
template <class L, Scalar S>
struct ContactCallbacks {
  using Base = ContactEventListenerT<S>;
  using Touch = typename Base::KeepContactPolicy(const TimeStampT<S>&, GeometryContactT<S>*);
  using Separation = void(const TimeStampT<S>&, GeometryPairT<S>&);
  static constexpr CallbackState impact = [] {
    if constexpr (requires { &L::impact; })
      return callbackState<Base, Touch, decltype(&L::impact)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr CallbackState contact = [] {
    if constexpr (requires { &L::contact; })
      return callbackState<Base, Touch, decltype(&L::contact)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr CallbackState separation = [] {
    if constexpr (requires { &L::separation; })
      return callbackState<Base, Separation, decltype(&L::separation)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr bool overridesAny = impact != CallbackState::INHERITED || contact != CallbackState::INHERITED ||
                                       separation != CallbackState::INHERITED;
};

/// Stops the compilation where a listener class L is added when one of its
/// callbacks would silently never be called.
template <class L, Scalar S>
constexpr void requireContactCallbacks() {
  using C = ContactCallbacks<L, S>;
  static_assert(C::impact != CallbackState::MISMATCHED,
                "ContactEventListener: this impact does not override ContactEventListener::impact and would never be "
                "called; declare it as KeepContactPolicy impact(const spook::TimeStamp& t, spook::GeometryContact* "
                "contact) override");
  static_assert(C::contact != CallbackState::MISMATCHED,
                "ContactEventListener: this contact does not override ContactEventListener::contact and would never "
                "be called; declare it as KeepContactPolicy contact(const spook::TimeStamp& t, "
                "spook::GeometryContact* contact) override");
  static_assert(C::separation != CallbackState::MISMATCHED,
                "ContactEventListener: this separation does not override ContactEventListener::separation and would "
                "never be called; declare it as void separation(const spook::TimeStamp& t, spook::GeometryPair& "
                "pair) override");
  static_assert(C::overridesAny,
                "ContactEventListener: this class overrides none of impact, contact, separation (a misspelt name?)");
}

/// A class derived from ContactEventListenerT<S> (not the base itself).
template <class L, class S>
concept ContactEventListenerClass =
    std::derived_from<L, ContactEventListenerT<S>> && !std::same_as<L, ContactEventListenerT<S>>;
}  // namespace detail

using ContactEventListener = ContactEventListenerT<double>;
using ContactEventListenerRef = ref_ptr<ContactEventListener>;
namespace f32 {
using ContactEventListener = ContactEventListenerT<float>;
using ContactEventListenerRef = ref_ptr<ContactEventListener>;
}  // namespace f32

}  // namespace spook
