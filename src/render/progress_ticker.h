#pragma once
// Reports a parallel loop's progress through a ProgressCallback: serialized, at most once per
// percent of the work items, and remembers a request to cancel.

#include <radiosity/error.h>
#include <radiosity/progress.h>

#include <atomic>
#include <cstddef>
#include <mutex>

namespace rad {

class ProgressTicker {
 public:
  ProgressTicker(const ProgressCallback& callback, size_t total)
      : callback_(callback), total_(total == 0 ? 1 : total) {}

  /// Marks one item done; calls back when another percent is complete.
  void tick() {
    const size_t done = done_.fetch_add(1, std::memory_order_relaxed) + 1;
    if (!callback_) return;
    const int percent = int(done * 100 / total_);
    if (percent <= reported_.load(std::memory_order_relaxed)) return;
    std::lock_guard lock(mutex_);
    if (percent <= reported_.load(std::memory_order_relaxed)) return;
    reported_.store(percent, std::memory_order_relaxed);
    if (!callback_(double(done) / double(total_))) cancelled_.store(true);
  }

  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
  /// Throws Cancelled if the callback asked to stop.
  void throwIfCancelled() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  const ProgressCallback& callback_;
  size_t total_;
  std::atomic<size_t> done_{0};
  std::atomic<int> reported_{-1};
  std::atomic<bool> cancelled_{false};
  std::mutex mutex_;
};

}  // namespace rad
