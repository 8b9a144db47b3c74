#pragma once
// What the processes of a split run (ProcessShare) compute together, on the library's own types:
// arrays of colours summed, a count summed, a block-split array gathered. Each is called by
// every process, and each is nothing (or the value itself) for one process.

#include <radiosity/process_share.h>
#include <radiosity/types.h>

#include <cstring>
#include <span>
#include <type_traits>
#include <vector>

namespace rad {

/// `colours` in every process replaced by their element-wise sum over the processes (in
/// ProcessShare::sumAll's fixed order). Where each element is one process's and the others hold
/// zeros, the sum is that element exactly.
inline void sumOverProcesses(const ProcessShare& processes, std::vector<Color>& colours) {
  if (!processes.split()) return;
  static_assert(sizeof(Color) == 3 * sizeof(float), "colours are summed as floats");
  processes.sumAll(std::span<float>(reinterpret_cast<float*>(colours.data()), 3 * colours.size()));
}

/// `value` summed over the processes in rank order.
template <typename T>
T sumOverProcesses(const ProcessShare& processes, T value) {
  static_assert(std::is_arithmetic_v<T>);
  if (!processes.split()) return value;
  const std::vector<char> all = processes.gatherAll(
      std::span<const char>(reinterpret_cast<const char*>(&value), sizeof value));
  T sum = 0;
  for (size_t at = 0; at + sizeof value <= all.size(); at += sizeof value) {
    T v{};
    std::memcpy(&v, all.data() + at, sizeof v);
    sum += v;
  }
  return sum;
}

/// Each process's block (ProcessShare::block) of `values`, as it computed it, into every
/// process.
template <typename T>
void gatherBlocks(const ProcessShare& processes, std::vector<T>& values) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (!processes.split()) return;
  const auto [first, last] = processes.block(values.size());
  const std::vector<char> all = processes.gatherAll(std::span<const char>(
      reinterpret_cast<const char*>(values.data() + first), (last - first) * sizeof(T)));
  std::memcpy(static_cast<void*>(values.data()), all.data(), values.size() * sizeof(T));
}

}  // namespace rad
