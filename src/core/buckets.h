#pragma once
// Items sorted into buckets in parallel, each bucket keeping the order of its sources: a
// transpose without a sort (a table's columns into rows, a list of pairs by its second member).
// The sources are cut into a fixed number of runs; each run counts its items per bucket, then
// writes them to its own places in every bucket, so the result does not depend on the threads.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/vector_memory.h"

namespace rad {

template <typename T>
struct Buckets {
  std::vector<uint64_t> start;  ///< bucket b's items are [start[b], start[b + 1])
  FilledLaterVector<T> items;   ///< not zeroed first: every place is written
  std::span<const T> of(size_t b) const {
    return {items.data() + start[b], size_t(start[b + 1] - start[b])};
  }
};

/// Buckets 0..n-1 of the items `each(source, put)` puts (put(bucket, item)) for each source of
/// `sources`, in their order. `each` is called twice per source, from several threads.
template <typename T, class Each>
Buckets<T> bucketed(size_t n, std::span<const uint32_t> sources, const Each& each) {
  constexpr size_t kRuns = 16;
  const size_t runLength = (sources.size() + kRuns - 1) / kRuns;
  auto run = [&](size_t r) {
    const size_t first = std::min(sources.size(), r * runLength);
    return sources.subspan(first, std::min(runLength, sources.size() - first));
  };
  // place[r * n + b]: where run r writes its next item of bucket b (first its count).
  std::vector<uint64_t> place(kRuns * n, 0);
  tbb::parallel_for(size_t(0), kRuns, [&](size_t r) {
    uint64_t* count = place.data() + r * n;
    for (uint32_t s : run(r)) each(s, [&](uint32_t bucket, const T&) { ++count[bucket]; });
  });
  Buckets<T> b;
  b.start.assign(n + 1, 0);
  for (size_t i = 0; i < n; ++i) {
    uint64_t at = b.start[i];
    for (size_t r = 0; r < kRuns; ++r) {
      const uint64_t count = place[r * n + i];
      place[r * n + i] = at;
      at += count;
    }
    b.start[i + 1] = at;
  }
  b.items.resize(b.start.back());
  tbb::parallel_for(size_t(0), kRuns, [&](size_t r) {
    uint64_t* next = place.data() + r * n;
    for (uint32_t s : run(r))
      each(s, [&](uint32_t bucket, const T& item) { b.items[next[bucket]++] = item; });
  });
  return b;
}

}  // namespace rad
