#pragma once
// The form factors F_ij between patches as a sparse matrix: compressed rows (CSR) of float values,
// column indices sorted within each row. Entries below a threshold are dropped; the table counts
// what it dropped so that the loss can be reported.

#include <cstdint>
#include <span>
#include <vector>

namespace rad {

struct FormFactorEntry {
  uint32_t column = 0;
  float value = 0.0f;
};

class FormFactorTable {
 public:
  FormFactorTable() = default;
  /// Takes rows of (column, value) entries, each row sorted by column with every column once (as
  /// the estimators and symmetrize() make them; asserted), and keeps those >= threshold.
  /// rows.size() is the patch count.
  static FormFactorTable fromRows(std::vector<std::vector<FormFactorEntry>> rows, float threshold);
  /// Assembles a table from its arrays (offsets has rows + 1 entries); for the disk cache.
  static FormFactorTable fromArrays(std::vector<uint64_t> offsets, std::vector<uint32_t> columns,
                                    std::vector<float> values, double droppedEntries,
                                    double droppedSum);

  size_t rows() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  size_t nonZeros() const { return values_.size(); }
  std::span<const uint32_t> columns(size_t row) const {
    return {columns_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }
  std::span<const float> values(size_t row) const {
    return {values_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }
  double rowSum(size_t row) const;

  /// Enforces reciprocity A_i F_ij = A_j F_ji, both set from the mean of the two estimates of
  /// A_i F_ij (an absent entry is an estimate of 0), then drops entries below the threshold.
  void symmetrize(std::span<const float> area, float threshold = 0.0f);

  /// Fraction of the estimated nonzero entries, and of their total form factor (summed over all
  /// rows, relative to the rows' total), that the threshold dropped.
  double droppedEntryFraction() const { return droppedEntries_; }
  double droppedSumFraction() const { return droppedSum_; }
  size_t memoryBytes() const;

  const std::vector<uint64_t>& offsetArray() const { return offsets_; }
  const std::vector<uint32_t>& columnArray() const { return columns_; }
  const std::vector<float>& valueArray() const { return values_; }

 private:
  std::vector<uint64_t> offsets_;
  std::vector<uint32_t> columns_;
  std::vector<float> values_;
  double droppedEntries_ = 0.0, droppedSum_ = 0.0;
};

}  // namespace rad
