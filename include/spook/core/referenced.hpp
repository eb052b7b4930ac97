#pragma once

#include <atomic>

namespace spook {

namespace detail {

/// Shared between an object and its observers; outlives the object while
/// observers hold it, and tells them whether the object is still alive.
class ObserverHub {
 public:
  void reference() noexcept { count_.fetch_add(1, std::memory_order_relaxed); }
  void unreference() noexcept {
    if (count_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
  }
  [[nodiscard]] bool alive() const noexcept { return alive_.load(std::memory_order_acquire); }
  void markDead() noexcept { alive_.store(false, std::memory_order_release); }

 private:
  std::atomic<int> count_{1};
  std::atomic<bool> alive_{true};
};

}  // namespace detail

/// Base of every long-lived spook object: an intrusive, atomic reference
/// count. Objects live on the heap, are held by ref_ptr and are deleted when
/// the last ref_ptr lets go; the protected destructor forbids stack objects.
class Referenced {
 public:
  Referenced(const Referenced&) = delete;
  Referenced& operator=(const Referenced&) = delete;

  void reference() const noexcept { count_.fetch_add(1, std::memory_order_relaxed); }

  /// Drops one reference; deletes the object when it was the last.
  void unreference() const noexcept {
    if (count_.fetch_sub(1, std::memory_order_acq_rel) == 1) delete this;
  }

  /// Drops one reference without deleting, for handing an object out of a
  /// function that created it.
  void unreferenceNoDelete() const noexcept { count_.fetch_sub(1, std::memory_order_acq_rel); }

  [[nodiscard]] int getReferenceCount() const noexcept { return count_.load(std::memory_order_relaxed); }

  /// The hub observers of this object share; created on first use.
  detail::ObserverHub* observerHub() const {
    detail::ObserverHub* hub = hub_.load(std::memory_order_acquire);
    if (hub) return hub;
    auto* fresh = new detail::ObserverHub();
    if (hub_.compare_exchange_strong(hub, fresh, std::memory_order_acq_rel)) return fresh;
    fresh->unreference();
    return hub;
  }

 protected:
  Referenced() = default;
  virtual ~Referenced() {
    if (detail::ObserverHub* hub = hub_.load(std::memory_order_acquire)) {
      hub->markDead();
      hub->unreference();
    }
  }

 private:
  mutable std::atomic<int> count_{0};
  mutable std::atomic<detail::ObserverHub*> hub_{nullptr};
};

}  // namespace spook
