#include "log_log_plot.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>

namespace rad::cli {

namespace {

constexpr double kWidth = 640, kHeight = 420;
constexpr double kLeft = 80, kRight = 30, kTop = 44, kBottom = 64;  // margins
constexpr double kCharWidth = 7.5, kLineHeight = 16, kLabelGap = 10;

struct Step {
  double value;
  int mantissa, exponent;  ///< value = mantissa x 10^exponent, mantissa 1, 2 or 5
};

// The 1-2-5 values from the largest at or below lo to the first above it at or above hi.
std::vector<Step> stepsOver(double lo, double hi) {
  const double slack = 1.0 + 1e-9;  // 2 x 10^-2 is not exactly 0.02
  std::vector<Step> steps;
  for (int e = int(std::floor(std::log10(lo))) - 1;; ++e)
    for (int m : {1, 2, 5}) {
      const double v = m * std::pow(10.0, e);
      if (v <= lo * slack) steps.clear();
      steps.push_back({v, m, e});
      if (steps.size() > 1 && v * slack >= hi) return steps;
    }
}

// Whether the labels on the steps `labelled` picks are `room(label)` pixels apart at least.
bool labelsFit(const std::vector<AxisTick>& ticks, const std::vector<Step>& steps,
               const std::function<bool(const Step&)>& labelled,
               const std::function<double(const std::string&)>& room) {
  const AxisTick* last = nullptr;
  for (size_t i = 0; i < ticks.size(); ++i) {
    if (!labelled(steps[i])) continue;
    if (last && ticks[i].offset - last->offset < std::max(room(last->label), room(ticks[i].label)))
      return false;
    last = &ticks[i];
  }
  return true;
}

std::string text(double x, double y, const std::string& anchor, const std::string& content,
                 const std::string& extra = "") {
  return fmt::format("<text x=\"{:.1f}\" y=\"{:.1f}\" text-anchor=\"{}\"{}>{}</text>\n", x, y,
                     anchor, extra, content);
}

std::string line(double x1, double y1, double x2, double y2, const std::string& stroke) {
  return fmt::format(
      "<line x1=\"{:.1f}\" y1=\"{:.1f}\" x2=\"{:.1f}\" y2=\"{:.1f}\" stroke=\"{}\"/>\n", x1, y1, x2,
      y2, stroke);
}

// Grid lines across the plot, tick marks and labels below the x axis and left of the y axis.
std::string xAxis(const std::vector<AxisTick>& ticks) {
  std::string svg;
  const double bottom = kHeight - kBottom;
  for (const AxisTick& t : ticks) {
    const double x = kLeft + t.offset;
    svg += line(x, kTop, x, bottom, t.label.empty() ? "#eee" : "#ccc");
    svg += line(x, bottom, x, bottom + (t.label.empty() ? 3 : 6), "black");
    if (!t.label.empty()) svg += text(x, bottom + 20, "middle", t.label);
  }
  return svg;
}

std::string yAxis(const std::vector<AxisTick>& ticks) {
  std::string svg;
  const double bottom = kHeight - kBottom;
  for (const AxisTick& t : ticks) {
    const double y = bottom - t.offset;
    svg += line(kLeft, y, kWidth - kRight, y, t.label.empty() ? "#eee" : "#ccc");
    svg += line(kLeft - (t.label.empty() ? 3 : 6), y, kLeft, y, "black");
    if (!t.label.empty()) svg += text(kLeft - 9, y + 4.5, "end", t.label);
  }
  return svg;
}

// Where a value lies on an axis whose ticks run from the first to the last.
double offsetOn(const std::vector<AxisTick>& ticks, double length, double value) {
  const double lo = std::log10(ticks.front().value), hi = std::log10(ticks.back().value);
  return (std::log10(value) - lo) / (hi - lo) * length;
}

}  // namespace

std::string axisLabel(double value, const std::string& unit) {
  const std::string number = value >= 1e6   ? fmt::format("{:g}M", value / 1e6)
                             : value >= 1e3 ? fmt::format("{:g}k", value / 1e3)
                                            : fmt::format("{:g}", value);
  return unit.empty() ? number : number + " " + unit;
}

std::vector<AxisTick> logAxisTicks(double lo, double hi, double length, const std::string& unit,
                                   bool horizontal) {
  const std::vector<Step> steps = stepsOver(lo, hi);
  const double low = std::log10(steps.front().value), high = std::log10(steps.back().value);
  std::vector<AxisTick> ticks;
  for (const Step& s : steps)
    ticks.push_back({s.value, (std::log10(s.value) - low) / (high - low) * length, ""});
  for (AxisTick& t : ticks) t.label = axisLabel(t.value, unit);  // to measure them
  const auto room = [horizontal](const std::string& label) {
    return horizontal ? kCharWidth * double(label.size()) + kLabelGap : kLineHeight;
  };
  const std::function<bool(const Step&)> choices[] = {
      [](const Step&) { return true; }, [](const Step& s) { return s.mantissa != 2; },
      [](const Step& s) { return s.mantissa == 1; },
      [](const Step& s) { return s.mantissa == 1 && s.exponent % 2 == 0; }};
  const auto* chosen = std::find_if(std::begin(choices), std::end(choices) - 1,
                                    [&](auto& c) { return labelsFit(ticks, steps, c, room); });
  for (size_t i = 0; i < ticks.size(); ++i)
    if (!(*chosen)(steps[i])) ticks[i].label.clear();
  return ticks;
}

std::string logLogSvg(const LogLogPlot& plot) {
  const double plotWidth = kWidth - kLeft - kRight, plotHeight = kHeight - kTop - kBottom;
  const auto [xLo, xHi] = std::minmax_element(plot.points.begin(), plot.points.end());
  const auto [yLo, yHi] =
      std::minmax_element(plot.points.begin(), plot.points.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; });
  const std::vector<AxisTick> xTicks =
      logAxisTicks(xLo->first, xHi->first, plotWidth, plot.xUnit, true);
  const std::vector<AxisTick> yTicks =
      logAxisTicks(yLo->second, yHi->second, plotHeight, plot.yUnit, false);
  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}\" height=\"{}\" "
      "font-family=\"sans-serif\" font-size=\"13\">\n"
      "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      kWidth, kHeight);
  svg += text(kLeft, 24, "start", plot.title, " font-size=\"14\"");
  svg += xAxis(xTicks) + yAxis(yTicks);
  svg += line(kLeft, kTop, kLeft, kHeight - kBottom, "black");
  svg += line(kLeft, kHeight - kBottom, kWidth - kRight, kHeight - kBottom, "black");
  std::string points;
  for (const auto& [x, y] : plot.points) {
    const double px = kLeft + offsetOn(xTicks, plotWidth, x),
                 py = kHeight - kBottom - offsetOn(yTicks, plotHeight, y);
    points += fmt::format("{:.1f},{:.1f} ", px, py);
    svg += fmt::format("<circle cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"4\" fill=\"#c33\"/>\n", px, py);
  }
  svg += fmt::format("<polyline points=\"{}\" fill=\"none\" stroke=\"#c33\"/>\n", points);
  svg += text(kLeft + plotWidth / 2, kHeight - 16, "middle", plot.xName);
  svg += text(20, kTop + plotHeight / 2, "middle", plot.yName,
              fmt::format(" transform=\"rotate(-90 20 {:.1f})\"", kTop + plotHeight / 2));
  return svg + "</svg>\n";
}

}  // namespace rad::cli
