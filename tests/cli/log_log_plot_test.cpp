// The scaling plot's axes: ticks at 1-2-5 steps over the measured range, labels that never
// overlap, and both scales on the plot.
#include "log_log_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace rad::cli {
namespace {

// The labelled ticks' offsets are at least `room(label)` apart, and the axis covers [lo, hi].
void expectReadable(const std::vector<AxisTick>& ticks, double lo, double hi, bool horizontal) {
  ASSERT_GE(ticks.size(), 2u);
  EXPECT_LE(ticks.front().value, lo * (1 + 1e-9));  // 5 x 10^-5 is not exactly 50e-6
  EXPECT_GE(ticks.back().value, hi * (1 - 1e-9));
  const AxisTick* last = nullptr;
  size_t labels = 0;
  for (const AxisTick& t : ticks) {
    if (t.label.empty()) continue;
    ++labels;
    if (last) {
      const double room =
          horizontal ? 7.5 * double(std::max(last->label.size(), t.label.size())) : 13.0;
      EXPECT_GE(t.offset - last->offset, room) << last->label << " and " << t.label;
    }
    last = &t;
  }
  EXPECT_GE(labels, 2u);
}

TEST(LogLogPlot, AxisLabelsNeverOverlap) {
  // voxel-scaling's range: room:2 to room:256 at 2.5 cm, 0.02 s to several seconds an iteration.
  for (const auto& [lo, hi] : {std::pair{3.1e4, 4.2e6}, {1.2e5, 1.6e5}, {50.0, 5e9}}) {
    SCOPED_TRACE(lo);
    expectReadable(logAxisTicks(lo, hi, 530, "", true), lo, hi, true);
    expectReadable(logAxisTicks(lo * 1e-6, hi * 1e-6, 312, "s", false), lo * 1e-6, hi * 1e-6,
                   false);
  }
  // Close points share one step: the axis still has two ends.
  const std::vector<AxisTick> one = logAxisTicks(2000, 2000, 530, "", true);
  ASSERT_EQ(one.size(), 2u);
  EXPECT_EQ(one.front().label, "2k");
  EXPECT_EQ(one.back().label, "5k");
}

TEST(LogLogPlot, LabelsNameTheValueAndUnit) {
  EXPECT_EQ(axisLabel(20000, ""), "20k");
  EXPECT_EQ(axisLabel(1.5e6, ""), "1.5M");
  EXPECT_EQ(axisLabel(0.02, "s"), "0.02 s");
  EXPECT_EQ(axisLabel(500, "s"), "500 s");
}

TEST(LogLogPlot, ThePlotShowsBothScales) {
  const std::string svg = logLogSvg({"title",
                                     "voxels",
                                     "seconds per iteration",
                                     "",
                                     "s",
                                     {{3.1e4, 0.021}, {2.5e5, 0.17}, {4.2e6, 3.3}}});
  // 20k to 5M and 0.02 s to 5 s at 1-2-5 steps, each labelled: there is room.
  for (const char* label : {">20k<", ">100k<", ">1M<", ">5M<", ">0.02 s<", ">1 s<", ">5 s<",
                            ">voxels<", ">seconds per iteration<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label << "\n" << svg;
  size_t dots = 0;
  for (size_t at = 0; (at = svg.find("<circle", at)) != std::string::npos; ++at) ++dots;
  EXPECT_EQ(dots, 3u);
}

}  // namespace
}  // namespace rad::cli
