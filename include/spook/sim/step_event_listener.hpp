#pragma once

#include <concepts>
#include <cstdint>

#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>
#include <spook/core/time_stamp.hpp>
#include <spook/sim/listener_callbacks.hpp>

namespace spook {

template <Scalar S>
class SimulationT;
namespace detail {
struct SimulationMembership;
}

/// User code in the step loop. Override the callbacks you need, as
/// `void pre(const spook::TimeStamp& t) override`, and select them with the
/// mask; each receives the time stamp at the start of the step (s). Adding a
/// listener to a simulation or collection refuses, at compile time, a class
/// with a member named like a callback that does not override it (another
/// signature) or that overrides none of them. A listener may add or remove
/// objects, itself included, from its callbacks. Listeners with a higher
/// priority are called first; equal priorities run in the order they were
/// added.
template <Scalar S>
class StepEventListenerT : public Referenced {
 public:
  enum ActivationMask : std::uint32_t {
    PRE_COLLIDE = 1u << 0,  ///< before collision detection
    PRE_STEP = 1u << 1,     ///< after collision detection, before the dynamics
    POST_STEP = 1u << 2,    ///< after the dynamics: new positions and velocities
    LAST_STEP = 1u << 3,    ///< last in the step, before the time stamp advances
    DEFAULT = PRE_COLLIDE | PRE_STEP | POST_STEP | LAST_STEP
  };

  using TimeStamp = TimeStampT<S>;

  explicit StepEventListenerT(std::uint32_t mask = DEFAULT, int priority = 0) : mask_(mask), priority_(priority) {}

  virtual void preCollide(const TimeStamp& /*t*/) {}
  virtual void pre(const TimeStamp& /*t*/) {}
  virtual void post(const TimeStamp& /*t*/) {}
  virtual void last(const TimeStamp& /*t*/) {}

  [[nodiscard]] std::uint32_t getMask() const { return mask_; }
  void setMask(std::uint32_t mask) { mask_ = mask; }
  [[nodiscard]] int getPriority() const { return priority_; }
  void setPriority(int priority) { priority_ = priority; }
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }

  /// The simulation this listener is added to, or nullptr.
  [[nodiscard]] SimulationT<S>* getSimulation() const { return simulation_; }

 protected:
  ~StepEventListenerT() override = default;

 private:
  friend struct detail::SimulationMembership;
  std::uint32_t mask_;
  int priority_;
  bool enable_ = true;
  SimulationT<S>* simulation_ = nullptr;
};

namespace detail {
/// The callbacks of a StepEventListener subclass L as `&L::name` shows them.
template <class L, Scalar S>
struct StepCallbacks {
  using Base = StepEventListenerT<S>;
  using Signature = void(const TimeStampT<S>&);
  static constexpr CallbackState preCollide = [] {
    if constexpr (requires { &L::preCollide; })
      return callbackState<Base, Signature, decltype(&L::preCollide)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr CallbackState pre = [] {
    if constexpr (requires { &L::pre; })
      return callbackState<Base, Signature, decltype(&L::pre)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr CallbackState post = [] {
    if constexpr (requires { &L::post; })
      return callbackState<Base, Signature, decltype(&L::post)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr CallbackState last = [] {
    if constexpr (requires { &L::last; })
      return callbackState<Base, Signature, decltype(&L::last)>();
    else
      return CallbackState::UNKNOWN;
  }();
  static constexpr bool overridesAny = preCollide != CallbackState::INHERITED || pre != CallbackState::INHERITED ||
                                       post != CallbackState::INHERITED || last != CallbackState::INHERITED;
};

/// Stops the compilation where a listener class L is added when one of its
/// callbacks would silently never be called.
template <class L, Scalar S>
constexpr void requireStepCallbacks() {
  using C = StepCallbacks<L, S>;
  static_assert(C::preCollide != CallbackState::MISMATCHED,
                "StepEventListener: this preCollide does not override StepEventListener::preCollide and would never "
                "be called; declare it as void preCollide(const spook::TimeStamp& t) override");
  static_assert(C::pre != CallbackState::MISMATCHED,
                "StepEventListener: this pre does not override StepEventListener::pre and would never be called; "
                "declare it as void pre(const spook::TimeStamp& t) override");
  static_assert(C::post != CallbackState::MISMATCHED,
                "StepEventListener: this post does not override StepEventListener::post and would never be called; "
                "declare it as void post(const spook::TimeStamp& t) override");
  static_assert(C::last != CallbackState::MISMATCHED,
                "StepEventListener: this last does not override StepEventListener::last and would never be called; "
                "declare it as void last(const spook::TimeStamp& t) override");
  static_assert(C::overridesAny,
                "StepEventListener: this class overrides none of preCollide, pre, post, last (a misspelt name?); "
                "declare them as void pre(const spook::TimeStamp& t) override");
}

/// A class derived from StepEventListenerT<S> (not the base itself).
template <class L, class S>
concept StepEventListenerClass = std::derived_from<L, StepEventListenerT<S>> && !std::same_as<L, StepEventListenerT<S>>;
}  // namespace detail

using StepEventListener = StepEventListenerT<double>;
using StepEventListenerRef = ref_ptr<StepEventListener>;
namespace f32 {
using StepEventListener = StepEventListenerT<float>;
using StepEventListenerRef = ref_ptr<StepEventListener>;
}  // namespace f32

}  // namespace spook
