// falseColourPicture: irradiance as a lighting designer reads it, in colours with isolines and a
// legend whose labels stb_easy_font draws (a font of line segments, no font file needed).
#include <fmt/format.h>
#include <radiosity/false_colour.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace rad {

namespace {

// The ramp of the viewer's false colours (after Google's Turbo), sRGB, 0 to 1.
Color rampColour(double t) {
  static const std::array<uint32_t, 7> kStops = {0x30123b, 0x4686fb, 0x1ae4b6, 0xa2fc3c,
                                                 0xfaba39, 0xe4460a, 0x7a0403};
  const double x = std::clamp(t, 0.0, 1.0) * double(kStops.size() - 1);
  const size_t k = std::min(size_t(x), kStops.size() - 2);
  const auto channel = [](uint32_t hex, int shift) {
    return float((hex >> shift) & 0xff) / 255.0f;
  };
  Color c(0.0f);
  for (int i = 0; i < 3; ++i) {
    const float a = channel(kStops[k], 16 - 8 * i), b = channel(kStops[k + 1], 16 - 8 * i);
    c[i] = a + float(x - double(k)) * (b - a);
  }
  return c;
}

// An sRGB colour as the linear value the PNG writer turns back into it.
Color linearOf(const Color& srgb) {
  Color c;
  for (int i = 0; i < 3; ++i)
    c[i] = srgb[i] <= 0.04045f ? srgb[i] / 12.92f : std::pow((srgb[i] + 0.055f) / 1.055f, 2.4f);
  return c;
}

// The 98th percentile of the lit pixels, rounded up to a step: a few hot spots (a lamp's own
// surface) do not wash the rest out.
double topOf(const std::vector<double>& values) {
  std::vector<double> lit;
  for (double v : values)
    if (v > 0.0) lit.push_back(v);
  if (lit.empty()) return 1.0;
  const size_t k = size_t(0.98 * double(lit.size() - 1));
  std::nth_element(lit.begin(), lit.begin() + ptrdiff_t(k), lit.end());
  const double step = falseColourStep(lit[k]);
  return std::max(step, std::ceil(lit[k] / step) * step);
}

// Text at (x, y) (its top left), `scale` pixels a font unit, in `colour`.
void drawText(Image& image, int x, int y, int scale, const std::string& text, const Color& colour) {
  std::vector<char> buffer(text.size() * 1024 + 64);  // ~270 B a character on average
  std::string copy = text;
  const int quads =
      stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(), int(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    // Four vertices of 16 bytes (x, y, z floats and a colour): an axis-aligned rectangle.
    float corner[2][2];
    for (int v = 0; v < 2; ++v)
      std::copy_n(reinterpret_cast<const float*>(buffer.data() + 64 * q + 32 * v), 2, corner[v]);
    for (int py = int(corner[0][1]) * scale; py < int(corner[1][1]) * scale; ++py)
      for (int px = int(corner[0][0]) * scale; px < int(corner[1][0]) * scale; ++px)
        if (x + px >= 0 && x + px < image.width && y + py >= 0 && y + py < image.height)
          image.at(x + px, y + py) = colour;
  }
}

// Pixels of font units: the labels readable at any picture size.
int fontScale(int height) {
  return std::max(1, int(std::lround(double(height) / 180.0)));
}

// The legend's steps, bottom to top, and their labels.
struct LegendStep {
  double value;
  std::string label;
};
std::vector<LegendStep> legendSteps(double top, double step) {
  std::vector<LegendStep> steps;
  for (double v = 0.0; v <= top * (1.0 + 1e-9); v += step)
    steps.push_back({v, fmt::format("{:g}", v)});
  return steps;
}

// The legend strip's width: a bar, its ticks and the widest label or the unit.
int legendWidth(int height, const std::vector<LegendStep>& steps, const std::string& unit) {
  int widest = 0;
  for (LegendStep s : steps) widest = std::max(widest, stb_easy_font_width(s.label.data()));
  std::string copy = unit;
  widest = std::max(widest, stb_easy_font_width(copy.data()));
  return fontScale(height) * (6 + 8 + 3 + 4 + widest + 4);
}

// The legend in the strip [x0, width): a bar from 0 (bottom) to `top`, a tick and a value at
// each step, the unit above.
void drawLegend(Image& image, int x0, double top, const std::vector<LegendStep>& steps,
                const std::string& unit) {
  const int scale = fontScale(image.height);
  const int barTop = 12 * scale + 8, barBottom = image.height - 8 * scale;
  const int barLeft = x0 + 6 * scale, barRight = barLeft + 8 * scale;
  const Color white = linearOf(Color(1.0f));
  for (int y = barTop; y < barBottom; ++y)
    for (int x = barLeft; x < barRight; ++x)
      image.at(x, y) =
          linearOf(rampColour(double(barBottom - y) / double(std::max(1, barBottom - barTop))));
  drawText(image, barLeft, 4, scale, unit, white);
  for (const LegendStep& s : steps) {
    const int y = barBottom - int(std::lround(s.value / top * double(barBottom - barTop)));
    for (int x = barRight; x < barRight + 3 * scale && x < image.width; ++x)
      image.at(x, std::clamp(y, 0, image.height - 1)) = white;
    drawText(image, barRight + 4 * scale, y - 3 * scale, scale, s.label, white);
  }
}

// The value each pixel's isoline test reads: the mean over its 3 x 3 neighbourhood, so that
// per-pixel noise near a step does not scatter the line into dots.
std::vector<double> smoothed(const std::vector<double>& values, int w, int h) {
  std::vector<double> out(values.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double sum = 0.0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int sx = x + dx, sy = y + dy;
          if (sx < 0 || sx >= w || sy < 0 || sy >= h) continue;
          sum += values[size_t(sy) * size_t(w) + size_t(sx)];
          ++n;
        }
      out[size_t(y) * size_t(w) + size_t(x)] = sum / double(n);
    }
  return out;
}

}  // namespace

double falseColourStep(double top) {
  if (!(top > 0.0) || !std::isfinite(top)) return 1.0;
  const double rough = top / 5.0;
  const double power = std::pow(10.0, std::floor(std::log10(rough)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * power >= rough) return m * power;
  return 10.0 * power;
}

Image falseColourPicture(const Image& irradiance, const FalseColourScale& scale) {
  const int w = irradiance.width, h = irradiance.height;
  std::vector<double> values(irradiance.pixels.size());
  for (size_t i = 0; i < values.size(); ++i)
    values[i] = std::max(0.0, double(luminance(irradiance.pixels[i])) * scale.perIrradiance);
  const double top = scale.max > 0.0 ? scale.max : topOf(values);
  const double step = falseColourStep(top);
  const std::vector<LegendStep> steps = legendSteps(top, step);
  Image out(w + legendWidth(h, steps, scale.unit), h);
  const std::vector<double> around = smoothed(values, w, h);
  const auto band = [&](int x, int y) {
    return int(std::floor(around[size_t(y) * size_t(w) + size_t(x)] / step));
  };
  const Color line = linearOf(Color(0.08f));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool edge = (x + 1 < w && band(x + 1, y) != band(x, y)) ||
                        (y + 1 < h && band(x, y + 1) != band(x, y));
      out.at(x, y) =
          edge ? line : linearOf(rampColour(values[size_t(y) * size_t(w) + size_t(x)] / top));
    }
  drawLegend(out, w, top, steps, scale.unit);
  return out;
}

}  // namespace rad
