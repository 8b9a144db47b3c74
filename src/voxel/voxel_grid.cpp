#include "voxel/voxel_grid.h"

#include <algorithm>
#include <cmath>

#include "core/vector_memory.h"
#include "voxel/half_float.h"

namespace rad {

namespace {

template <typename T>
size_t bytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

IVec3 VoxelGrid::cellCoordinates(uint32_t cell) const {
  // The row holding the cell, then the slab holding the row.
  const auto rowIt = std::upper_bound(rowCellBegin.begin(), rowCellBegin.end(), cell);
  const uint32_t row = uint32_t(rowIt - rowCellBegin.begin()) - 1;
  const auto slabIt = std::upper_bound(slabRowBegin.begin(), slabRowBegin.end(), row);
  const int x = int(slabIt - slabRowBegin.begin()) - 1;
  return IVec3(x, rowY[row], cellZ[cell]);
}

uint32_t VoxelGrid::findCell(const IVec3& c) const {
  if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= dims.x || c.y >= dims.y || c.z >= dims.z)
    return UINT32_MAX;
  const auto rowsBegin = rowY.begin() + slabRowBegin[c.x];
  const auto rowsEnd = rowY.begin() + slabRowBegin[c.x + 1];
  const auto rowIt = std::lower_bound(rowsBegin, rowsEnd, int16_t(c.y));
  if (rowIt == rowsEnd || *rowIt != c.y) return UINT32_MAX;
  const size_t row = size_t(rowIt - rowY.begin());
  const auto cellsBegin = cellZ.begin() + rowCellBegin[row];
  const auto cellsEnd = cellZ.begin() + rowCellBegin[row + 1];
  const auto cellIt = std::lower_bound(cellsBegin, cellsEnd, int16_t(c.z));
  if (cellIt == cellsEnd || *cellIt != c.z) return UINT32_MAX;
  return uint32_t(cellIt - cellZ.begin());
}

void NarrowIndices::push_back(uint32_t index) {
  if (!widened_ && index > UINT16_MAX) {
    wide_.reserve(narrow_.capacity());
    wide_.assign(narrow_.begin(), narrow_.end());
    releaseMemory(narrow_);
    widened_ = true;
  }
  if (widened_)
    wide_.push_back(index);
  else
    narrow_.push_back(uint16_t(index));
}

bool NarrowIndices::operator==(const NarrowIndices& other) const {
  if (size() != other.size()) return false;
  for (size_t i = 0; i < size(); ++i)
    if ((*this)[i] != other[i]) return false;
  return true;
}

float VoxelGrid::pointStepFor(const IVec3& dims, float voxelSize) {
  const int widest = std::max({dims.x, dims.y, dims.z, 1});
  int k = 21;  // widest * 2^k <= 2^21
  while (k > 0 && (int64_t(widest) << k) > (int64_t(1) << 21)) --k;
  return std::ldexp(voxelSize, -k);
}

PackedPoint VoxelGrid::pack(const Vec3d& p) const {
  constexpr double kMost = double((1 << 21) - 1);
  uint64_t bits = 0;
  for (int k = 2; k >= 0; --k) {
    const double steps = std::clamp(std::round((p[k] - double(origin[k])) / pointStep), 0.0, kMost);
    bits = bits << 21 | uint64_t(steps);
  }
  return {bits};
}

float VoxelGrid::areaOf(size_t entry) const {
  return fromHalf(faceArea[entry]) * (voxelSize * voxelSize);
}

size_t VoxelGrid::memoryBytes() const {
  return bytes(cellZ) + bytes(cellEntryBegin) + bytes(rowY) + bytes(rowCellBegin) +
         bytes(slabRowBegin) + bytes(orientation) + bytes(centroid) + bytes(faceArea) +
         surface.memoryBytes() + bytes(surfaces);
}

}  // namespace rad
