#pragma once
// Lowers this process's address-space limit (ulimit -v) for the lifetime of an object, to what
// the process holds now plus `room` bytes: how tests make a run short of memory on purpose.

#include <radiosity/process_memory.h>
#include <sys/resource.h>

#include <cstdint>

namespace rad::test {

class AddressSpaceLimit {
 public:
  explicit AddressSpaceLimit(uint64_t room) {
    const uint64_t size = virtualBytes();
    if (size == 0 || getrlimit(RLIMIT_AS, &saved_) != 0) return;
    rlimit lowered = saved_;
    lowered.rlim_cur = size + room;
    alreadyBelow_ = saved_.rlim_cur != RLIM_INFINITY && saved_.rlim_cur < lowered.rlim_cur;
    lowered_ = !alreadyBelow_ && setrlimit(RLIMIT_AS, &lowered) == 0;
  }
  ~AddressSpaceLimit() {
    if (lowered_) setrlimit(RLIMIT_AS, &saved_);
  }
  AddressSpaceLimit(const AddressSpaceLimit&) = delete;
  AddressSpaceLimit& operator=(const AddressSpaceLimit&) = delete;

  /// True when the limit now leaves `room`; false when it could not be read or set.
  bool lowered() const { return lowered_; }
  /// True when the process was already limited below that (a test then has nothing to show).
  bool alreadyBelow() const { return alreadyBelow_; }

 private:
  rlimit saved_{};
  bool lowered_ = false, alreadyBelow_ = false;
};

}  // namespace rad::test
