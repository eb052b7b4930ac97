#pragma once

#include <cstdint>

#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/core/scalar.hpp>

namespace spook {

template <Scalar S>
class SimulationT;
namespace detail {
struct SimulationMembership;
}

/// User code in the step loop. Override the callbacks you need and select
/// them with the mask; each receives the time stamp at the start of the step
/// (s). A listener may add or remove objects, itself included, from its
/// callbacks. Listeners with a higher priority are called first; equal
/// priorities run in the order they were added.
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

  explicit StepEventListenerT(std::uint32_t mask = DEFAULT, int priority = 0) : mask_(mask), priority_(priority) {}

  virtual void preCollide(S /*timeStamp*/) {}
  virtual void pre(S /*timeStamp*/) {}
  virtual void post(S /*timeStamp*/) {}
  virtual void last(S /*timeStamp*/) {}

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

using StepEventListener = StepEventListenerT<double>;
using StepEventListenerRef = ref_ptr<StepEventListener>;
namespace f32 {
using StepEventListener = StepEventListenerT<float>;
using StepEventListenerRef = ref_ptr<StepEventListener>;
}  // namespace f32

}  // namespace spook
