#pragma once

#include <concepts>
#include <cstddef>
#include <functional>
#include <utility>

namespace spook {

/// Intrusive strong pointer to a Referenced object. Converts to T* like the
/// AGX-style API expects, so `sim->add(body)` takes a ref_ptr or a raw pointer.
template <class T>
class ref_ptr {
 public:
  using element_type = T;

  ref_ptr() noexcept = default;
  ref_ptr(std::nullptr_t) noexcept {}
  ref_ptr(T* object) noexcept : ptr_(object) { acquire(); }
  ref_ptr(const ref_ptr& other) noexcept : ptr_(other.ptr_) { acquire(); }
  ref_ptr(ref_ptr&& other) noexcept : ptr_(std::exchange(other.ptr_, nullptr)) {}
  // clang-format off
  template <class Y>
    requires std::convertible_to<Y*, T*>
  ref_ptr(const ref_ptr<Y>& other) noexcept : ptr_(other.get()) { acquire(); }
  // clang-format on
  ~ref_ptr() { release(); }

  ref_ptr& operator=(ref_ptr other) noexcept {
    std::swap(ptr_, other.ptr_);
    return *this;
  }

  [[nodiscard]] T* get() const noexcept { return ptr_; }
  T& operator*() const noexcept { return *ptr_; }
  T* operator->() const noexcept { return ptr_; }
  operator T*() const noexcept { return ptr_; }
  [[nodiscard]] bool valid() const noexcept { return ptr_ != nullptr; }

  /// Gives up ownership without deleting: the caller takes the reference.
  [[nodiscard]] T* releaseNoDelete() noexcept {
    T* object = std::exchange(ptr_, nullptr);
    if (object) object->unreferenceNoDelete();
    return object;
  }

 private:
  void acquire() const noexcept {
    if (ptr_) ptr_->reference();
  }
  void release() noexcept {
    if (ptr_) std::exchange(ptr_, nullptr)->unreference();
  }

  T* ptr_ = nullptr;
};

}  // namespace spook

template <class T>
struct std::hash<spook::ref_ptr<T>> {
  std::size_t operator()(const spook::ref_ptr<T>& p) const noexcept { return std::hash<T*>()(p.get()); }
};
