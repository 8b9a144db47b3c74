#pragma once
// Reports a parallel loop's progress through a ProgressCallback: serialized, at most once per
// percent of the work items, and remembers a request to cancel.

#include <radiosity/error.h>
#include <radiosity/progress.h>

#include <algorithm>
#include <atomic>
#include <chrono>
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
    const size_t total = total_.load(std::memory_order_relaxed);
    const int percent = int(done * 100 / total);
    if (percent <= reported_.load(std::memory_order_relaxed)) return;
    std::lock_guard lock(mutex_);
    if (percent <= reported_.load(std::memory_order_relaxed)) return;
    reported_.store(percent, std::memory_order_relaxed);
    if (!callback_(std::min(double(done) / double(total), 1.0))) cancelled_.store(true);
  }

  /// Changes the count of work items, for work whose end is estimated as it goes (a solve
  /// until a tolerance); called between items, not while others tick.
  void setTotal(size_t total) { total_.store(std::max<size_t>(total, 1)); }

  bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }

  /// Asks the callback whether to stop, at most every 100 ms (from whichever thread comes first):
  /// for items that each take long (a pixel at a million samples, a voxel side's thousands of
  /// shadow rays), where tick() alone would ask too late for Ctrl-C.
  bool pollCancelled() {
    if (cancelled() || !callback_) return cancelled();
    using namespace std::chrono;
    const int64_t now = duration_cast<milliseconds>(steady_clock::now().time_since_epoch()).count();
    int64_t last = lastPollMs_.load(std::memory_order_relaxed);
    if (now - last < 100 || !lastPollMs_.compare_exchange_strong(last, now)) return false;
    std::lock_guard lock(mutex_);
    const double fraction = double(done_.load(std::memory_order_relaxed)) /
                            double(total_.load(std::memory_order_relaxed));
    if (!callback_(std::min(fraction, 1.0))) cancelled_.store(true);
    return cancelled();
  }
  /// Throws Cancelled if the callback asked to stop.
  void throwIfCancelled() const {
    if (cancelled()) throw Cancelled();
  }

 private:
  const ProgressCallback& callback_;
  std::atomic<size_t> total_;
  std::atomic<size_t> done_{0};
  std::atomic<int> reported_{-1};
  std::atomic<bool> cancelled_{false};
  std::atomic<int64_t> lastPollMs_{0};
  std::mutex mutex_;
};

}  // namespace rad
