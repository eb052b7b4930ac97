#pragma once

#include <cstdint>

#include <spook/collide/geometry_contact.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

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
/// disables the contact: listeners called later and the solver do not see
/// it. An execution filter of one or two geometries restricts the events
/// to contacts involving them. Listeners are called in the order added.
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

  explicit ContactEventListenerT(std::uint32_t mask = DEFAULT) : mask_(mask) {}

  virtual KeepContactPolicy impact(S /*timeStamp*/, GeometryContactT<S>* /*contact*/) { return KEEP_CONTACT; }
  virtual KeepContactPolicy contact(S /*timeStamp*/, GeometryContactT<S>* /*contact*/) { return KEEP_CONTACT; }
  virtual void separation(S /*timeStamp*/, GeometryPairT<S>& /*pair*/) {}

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

using ContactEventListener = ContactEventListenerT<double>;
using ContactEventListenerRef = ref_ptr<ContactEventListener>;
namespace f32 {
using ContactEventListener = ContactEventListenerT<float>;
using ContactEventListenerRef = ref_ptr<ContactEventListener>;
}  // namespace f32

}  // namespace spook
