// What the tests read of a sweep's lines and orders: the line of every cell and the cells in the
// order a pass, whole or in bands, visits them. The order is the build's own instruction set's
// (pass_order-inl.h at Highway's static target): the same on every target.

#include <hwy/highway.h>

#include "voxel/discrete_line_sweep.h"
#include "voxel/pass_order-inl.h"

namespace rad {

namespace order = sweep::HWY_NAMESPACE;

std::vector<uint32_t> DiscreteLineSweep::lineOfEachCell(const IVec3& step,
                                                        const LineOffset& offset) {
  prepareLines(step, offset);
  std::vector<uint32_t> lines(grid_.cellCount());
  order::forEachCellInPassOrder({grid_, table_, occupiedSlabs_}, step, {},
                                [&](uint32_t cell, uint32_t line, int32_t) { lines[cell] = line; });
  return lines;
}

std::vector<uint32_t> DiscreteLineSweep::passOrder(const IVec3& step) {
  prepareLines(step);
  return cellsInPassOrder(step, {});
}

std::vector<uint32_t> DiscreteLineSweep::cellsInPassOrder(const IVec3& step,
                                                          const LineBand& band) const {
  std::vector<uint32_t> cells;
  order::forEachCellInPassOrder({grid_, table_, occupiedSlabs_}, step, band,
                                [&](uint32_t cell, uint32_t, int32_t) { cells.push_back(cell); });
  return cells;
}

std::vector<std::vector<uint32_t>> DiscreteLineSweep::passOrderInBands(const IVec3& step,
                                                                       size_t bands) {
  prepareLines(step);
  bands_.cut(table_, bands, bandLines_);
  std::vector<std::vector<uint32_t>> orders;
  for (const LineBand& band : bands_.bands()) orders.push_back(cellsInPassOrder(step, band));
  return orders;
}

}  // namespace rad
