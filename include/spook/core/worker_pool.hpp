#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include <spook/core/implementation.hpp>

namespace spook::detail {

/// The threads of a simulation (SimulationT::setNumThreads), for the parts
/// of a step that split into independent pieces: the narrow phase's pairs,
/// the islands' solves. Each piece writes only its own output and the step
/// merges the outputs in the pieces' order, so its results are the same bit
/// for bit whatever the number of threads.
class WorkerPool {
 public:
  WorkerPool() = default;
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;
  ~WorkerPool();

  /// Threads that take part in a run, the calling one included (>= 1).
  [[nodiscard]] int size() const { return static_cast<int>(threads_.size()) + 1; }
  /// Starts or stops threads so that size() is n (>= 1); not during a run.
  void resize(int n);

  /// Calls f(index, worker) once for every index in [0, count), spread over
  /// the threads; `worker` in [0, size()) names the calling thread's slot
  /// (0: the thread that called forEach), for per-thread scratch. Returns
  /// when all calls have returned; then rethrows the first exception one of
  /// them threw (the others still ran).
  void forEach(std::size_t count, const std::function<void(std::size_t, int)>& f);

 private:
  void serve(int worker, std::uint64_t seen);
  void runTask(int worker);
  void stopThreads();

  std::vector<std::thread> threads_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  std::uint64_t generation_ = 0;
  bool stop_ = false;
  std::size_t busy_ = 0;
  std::function<void(int)> task_;
  std::exception_ptr error_;
};

#if defined(SPOOK_DEFINES_NON_TEMPLATES)
SPOOK_INLINE WorkerPool::~WorkerPool() { stopThreads(); }

SPOOK_INLINE void WorkerPool::resize(int n) {
  if (n == size()) return;
  stopThreads();
  for (int worker = 1; worker < n; ++worker) threads_.emplace_back(&WorkerPool::serve, this, worker, generation_);
}

SPOOK_INLINE void WorkerPool::stopThreads() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  stop_ = false;
}

SPOOK_INLINE void WorkerPool::forEach(std::size_t count, const std::function<void(std::size_t, int)>& f) {
  if (threads_.empty() || count < 2) {
    for (std::size_t i = 0; i < count; ++i) f(i, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    task_ = [&](int worker) {
      for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) f(i, worker);
    };
    error_ = nullptr;
    busy_ = threads_.size();
    ++generation_;
  }
  wake_.notify_all();
  runTask(0);
  std::exception_ptr error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return busy_ == 0; });
    task_ = nullptr;
    std::swap(error, error_);
  }
  if (error) std::rethrow_exception(error);
}

SPOOK_INLINE void WorkerPool::runTask(int worker) {
  try {
    task_(worker);
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!error_) error_ = std::current_exception();
  }
}

SPOOK_INLINE void WorkerPool::serve(int worker, std::uint64_t seen) {
  for (;;) {
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
    }
    runTask(worker);
    std::lock_guard<std::mutex> lock(mutex_);
    if (--busy_ == 0) done_.notify_one();
  }
}
#endif

}  // namespace spook::detail
