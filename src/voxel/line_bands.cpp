#include "voxel/line_bands.h"

namespace rad {

void LineBands::sampleCells() {
  if (!samples_.empty() || grid_.cellCount() == 0) return;
  const VoxelGrid& grid = grid_;
  const size_t stride = std::max<size_t>(32, (grid.cellCount() + kMaxSamples - 1) / kMaxSamples);
  for (uint32_t x = 0; x < uint32_t(grid.dims.x); ++x)
    for (uint32_t row = grid.slabRowBegin[x]; row < grid.slabRowBegin[x + 1]; ++row)
      for (uint32_t cell = grid.rowCellBegin[row]; cell < grid.rowCellBegin[row + 1]; ++cell)
        if (cell % stride == 0) samples_.push_back({int16_t(x), grid.rowY[row], grid.cellZ[cell]});
}

void LineBands::cut(const LineTable& table, size_t count, size_t mostLines) {
  bands_.clear();
  const size_t rows = table.rowCount();
  std::vector<uint32_t>& perRow = sampledPerRow_;
  perRow.assign(rows, 0);
  if (count > 1) {
    sampleCells();
    for (const auto& [x, y, z] : samples_) ++perRow[table.rowOf(size_t(x), size_t(y), size_t(z))];
  }
  auto cutAt = [&](size_t begin, size_t end) {
    const uint32_t first = table.rowFirstLine(begin);
    bands_.push_back({int64_t(begin), int64_t(end), first, table.rowFirstLine(end) - first});
  };
  // Band k of the count ends at the first row where the running count reaches k / count of the
  // sample; a band ends earlier where its next row would take it past mostLines lines.
  const double total = double(samples_.size());
  size_t begin = 0, quotas = 0;
  int64_t seen = 0;
  for (size_t row = 0; row < rows; ++row) {
    if (row > begin && table.rowFirstLine(row + 1) - table.rowFirstLine(begin) > mostLines) {
      cutAt(begin, row);
      begin = row;
    }
    seen += perRow[row];
    if (quotas + 1 < count && double(seen) >= total * double(quotas + 1) / double(count)) {
      ++quotas;
      cutAt(begin, row + 1);
      begin = row + 1;
    }
  }
  if (begin < rows || bands_.empty()) cutAt(begin, rows);
}

}  // namespace rad
