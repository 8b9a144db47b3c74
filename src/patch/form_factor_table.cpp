// Compressed sparse rows of form factors. Reciprocity averaging as in Cohen and Wallace,
// "Radiosity and Realistic Image Synthesis" (1993), section 4.9: A_i F_ij and A_j F_ji estimate
// the same quantity, so a weighted mean of the two (by inverse variance) has less variance than
// either, and the averaged table satisfies reciprocity exactly, which shooting (which uses
// F_ij A_i / A_j for F_ji) and gathering then agree on.
#include "patch/form_factor_table.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cassert>
#include <memory>

#include "core/buckets.h"
#include "core/vector_memory.h"

namespace rad {

FormFactorTable FormFactorTable::fromRows(std::vector<std::vector<FormFactorEntry>> rows) {
  FormFactorTable t;
  tbb::parallel_for(size_t(0), rows.size(), [&](size_t i) {
    auto& row = rows[i];
    assert(std::adjacent_find(row.begin(), row.end(), [](const auto& a, const auto& b) {
             return a.column >= b.column;
           }) == row.end());
    std::erase_if(row, [](const FormFactorEntry& e) { return !(e.value > 0.0f); });
  });
  t.offsets_.assign(rows.size() + 1, 0);
  for (size_t i = 0; i < rows.size(); ++i) t.offsets_[i + 1] = t.offsets_[i] + rows[i].size();
  t.columns_.resize(t.offsets_.back());
  t.values_.resize(t.offsets_.back());
  tbb::parallel_for(size_t(0), rows.size(), [&](size_t i) {
    for (size_t k = 0; k < rows[i].size(); ++k) {
      t.columns_[t.offsets_[i] + k] = rows[i][k].column;
      t.values_[t.offsets_[i] + k] = rows[i][k].value;
    }
    releaseMemory(rows[i]);
  });
  return t;
}

FormFactorTable FormFactorTable::withRowSizes(std::span<const uint64_t> counts,
                                              FormFactorTable storage) {
  FormFactorTable t = std::move(storage);
  t.loss_ = {};
  t.offsets_.assign(counts.size() + 1, 0);
  for (size_t i = 0; i < counts.size(); ++i) t.offsets_[i + 1] = t.offsets_[i] + counts[i];
  t.columns_.resize(t.offsets_.back());
  t.values_.resize(t.offsets_.back());
  return t;
}

FormFactorTable FormFactorTable::fromArrays(std::vector<uint64_t> offsets,
                                            std::vector<uint32_t> columns,
                                            std::vector<float> values, const ThresholdLoss& loss) {
  FormFactorTable t;
  t.offsets_.assign(offsets.begin(), offsets.end());
  t.columns_.assign(columns.begin(), columns.end());
  t.values_.assign(values.begin(), values.end());
  t.loss_ = loss;
  return t;
}

RowThresholding thresholdRow(std::vector<FormFactorEntry>& row, float threshold) {
  RowThresholding sums;
  sums.entries = row.size();
  float largest = 0.0f;
  for (const FormFactorEntry& e : row) {
    sums.total += e.value;
    largest = std::max(largest, e.value);
  }
  const float bar = std::min(threshold, largest);
  std::erase_if(row,
                [bar](const FormFactorEntry& e) { return e.value <= 0.0f || !(e.value >= bar); });
  for (const FormFactorEntry& e : row) sums.kept += e.value;
  sums.keptEntries = row.size();
  if (threshold > 0.0f && sums.kept > 0.0 && sums.kept < sums.total) {
    const double scale = sums.total / sums.kept;  // 1 / (1 - the share dropped)
    for (FormFactorEntry& e : row) e.value = float(e.value * scale);
  }
  return sums;
}

ThresholdLoss lossOf(std::span<const RowThresholding> rows) {
  ThresholdLoss loss;
  double total = 0.0, kept = 0.0, entries = 0.0, keptEntries = 0.0;
  for (const RowThresholding& row : rows) {
    total += row.total;
    kept += row.kept;
    entries += double(row.entries);
    keptEntries += double(row.keptEntries);
    if (!(row.total > 0.0)) continue;
    const double lost = 1.0 - row.kept / row.total;
    loss.worstRowFraction = std::max(loss.worstRowFraction, lost);
    if (lost > 0.01) ++loss.rowsOverOnePercent;
  }
  loss.entryFraction = entries > 0.0 ? 1.0 - keptEntries / entries : 0.0;
  loss.sumFraction = total > 0.0 ? 1.0 - kept / total : 0.0;
  return loss;
}

void FormFactorTable::applyThreshold(std::span<const float> area, float threshold,
                                     std::span<const uint8_t> keepRows) {
  if (!(threshold > 0.0f)) return;
  const size_t n = rows();
  std::vector<std::vector<FormFactorEntry>> sent(n);
  std::vector<RowThresholding> sums(n);
  tbb::parallel_for(size_t(0), n, [&](size_t j) {
    for (size_t k = 0; k < columns(j).size(); ++k) sent[j].push_back({columns(j)[k], values(j)[k]});
    sums[j] = thresholdRow(sent[j], keepRows.empty() || !keepRows[j] ? threshold : 0.0f);
  });
  const ThresholdLoss loss = lossOf(sums);
  // Gathering row i lists, in increasing j, what each patch j sends to i.
  std::vector<std::vector<FormFactorEntry>> gathered(n);
  for (uint32_t j = 0; j < n; ++j) {
    for (const FormFactorEntry& e : sent[j])
      gathered[e.column].push_back({j, float(double(e.value) * area[j] / area[e.column])});
    releaseMemory(sent[j]);
  }
  *this = fromRows(std::move(gathered));
  loss_ = loss;
}

double FormFactorTable::rowSum(size_t row) const {
  double s = 0.0;
  for (float v : values(row)) s += v;
  return s;
}

void FormFactorTable::symmetrize(std::span<const float> area) {
  // The transpose: row i lists (k, F_ki) for everyone k who sees i, in increasing k (bucketed:
  // the same table whatever the threads did, with no sort).
  const size_t n = rows();
  struct Sent {
    uint32_t column;
    float value;
  };
  std::vector<uint32_t> everyRow(n);
  for (size_t k = 0; k < n; ++k) everyRow[k] = uint32_t(k);
  Buckets<Sent> transpose = bucketed<Sent>(n, everyRow, [&](uint32_t k, auto&& put) {
    for (uint64_t e = offsets_[k]; e < offsets_[k + 1]; ++e) put(columns_[e], Sent{k, values_[e]});
  });
  const std::vector<uint64_t>& tOffsets = transpose.start;
  const FilledLaterVector<Sent>& transposed = transpose.items;
  // Row i of the result: the union of row i and transposed row i. A_i F_ij and A_j F_ji estimate
  // one quantity G_ij, by n rays from each side: their variances go as A_i^2 F_ij / n and
  // A_j^2 F_ji / n = A_i A_j F_ij / n, so weighted by inverse variance (1 / A_i, 1 / A_j) they give
  // G_ij = A_i A_j (F_ij + F_ji) / (A_i + A_j). Equal areas: the plain mean. A small patch next to
  // a large one keeps its own estimate (the large one's few rays that find it no longer lift its
  // row far above 1: 1.59 -> 1.07 on cornell-spot's refined mesh). An entry estimated from one
  // side only is combined with that side's zero. Walked twice: to count each row's positive
  // entries, then to write them in place.
  auto mergeRow = [&](size_t i, auto&& emit) {
    uint64_t a = offsets_[i], b = tOffsets[i];
    while (a < offsets_[i + 1] || b < tOffsets[i + 1]) {
      const uint32_t ca = a < offsets_[i + 1] ? columns_[a] : ~0u;
      const uint32_t cb = b < tOffsets[i + 1] ? transposed[b].column : ~0u;
      const uint32_t c = std::min(ca, cb);
      float fromI = 0.0f, fromJ = 0.0f;  // F_ic as i's rays found it, F_ci as c's did
      if (ca == c) fromI = values_[a++];
      if (cb == c) fromJ = transposed[b++].value;
      const float value = reciprocalMean(fromI, fromJ, area[i], area[c]);
      if (value > 0.0f) emit(c, value);
    }
  };
  FilledLaterVector<uint64_t> offsets(n + 1, 0);
  tbb::parallel_for(size_t(0), n,
                    [&](size_t i) { mergeRow(i, [&](uint32_t, float) { ++offsets[i + 1]; }); });
  for (size_t i = 0; i < n; ++i) offsets[i + 1] += offsets[i];
  FilledLaterVector<uint32_t> columns(offsets.back());
  FilledLaterVector<float> values(offsets.back());
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    uint64_t at = offsets[i];
    mergeRow(i, [&](uint32_t c, float v) {
      columns[at] = c;
      values[at++] = v;
    });
  });
  offsets_ = std::move(offsets);
  columns_ = std::move(columns);
  values_ = std::move(values);
}

