#pragma once

#include <concepts>
#include <cstddef>
#include <utility>

#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>

namespace spook {

/// Non-owning pointer that reads as null once the object has been deleted;
/// breaks ownership cycles (a listener watching a body, a body's simulation).
template <class T>
class observer_ptr {
 public:
  observer_ptr() noexcept = default;
  observer_ptr(std::nullptr_t) noexcept {}
  observer_ptr(T* object) : ptr_(object), hub_(object ? object->observerHub() : nullptr) {
    if (hub_) hub_->reference();
  }
  /// From a strong pointer, as in `RigidBodyObserver o = bodyRef;`.
  // clang-format off
  template <class Y>
    requires std::convertible_to<Y*, T*>
  observer_ptr(const ref_ptr<Y>& object) : observer_ptr(static_cast<T*>(object.get())) {}
  // clang-format on
  observer_ptr(const observer_ptr& other) noexcept : ptr_(other.ptr_), hub_(other.hub_) {
    if (hub_) hub_->reference();
  }
  observer_ptr(observer_ptr&& other) noexcept
      : ptr_(std::exchange(other.ptr_, nullptr)), hub_(std::exchange(other.hub_, nullptr)) {}
  ~observer_ptr() {
    if (hub_) hub_->unreference();
  }

  observer_ptr& operator=(observer_ptr other) noexcept {
    std::swap(ptr_, other.ptr_);
    std::swap(hub_, other.hub_);
    return *this;
  }

  /// The object, or nullptr when it is gone (or was never set).
  [[nodiscard]] T* get() const noexcept { return hub_ && hub_->alive() ? ptr_ : nullptr; }
  T* operator->() const noexcept { return get(); }
  T& operator*() const noexcept { return *get(); }
  operator T*() const noexcept { return get(); }
  [[nodiscard]] bool valid() const noexcept { return get() != nullptr; }

 private:
  T* ptr_ = nullptr;
  detail::ObserverHub* hub_ = nullptr;
};

}  // namespace spook
