#pragma once
// The form factors F_ij between patches as a sparse matrix: compressed rows (CSR) of float values,
// column indices sorted within each row. A threshold drops small entries without losing light
// (thresholdRow, FormFactorTable::applyThreshold); the table counts what it dropped so that the
// distortion can be reported.

#include <cstdint>
#include <span>
#include <vector>

#include "core/vector_memory.h"

namespace rad {

struct FormFactorEntry {
  uint32_t column = 0;
  float value = 0.0f;
};

/// What a threshold dropped, before the kept entries were rescaled.
struct ThresholdLoss {
  double entryFraction = 0.0;       ///< of the nonzero entries
  double sumFraction = 0.0;         ///< of the rows' total form factor
  double worstRowFraction = 0.0;    ///< of one row's sum, the largest
  uint64_t rowsOverOnePercent = 0;  ///< rows that lost more than 1% of their sum
};

/// One row's sum and entry count before and after a threshold.
struct RowThresholding {
  double total = 0.0, kept = 0.0;
  size_t entries = 0, keptEntries = 0;
};
/// What a threshold dropped from these rows, together.
ThresholdLoss lossOf(std::span<const RowThresholding> rows);
/// Thresholds row i read as where patch i's light goes (F_ij: the share of it that reaches j):
/// drops the entries below `threshold` but the row's largest, and scales the rest so that the row
/// keeps its sum, so the light that would have gone through the dropped entries goes to the
/// patches that i sees most instead of being lost. Entries that are not positive are dropped.
RowThresholding thresholdRow(std::vector<FormFactorEntry>& row, float threshold);

/// Entry (i, j) of a symmetrized table (FormFactorTable::symmetrize) from the two estimates,
/// F_ij by i's rays and F_ji by j's (0 for none), and the areas: the one formula, in floats and
/// doubles as symmetrize() has it, so that a table updated in place (patch/table_update.h) holds
/// the same bits as one symmetrized whole.
inline float reciprocalMean(float fij, float fji, float ai, float aj) {
  const float sent = aj * fji;  // A_j F_ji
  const double fromI = fij, fromJ = double(sent) / double(aj);
  return float((fromI + fromJ) * aj / (double(ai) + aj));
}

class FormFactorTable {
 public:
  FormFactorTable() = default;
  /// Takes rows of (column, value) entries, each row sorted by column with every column once (as
  /// the estimators and symmetrize() make them; asserted), and keeps the positive ones.
  /// rows.size() is the patch count.
  static FormFactorTable fromRows(std::vector<std::vector<FormFactorEntry>> rows);
  /// Assembles a table from its arrays (offsets has rows + 1 entries); for the disk cache.
  static FormFactorTable fromArrays(std::vector<uint64_t> offsets, std::vector<uint32_t> columns,
                                    std::vector<float> values, const ThresholdLoss& loss);

  /// A table of rows `counts[i]` entries long, their entries left to write through rowColumns
  /// and rowValues (each row's columns ascending, values positive). It takes the arrays of
  /// `storage` (a table no longer needed), whose memory is then written again without the
  /// system having to provide (and zero) fresh pages.
  static FormFactorTable withRowSizes(std::span<const uint64_t> counts,
                                      FormFactorTable storage = {});
  std::span<uint32_t> rowColumns(size_t row) {
    return {columns_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }
  std::span<float> rowValues(size_t row) {
    return {values_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }

  size_t rows() const { return offsets_.empty() ? 0 : offsets_.size() - 1; }
  size_t nonZeros() const { return values_.size(); }
  std::span<const uint32_t> columns(size_t row) const {
    return {columns_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }
  std::span<const float> values(size_t row) const {
    return {values_.data() + offsets_[row], size_t(offsets_[row + 1] - offsets_[row])};
  }
  double rowSum(size_t row) const;

  /// Enforces reciprocity A_i F_ij = A_j F_ji, both set from the two estimates of A_i F_ij (an
  /// absent entry is an estimate of 0) weighted by their inverse variances (equal rays a patch):
  /// A_i A_j (F_ij + F_ji) / (A_i + A_j).
  void symmetrize(std::span<const float> area);

  /// Drops small entries of a reciprocal table (A_i F_ij = A_j F_ji) without losing light: each
  /// row, as the patch's outgoing light, is thresholded by thresholdRow (the rows of the patches
  /// marked in `keepRows`, the emitters, whose light is the direct light, stay whole), and the
  /// table becomes the reciprocal transpose of the result, F_ij = F'_ji A_j / A_i: what each
  /// patch gathers is then what the others send it, so the power leaving every patch is
  /// preserved exactly. Nothing happens for a threshold of 0.
  void applyThreshold(std::span<const float> area, float threshold,
                      std::span<const uint8_t> keepRows = {});

  /// What closeRows() found and did.
  struct ClosureRepair {
    size_t rows = 0;        ///< rows whose sum exceeded 1 + noise, scaled back
    double worstSum = 0.0;  ///< the largest row sum before
  };
  /// Scales back the rows whose sum exceeds 1 + `noise` (no patch sends on more light than
  /// reaches it): entry (i, j) times min(s_i, s_j), s_i = 1 / sum_i for those rows and 1 for the
  /// rest. Every row then sums to at most 1 + noise, and a reciprocal table stays reciprocal
  /// (both entries of a pair take one factor).
  ClosureRepair closeRows(double noise);

  /// What boundReflection() found and did.
  struct ReflectionBound {
    size_t patches = 0;       ///< patches whose column was scaled back
    double worstShare = 0.0;  ///< the largest reflected share q_j before
  };
  /// Makes the radiosity iteration unable to grow. Patch j's reflected share is
  /// q_j = sum_i rho_i A_i F_ij / A_j (`rho`: each patch's largest channel): of the light j sends
  /// (to i, A_i F_ij / A_j of it, as shooting reads the table), the share that comes back
  /// reflected; for a reciprocal table, its row's sum weighted by the reflectances,
  /// sum_i rho_i F_ji. Patches with q_j above `limit` (below 1) are scaled back, entry (i, j)
  /// times min(s_i, s_j), s_j = limit / q_j, which keeps reciprocity. Afterwards every q is at
  /// most `limit` (to float rounding): a Gauss-Seidel step, a shot or a Jacobi sweep passes a
  /// patch's residual power (A |r|) on times its q, so the residual's power, sum_i A_i |r_i|,
  /// never grows. A reciprocal row summing to at most 1 is never touched when every rho is at
  /// most `limit`.
  ReflectionBound boundReflection(std::span<const float> rho, std::span<const float> area,
                                  double limit);

  /// What applyThreshold dropped.
  const ThresholdLoss& thresholdLoss() const { return loss_; }
  size_t memoryBytes() const;

  std::span<const uint64_t> offsetArray() const { return offsets_; }
  std::span<const uint32_t> columnArray() const { return columns_; }
  std::span<const float> valueArray() const { return values_; }

 private:
  // Filled in parallel after they are sized: not zeroed first (FilledLaterVector).
  FilledLaterVector<uint64_t> offsets_;
  FilledLaterVector<uint32_t> columns_;
  FilledLaterVector<float> values_;
  ThresholdLoss loss_;
};

}  // namespace rad
