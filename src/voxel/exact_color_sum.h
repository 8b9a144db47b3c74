#pragma once
// Colours added exactly, so that a sum comes out the same, bit for bit, however its terms are
// split among processes and in whatever order their parts are added: each channel is kept as
// an integer count of a fixed unit, a power of two, and integer addition does not round. The
// voxel sweep adds the light of each fixed block of direction pairs here, so one process and
// any split of the blocks among processes give the same bounce.

#include <radiosity/process_share.h>
#include <radiosity/types.h>

#include <cstdint>
#include <span>
#include <vector>

namespace rad {

class ExactColorSum {
 public:
  /// `size` colours of zero, counted in units of `unit` (a power of two, so that converting
  /// to and from the counts only shifts exponents before the one rounding to a whole count).
  /// Magnitudes up to 2^62 units are kept; larger ones saturate there.
  ExactColorSum(size_t size, float unit);

  /// Adds `values` (one a colour) to the sum.
  void add(std::span<const Color> values);
  /// Replaces the sum in every process by the sum over the processes.
  void sumOverProcesses(const ProcessShare& processes);
  /// The sum, as colours.
  void store(std::span<Color> out) const;

  static constexpr uint64_t kBytesPerColor = 3 * sizeof(int64_t);

 private:
  std::vector<int64_t> counts_;  ///< three a colour
  double perUnit_, unit_;
};

}  // namespace rad
