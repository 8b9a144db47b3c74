// IES LM-63 photometric file parser and evaluator.
// Based on: the LM-63 layout and conventions of docs/references.md section 4 (AGi32's "IESNA LM-63
// Format" pages; I. Ashdown, "Parsing the IESNA LM-63 photometric data file", 1998; Radiance
// ies2rad.c for the Type C frame).
//
// Choices where the sources are silent or disagree:
// - Field 12 is never a multiplier except in LM-63-1986/1991 files, where it is the
//   "ballast-lamp photometric factor" (1995/2002: future use; 2019: file generation type).
// - Tilt factors are stored, not applied: they depend on how the luminaire is installed.
// - Type A/B: photometric zero is the aim (-z). Type A planes share the luminaire's y axis
//   (H = atan2(x, -z), V = elevation asin(y)); Type B planes share its x axis
//   (V = atan2(y, -z), H = asin(x)). A table whose horizontal angles start at 0 is mirrored
//   laterally (Ashdown: "laterally symmetric ... first 0, last 90").
// - Type C horizontal angles increase from +x toward +y (docs/references.md 4.3).

#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/ies_profile.h>
#include <radiosity/message_text.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>

#include "scene/io/text_file.h"

namespace rad {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kAngleEps = 1e-6;
// The largest photometric files in use (road lighting, 0.5-degree grids) are a few hundred KB.
constexpr size_t kMaxIesFileBytes = size_t(64) << 20;

struct Token {
  std::string text;
  int line;
};

std::string trim(const std::string& s) {
  size_t b = 0, e = s.size();
  while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
  while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
  return s.substr(b, e - b);
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// The numeric part of an LM-63 file: a stream of numbers separated by blanks, commas or line
// breaks, wrapping anywhere (LM-63-2002), each remembered with its line for messages.
class NumberStream {
 public:
  NumberStream(const std::vector<std::string>& lines, size_t first, std::string source)
      : source_(std::move(source)), lastLine_(int(lines.size())) {
    for (size_t i = first; i < lines.size(); ++i) {
      std::string word;
      for (char c : lines[i] + " ") {
        if (std::isspace(static_cast<unsigned char>(c)) || c == ',') {
          if (!word.empty()) tokens_.push_back({word, int(i + 1)});
          word.clear();
        } else {
          word += c;
        }
      }
    }
  }

  /// Reads `count` numbers naming the block `what` ("vertical angles") for messages.
  std::vector<double> block(size_t count, const std::string& what) {
    std::vector<double> values;
    // The count is the file's word: reserve no more than the numbers the file holds.
    values.reserve(std::min(count, tokens_.size() - pos_));
    for (size_t i = 0; i < count; ++i) {
      std::optional<double> v = tryNext();
      if (!v)
        throw InputError(where(),
                         fmt::format("expected {} {}, found {}{}", count, what, i, foundSuffix()));
      values.push_back(*v);
    }
    return values;
  }

  double one(const std::string& what) {
    std::optional<double> v = tryNext();
    if (!v) throw InputError(where(), fmt::format("expected {}{}", what, foundSuffix()));
    return *v;
  }

  int integer(const std::string& what) {
    const double v = one(what);
    if (v != std::floor(v) || std::abs(v) > 1e9)
      throw InputError(lineOfPrevious(), fmt::format("{} must be an integer, found {}", what, v));
    return int(v);
  }

  /// Throws if numbers remain after the candela table.
  void expectEnd(const std::string& expected) {
    if (pos_ < tokens_.size())
      throw InputError(where(), fmt::format("unexpected extra value {} after {}",
                                            quotedToken(tokens_[pos_].text), expected));
  }

  std::string lineOfPrevious() const {
    const int line = pos_ == 0 ? lastLine_ : tokens_[pos_ - 1].line;
    return fmt::format("{}:{}", source_, line);
  }

 private:
  std::optional<double> tryNext() {
    if (pos_ >= tokens_.size()) return std::nullopt;
    const std::string& s = tokens_[pos_].text;
    double v = 0.0;
    const char* begin = s.data() + (s[0] == '+' ? 1 : 0);
    auto [end, ec] = std::from_chars(begin, s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
    ++pos_;
    return v;
  }
  std::string where() const {
    const int line = pos_ < tokens_.size() ? tokens_[pos_].line : lastLine_;
    return fmt::format("{}:{}", source_, line);
  }
  std::string foundSuffix() const {
    return pos_ < tokens_.size() ? fmt::format(" (next is {})", quotedToken(tokens_[pos_].text))
                                 : " before the end of the file";
  }

  std::string source_;
  int lastLine_;
  std::vector<Token> tokens_;
  size_t pos_ = 0;
};

void requireAscending(const std::vector<double>& a, const std::string& what,
                      const std::string& at) {
  for (size_t i = 1; i < a.size(); ++i)
    if (!(a[i] > a[i - 1]))
      throw InputError(
          at, fmt::format("{} must be strictly ascending ({} follows {})", what, a[i], a[i - 1]));
}

// Cell of `x` in ascending `nodes`: indices i0, i1 and weight t of i1. False when outside.
void requireWithin(const std::vector<double>& a, double lo, double hi, const std::string& what,
                   const std::string& at) {
  for (const double v : a)
    if (!(v >= lo - kAngleEps && v <= hi + kAngleEps))
      throw InputError(
          at, fmt::format("{} must lie in [{}, {}] for this photometric type, found {}", what, lo,
                          hi, v));
}

bool locate(const std::vector<double>& nodes, double x, size_t& i0, size_t& i1, double& t) {
  if (nodes.size() == 1) {
    i0 = i1 = 0;
    t = 0.0;
    return std::abs(x - nodes[0]) <= kAngleEps;
  }
  if (x < nodes.front() - kAngleEps || x > nodes.back() + kAngleEps) return false;
  x = std::clamp(x, nodes.front(), nodes.back());
  const size_t hi = size_t(std::upper_bound(nodes.begin(), nodes.end(), x) - nodes.begin());
  i1 = std::clamp<size_t>(hi, 1, nodes.size() - 1);
  i0 = i1 - 1;
  t = (x - nodes[i0]) / (nodes[i1] - nodes[i0]);
  return true;
}

// Exact integral over [a, b] (radians) of the linear function through (a, fa), (b, fb) times
// sin x (weightSin) or cos x.
double linearTrigIntegral(double a, double b, double fa, double fb, bool weightSin) {
  const double beta = (fb - fa) / (b - a);
  const double alpha = fa - beta * a;
  auto g0 = [&](double x) { return weightSin ? -std::cos(x) : std::sin(x); };
  auto g1 = [&](double x) {
    return weightSin ? std::sin(x) - x * std::cos(x) : std::cos(x) + x * std::sin(x);
  };
  return alpha * (g0(b) - g0(a)) + beta * (g1(b) - g1(a));
}

// Integral of a piecewise-linear curve sampled at angles (degrees) times sin or cos.
double curveIntegral(const std::vector<double>& angles, const std::vector<double>& values,
                     bool weightSin) {
  double sum = 0.0;
  for (size_t i = 0; i + 1 < angles.size(); ++i)
    sum += linearTrigIntegral(angles[i] * kDeg, angles[i + 1] * kDeg, values[i], values[i + 1],
                              weightSin);
  return sum;
}

// Trapezoid integral over the azimuth-like angle of per-row integrals F (exact, since the table
// is linear in that angle), in radians.
double trapezoid(const std::vector<double>& angles, const std::vector<double>& f) {
  double sum = 0.0;
  for (size_t i = 0; i + 1 < angles.size(); ++i)
    sum += 0.5 * (angles[i + 1] - angles[i]) * kDeg * (f[i] + f[i + 1]);
  return sum;
}

}  // namespace

double IesProfile::candelaToward(double dx, double dy, double dz) const {
  const double len = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(len > 0.0) || candela.empty()) return 0.0;
  dx /= len, dy /= len, dz /= len;
  const double firstH = horizontalAngles.front(), lastH = horizontalAngles.back();
  double v = 0.0, h = 0.0;
  if (type == PhotometricType::C) {
    if (horizontalAngles.size() == 1)
      dx = std::hypot(dx, dy), dy = 0.0;
    else if (std::abs(lastH - 90.0) < kAngleEps)
      dx = std::abs(dx), dy = std::abs(dy);
    else if (std::abs(firstH - 90.0) < kAngleEps && std::abs(lastH - 270.0) < kAngleEps)
      dx = -std::abs(dx);
    else if (std::abs(lastH - 180.0) < kAngleEps)
      dy = std::abs(dy);
    v = std::acos(std::clamp(-dz, -1.0, 1.0)) / kDeg;
    h = std::atan2(dy, dx) / kDeg;
    if (h < 0.0) h += 360.0;
    if (horizontalAngles.size() == 1) h = firstH;
  } else if (type == PhotometricType::A) {
    h = std::atan2(dx, -dz) / kDeg;
    v = std::asin(std::clamp(dy, -1.0, 1.0)) / kDeg;
  } else {
    v = std::atan2(dy, -dz) / kDeg;
    h = std::asin(std::clamp(dx, -1.0, 1.0)) / kDeg;
  }
  if (type != PhotometricType::C) {
    if (std::abs(firstH) < kAngleEps) h = std::abs(h);
    if (horizontalAngles.size() == 1) h = firstH;
  }
  size_t v0, v1, h0, h1;
  double tv, th;
  if (!locate(verticalAngles, v, v0, v1, tv)) return 0.0;
  if (!locate(horizontalAngles, h, h0, h1, th)) {
    // A Type C table without symmetry wraps from its last plane back to its first.
    if (type != PhotometricType::C) return 0.0;
    const double hw = h < firstH ? h + 360.0 : h;
    const double span = firstH + 360.0 - lastH;
    if (!(span > 0.0)) return 0.0;
    h0 = horizontalAngles.size() - 1, h1 = 0;
    th = std::clamp((hw - lastH) / span, 0.0, 1.0);
  }
  const size_t nv = verticalAngles.size();
  auto at = [&](size_t hi, size_t vi) { return candela[hi * nv + vi]; };
  const double a = at(h0, v0) * (1.0 - tv) + at(h0, v1) * tv;
  const double b = at(h1, v0) * (1.0 - tv) + at(h1, v1) * tv;
  return a * (1.0 - th) + b * th;
}

double IesProfile::totalFlux() const {
  const size_t nv = verticalAngles.size(), nh = horizontalAngles.size();
  if (candela.empty()) return 0.0;
  const double firstH = horizontalAngles.front(), lastH = horizontalAngles.back();
  if (type == PhotometricType::B) {
    // Planes at vertical angles V rotate about the x axis; H is a latitude: dOmega = cos H dH dV.
    std::vector<double> g(nv);
    for (size_t v = 0; v < nv; ++v) {
      std::vector<double> column(nh);
      for (size_t h = 0; h < nh; ++h) column[h] = candela[h * nv + v];
      g[v] = nh == 1 ? 2.0 * column[0] : curveIntegral(horizontalAngles, column, false);
      if (nh > 1 && std::abs(firstH) < kAngleEps) g[v] *= 2.0;
    }
    return nv == 1 ? 0.0 : trapezoid(verticalAngles, g);
  }
  // Types A and C: rows over V at each horizontal plane H.
  const bool sinWeight = type == PhotometricType::C;
  std::vector<double> f(nh);
  for (size_t h = 0; h < nh; ++h) {
    const std::vector<double> row(candela.begin() + long(h * nv),
                                  candela.begin() + long(h * nv + nv));
    f[h] = curveIntegral(verticalAngles, row, sinWeight);
  }
  if (type == PhotometricType::A) {
    if (nh == 1) return std::numbers::pi * f[0];
    return trapezoid(horizontalAngles, f) * (std::abs(firstH) < kAngleEps ? 2.0 : 1.0);
  }
  if (nh == 1) return 2.0 * std::numbers::pi * f[0];
  if (std::abs(lastH - 90.0) < kAngleEps) return 4.0 * trapezoid(horizontalAngles, f);
  if (std::abs(lastH - 180.0) < kAngleEps ||
      (std::abs(firstH - 90.0) < kAngleEps && std::abs(lastH - 270.0) < kAngleEps))
    return 2.0 * trapezoid(horizontalAngles, f);
  const double wrap = (firstH + 360.0 - lastH) * kDeg;
  return trapezoid(horizontalAngles, f) + 0.5 * wrap * (f.back() + f.front());
}

double IesProfile::maxCandela() const {
  return candela.empty() ? 0.0 : *std::max_element(candela.begin(), candela.end());
}

namespace {

// Reads TILT=INCLUDE data: geometry, pair count, angles, factors.
void parseTilt(NumberStream& numbers, IesProfile& p) {
  const int geometry = numbers.integer("lamp-to-luminaire geometry (1, 2 or 3)");
  if (geometry < 1 || geometry > 3)
    throw InputError(
        numbers.lineOfPrevious(),
        fmt::format("lamp-to-luminaire geometry {} out of range (1, 2 or 3)", geometry));
  const int pairs = numbers.integer("number of tilt angle/factor pairs");
  if (pairs < 1 || pairs > 100000)
    throw InputError(numbers.lineOfPrevious(),
                     fmt::format("number of tilt pairs {} out of range [1, 100000]", pairs));
  p.tiltAngles = numbers.block(size_t(pairs), "tilt angles");
  p.tiltFactors = numbers.block(size_t(pairs), "tilt multiplying factors");
}

void parseTable(NumberStream& numbers, IesProfile& p) {
  numbers.integer("number of lamps");
  numbers.one("lumens per lamp");  // -1 = absolute photometry; never a scale factor
  p.candelaMultiplier = numbers.one("candela multiplier");
  if (!(p.candelaMultiplier > 0.0))
    throw InputError(numbers.lineOfPrevious(),
                     fmt::format("candela multiplier {} must be > 0", p.candelaMultiplier));
  const int nv = numbers.integer("number of vertical angles");
  const int nh = numbers.integer("number of horizontal angles");
  if (nv < 1 || nv > 100000 || nh < 1 || nh > 100000)
    throw InputError(numbers.lineOfPrevious(),
                     fmt::format("angle counts {} x {} out of range [1, 100000]", nv, nh));
  const int type = numbers.integer("photometric type (1 = C, 2 = B, 3 = A)");
  if (type < 1 || type > 3)
    throw InputError(numbers.lineOfPrevious(),
                     fmt::format("photometric type {} out of range (1 = C, 2 = B, 3 = A)", type));
  p.type = PhotometricType(type);
  numbers.integer("units type (1 = feet, 2 = metres)");
  numbers.block(3, "luminous dimensions (width length height)");
  p.ballastFactor = numbers.one("ballast factor");
  if (!(p.ballastFactor > 0.0))
    throw InputError(numbers.lineOfPrevious(),
                     fmt::format("ballast factor {} must be > 0", p.ballastFactor));
  const double field12 = numbers.one("ballast-lamp factor / file generation type");
  const bool old = p.version == "LM-63-1986" || p.version == "IESNA91";
  if (old && field12 > 0.0) p.ballastFactor *= field12;
  numbers.one("input watts");
  // Type C: V from the nadir [0, 180], H around the axis [0, 360]; types A and B: [-90, 90] both.
  const bool typeC = p.type == PhotometricType::C;
  p.verticalAngles = numbers.block(size_t(nv), "vertical angles");
  requireAscending(p.verticalAngles, "vertical angles", numbers.lineOfPrevious());
  requireWithin(p.verticalAngles, typeC ? 0.0 : -90.0, typeC ? 180.0 : 90.0, "vertical angles",
                numbers.lineOfPrevious());
  p.horizontalAngles = numbers.block(size_t(nh), "horizontal angles");
  requireAscending(p.horizontalAngles, "horizontal angles", numbers.lineOfPrevious());
  requireWithin(p.horizontalAngles, typeC ? 0.0 : -90.0, typeC ? 360.0 : 90.0, "horizontal angles",
                numbers.lineOfPrevious());
  const size_t total = size_t(nv) * size_t(nh);
  p.candela = numbers.block(total, fmt::format("candela values ({} x {})", nh, nv));
  numbers.expectEnd(fmt::format("the {} candela values", total));
  for (double& c : p.candela) {
    if (c < 0.0)
      throw InputError(p.source, fmt::format("negative candela value {} in the table", c));
    c *= p.candelaMultiplier * p.ballastFactor;
    if (!std::isfinite(c))
      throw InputError(p.source, "candela times multiplier and ballast factor is not finite");
  }
}

}  // namespace

IesProfile parseIesProfile(const std::string& text, const std::string& source) {
  IesProfile p;
  p.source = source;
  const std::vector<std::string> lines = splitLines(text);
  const std::string first = lines.empty() ? "" : trim(lines[0]);
  const bool versioned = first.rfind("IESNA", 0) == 0 || first.rfind("IES:", 0) == 0;
  p.version = versioned ? first : "LM-63-1986";
  size_t tiltLine = lines.size();
  for (size_t i = 0; i < lines.size(); ++i)
    if (trim(lines[i]).rfind("TILT", 0) == 0) {
      tiltLine = i;
      break;
    }
  if (tiltLine == lines.size())
    throw InputError(fmt::format("{}:{}", source, lines.size()),
                     "no TILT= line found (expected TILT=NONE or TILT=INCLUDE after the header)");
  std::string tilt = trim(lines[tiltLine]);
  const size_t eq = tilt.find('=');
  const std::string where = fmt::format("{}:{}", source, tiltLine + 1);
  if (eq == std::string::npos)
    throw InputError(
        where, fmt::format("malformed {} (expected TILT=NONE or TILT=INCLUDE)", quotedToken(tilt)));
  tilt = trim(tilt.substr(eq + 1));
  NumberStream numbers(lines, tiltLine + 1, source);
  if (tilt == "INCLUDE") {
    parseTilt(numbers, p);
  } else if (tilt != "NONE") {
    throw InputError(where, fmt::format("TILT={} (a separate tilt file) is not supported; use "
                                        "TILT=NONE or TILT=INCLUDE",
                                        quotedToken(tilt)));
  }
  parseTable(numbers, p);
  return p;
}

IesProfile loadIesProfile(const std::string& path) {
  return parseIesProfile(readTextFile(path, "IES file", kMaxIesFileBytes), path);
}

}  // namespace rad
