#pragma once
// One solve split among several processes (MPI ranks; the library knows no MPI: the command
// line's `mpirun` support fills this in). Each process takes a block of the work, and sumAll
// adds the processes' arrays element by element in a fixed order, so that every process ends with
// the same sum, whatever the timing.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <utility>
#include <vector>

namespace rad {

struct ProcessShare {
  int rank = 0, count = 1;
  /// Replaces `values` in every process by the sum over the processes (in a fixed order). Called
  /// by every process with arrays of one length. Empty when count is 1.
  std::function<void(std::span<float> values)> sumAll;
  /// Replaces `values` in every process by the sum over the processes: integers, so the sum is
  /// exact and the order does not matter. Called by every process with arrays of one length.
  /// Empty when count is 1.
  std::function<void(std::span<int64_t> values)> sumIntegers;
  /// Every process's `bytes`, concatenated in rank order, in every process. Called by every
  /// process. Empty when count is 1.
  std::function<std::vector<char>(std::span<const char> bytes)> gatherAll;

  bool split() const { return count > 1; }
  /// Rank r's block [begin, end) of n items: the blocks of the ranks in order, their sizes
  /// differing by one at most.
  std::pair<size_t, size_t> block(size_t n, int r) const {
    return {n * size_t(r) / size_t(count), n * size_t(r + 1) / size_t(count)};
  }
  /// This process's block.
  std::pair<size_t, size_t> block(size_t n) const { return block(n, rank); }
};

}  // namespace rad