FormFactorTable::ClosureRepair FormFactorTable::closeRows(double noise) {
  const size_t n = rows();
  std::vector<float> scale(n, 1.0f);
  std::vector<double> sums(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) { sums[i] = rowSum(i); });
  ClosureRepair repair;
  for (size_t i = 0; i < n; ++i) {
    const double sum = sums[i];
    repair.worstSum = std::max(repair.worstSum, sum);
    if (sum > 1.0 + noise) {
      scale[i] = float(1.0 / sum);
      ++repair.rows;
    }
  }
  if (repair.rows == 0) return repair;
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    for (uint64_t e = offsets_[i]; e < offsets_[i + 1]; ++e)
      values_[e] *= std::min(scale[i], scale[columns_[e]]);
  });
  return repair;
}

FormFactorTable::ReflectionBound FormFactorTable::boundReflection(std::span<const float> rho,
                                                                  std::span<const float> area,
                                                                  double limit) {
  // Column sums, in row order (one pass, the same sums whatever the threads).
  const size_t n = rows();
  std::vector<double> share(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const double weight = double(rho[i]) * area[i];
    for (uint64_t e = offsets_[i]; e < offsets_[i + 1]; ++e)
      share[columns_[e]] += weight * values_[e];
  }
  ReflectionBound bound;
  std::vector<float> scale(n, 1.0f);
  for (size_t j = 0; j < n; ++j) {
    share[j] /= area[j];
    bound.worstShare = std::max(bound.worstShare, share[j]);
    if (share[j] > limit) {
      scale[j] = float(limit / share[j]);
      ++bound.patches;
    }
  }
  if (bound.patches == 0) return bound;
  tbb::parallel_for(size_t(0), n, [&](size_t i) {
    for (uint64_t e = offsets_[i]; e < offsets_[i + 1]; ++e)
      values_[e] *= std::min(scale[i], scale[columns_[e]]);
  });
  return bound;
}

size_t FormFactorTable::memoryBytes() const {
  return offsets_.size() * sizeof(uint64_t) + columns_.size() * sizeof(uint32_t) +
         values_.size() * sizeof(float);
}

}  // namespace rad
