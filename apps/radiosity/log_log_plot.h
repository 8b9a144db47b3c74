#pragma once
// A log-log plot as SVG, for the benchmarks' scaling measurements: the points joined by a line
// over axes with ticks at 1-2-5 steps, labelled as far apart as their text needs.

#include <string>
#include <utility>
#include <vector>

namespace rad::cli {

/// One tick of an axis: its value, its offset along the axis in pixels from the axis's low end,
/// and its label (empty: a tick and grid line without one).
struct AxisTick {
  double value = 0.0, offset = 0.0;
  std::string label;
};

/// The ticks of a logarithmic axis `length` pixels long over the values [lo, hi] (0 < lo <=
/// hi): every 1-2-5 value from the largest at or below lo to the smallest at or above hi (the
/// axis's ends). The labels ("20k", "0.5 s": the value, k or M for thousands or millions, and
/// `unit`) go on every tick, else on 1 and 5 of each decade, else on decades, else on every
/// other decade: the first choice whose labels are at least `labelRoom(label)` pixels apart.
/// Horizontal axes need a label's width (7.5 px a character at 13 px type), vertical ones its
/// height.
std::vector<AxisTick> logAxisTicks(double lo, double hi, double length, const std::string& unit,
                                   bool horizontal);

/// The text of a value on an axis: "20k", "1.5M", "0.02", with " unit" after when given.
std::string axisLabel(double value, const std::string& unit);

struct LogLogPlot {
  std::string title, xName, yName, xUnit, yUnit;
  std::vector<std::pair<double, double>> points;  ///< (x, y), both > 0, in x order
};

/// The plot as an SVG document, 640 x 420 pixels.
std::string logLogSvg(const LogLogPlot& plot);

}  // namespace rad::cli
