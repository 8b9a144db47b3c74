#pragma once
// Rows of a table computed in shares by the processes of a split run, to every process: each
// sends the rows it owns, every row its length and then its entries, and every process takes
// them all. Entries are copied as bytes (trivially copyable, no padding to send).

#include <radiosity/process_share.h>

#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace rad {

/// Which rows a process computes: a block of consecutive rows (ProcessShare::block: rows of
/// one cost), or every count-th row from its rank (rows whose cost varies along the table).
enum class RowShare { Blocks, Interleaved };

/// Calls f(i) for each of the n rows that `rank` owns, in increasing order.
template <typename F>
void forEachRowOf(const ProcessShare& processes, RowShare share, size_t n, int rank, F&& f) {
  if (share == RowShare::Blocks) {
    const auto [begin, end] = processes.block(n, rank);
    for (size_t i = begin; i < end; ++i) f(i);
  } else {
    for (size_t i = size_t(rank); i < n; i += size_t(processes.count)) f(i);
  }
}

/// The rows of n that this process computes (all of them in one process), in increasing order.
inline std::vector<uint32_t> rowsOf(const ProcessShare& processes, RowShare share, size_t n) {
  std::vector<uint32_t> rows;
  forEachRowOf(processes, share, n, processes.rank, [&](size_t i) { rows.push_back(uint32_t(i)); });
  return rows;
}

/// Every process's own rows (as `share` says) into every process.
template <typename Entry>
void exchangeRows(const ProcessShare& processes, RowShare share,
                  std::vector<std::vector<Entry>>& rows) {
  static_assert(std::is_trivially_copyable_v<Entry>);
  std::vector<char> mine;
  forEachRowOf(processes, share, rows.size(), processes.rank, [&](size_t i) {
    const uint32_t count = uint32_t(rows[i].size());
    mine.insert(mine.end(), reinterpret_cast<const char*>(&count),
                reinterpret_cast<const char*>(&count) + sizeof count);
    const auto* bytes = reinterpret_cast<const char*>(rows[i].data());
    mine.insert(mine.end(), bytes, bytes + count * sizeof(Entry));
  });
  const std::vector<char> all = processes.gatherAll(mine);
  size_t at = 0;
  for (int rank = 0; rank < processes.count; ++rank)
    forEachRowOf(processes, share, rows.size(), rank, [&](size_t i) {
      uint32_t count = 0;
      std::memcpy(&count, all.data() + at, sizeof count);
      at += sizeof count;
      rows[i].resize(count);
      std::memcpy(static_cast<void*>(rows[i].data()), all.data() + at, count * sizeof(Entry));
      at += count * sizeof(Entry);
    });
}

}  // namespace rad
