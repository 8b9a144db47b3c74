// IES LM-63 parser and evaluator. References: docs/references.md section 4 (layout, symmetry,
// the flux of the photompy tilt file) and closed-form integrals stated beside each test.

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/ies_profile.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

namespace rad {
namespace {

const std::string kIesDir = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/ies/";
constexpr double kPi = std::numbers::pi;

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Direction of (V, H) in the luminaire frame of docs/references.md 4.3 (V from nadir -z, H from +x
// toward +y).
double at(const IesProfile& p, double vDeg, double hDeg) {
  const double v = vDeg * kPi / 180.0, h = hDeg * kPi / 180.0;
  return p.candelaToward(std::sin(v) * std::cos(h), std::sin(v) * std::sin(h), -std::cos(v));
}

std::string messageOf(const std::string& text, const std::string& source) {
  try {
    parseIesProfile(text, source);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(IesProfile, TiltIncludeFileHeaderAndTable) {
  const IesProfile p = loadIesProfile(kIesDir + "photompy_tilt_include_v19.ies");
  EXPECT_EQ(p.version, "IES:LM-63-2019");
  EXPECT_EQ(p.type, PhotometricType::C);
  ASSERT_EQ(p.verticalAngles.size(), 5u);
  ASSERT_EQ(p.horizontalAngles.size(), 3u);
  EXPECT_DOUBLE_EQ(p.verticalAngles[1], 22.5);
  EXPECT_DOUBLE_EQ(p.horizontalAngles[2], 90.0);
  ASSERT_EQ(p.tiltAngles.size(), 7u);
  EXPECT_DOUBLE_EQ(p.tiltFactors.back(), 0.75);
  // Field 12 is 1.10000 (file generation type), not a scale factor (docs/references.md 4.2).
  EXPECT_DOUBLE_EQ(p.candela[4], 500.0);
  EXPECT_DOUBLE_EQ(p.maxCandela(), 10000.0);
}

TEST(IesProfile, InterpolatesAndFoldsQuadrantSymmetry) {
  const IesProfile p = loadIesProfile(kIesDir + "photompy_tilt_include_v19.ies");
  // Table nodes (rows of the file: H = 0, 45, 90).
  EXPECT_NEAR(at(p, 0, 0), 10000.0, 1e-6);
  EXPECT_NEAR(at(p, 45, 45), 4500.0, 1e-6);
  EXPECT_NEAR(at(p, 90, 90), 300.0, 1e-6);
  // Midpoints: linear in V, bilinear in (V, H).
  EXPECT_NEAR(at(p, 11.25, 0), 9000.0, 1e-6);
  EXPECT_NEAR(at(p, 11.25, 22.5), 0.25 * (10000 + 8000 + 10000 + 7500), 1e-6);
  // Last H = 90: each quadrant mirrors the first (docs/references.md 4.3).
  EXPECT_NEAR(at(p, 45, 180), 5000.0, 1e-6);
  EXPECT_NEAR(at(p, 45, 270), 4000.0, 1e-6);
  EXPECT_NEAR(at(p, 45, 135), 4500.0, 1e-6);
  EXPECT_NEAR(at(p, 67.5, 315), 1800.0, 1e-6);
  // The table covers the lower hemisphere only.
  EXPECT_EQ(at(p, 120, 0), 0.0);
}

TEST(IesProfile, TiltFileFluxMatchesValidation) {
  // docs/references.md 4.5: 20 826.25 lm without tilt factors.
  const IesProfile p = loadIesProfile(kIesDir + "photompy_tilt_include_v19.ies");
  EXPECT_NEAR(p.totalFlux(), 20826.25, 0.01);
}

TEST(IesProfile, CrlfAndWrappedNumbersParseTheSame) {
  // The file is CRLF (as copied); make an LF copy, a CRLF copy of that, and a wrapped copy.
  std::string text;
  for (char c : readFile(kIesDir + "photompy_tilt_include_v19.ies"))
    if (c != '\r') text += c;
  std::string crlf, wrapped;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  // After TILT, one number per line with commas: LM-63-2002 lets numbers wrap anywhere.
  const size_t tilt = text.find('\n', text.find("\nTILT=INCLUDE") + 1) + 1;
  wrapped = text.substr(0, tilt);
  std::istringstream rest(text.substr(tilt));
  for (std::string word; rest >> word;) wrapped += word + ",\n";
  const IesProfile a = parseIesProfile(text, "a.ies"), b = parseIesProfile(crlf, "b.ies"),
                   c = parseIesProfile(wrapped, "c.ies");
  EXPECT_EQ(a.candela, b.candela);
  EXPECT_EQ(a.candela, c.candela);
  EXPECT_EQ(a.horizontalAngles, c.horizontalAngles);
}

TEST(IesProfile, TypeBFile) {
  const IesProfile p = loadIesProfile(kIesDir + "photompy_type_b_symmetric.ies");
  EXPECT_EQ(p.type, PhotometricType::B);
  EXPECT_EQ(p.candela.size(), 25u);
  EXPECT_DOUBLE_EQ(p.maxCandela(), 25000.0);
  // Photometric zero is the aim (-z); H = 0..90 is mirrored laterally (docs/references.md 4.3).
  EXPECT_NEAR(p.candelaToward(0, 0, -1), 25000.0, 1e-6);
  const double s = std::sin(22.5 * kPi / 180), c = std::cos(22.5 * kPi / 180);
  EXPECT_NEAR(p.candelaToward(s, 0, -c), 24000.0, 1e-6);
  EXPECT_NEAR(p.candelaToward(-s, 0, -c), 24000.0, 1e-6);
  EXPECT_NEAR(p.candelaToward(0, s, -c), 22000.0, 1e-6);
  EXPECT_GT(p.totalFlux(), 0.0);
}

// A Type C table with constant intensity I over the lower hemisphere emits 2 pi I lumens;
// over the whole sphere 4 pi I (the integral of sin V over [0, pi/2] is 1, over [0, pi] 2).
TEST(IesProfile, ConstantTablesHaveClosedFormFlux) {
  const std::string lower =
      "IESNA:LM-63-2002\n[TEST] t\nTILT=NONE\n"
      "1 -1 1 3 1 1 2 0 0 0\n1 1 10\n0 45 90\n0\n100 100 100\n";
  EXPECT_NEAR(parseIesProfile(lower, "lower.ies").totalFlux(), 2 * kPi * 100, 1e-9);
  const std::string sphere =
      "IESNA:LM-63-2002\nTILT=NONE\n"
      "1 -1 2 3 1 1 2 0 0 0\n0.5 1 10\n0 90 180\n0\n100 100 100\n";
  const IesProfile p = parseIesProfile(sphere, "sphere.ies");
  // Multiplier 2 and ballast factor 0.5 cancel.
  EXPECT_NEAR(p.totalFlux(), 4 * kPi * 100, 1e-9);
  EXPECT_NEAR(at(p, 150, 77), 100.0, 1e-9);
}

// Full-circle table without the 360 plane: the last plane interpolates back to the first.
// I(H) piecewise linear through 100, 200, 300, 200 at 0, 90, 180, 270 (and 100 at 360), constant
// in V over the sphere: flux = 2 * integral of I dH = 2 * (pi/2)(150 + 250 + 250 + 150) = 800 pi.
TEST(IesProfile, FullCircleWrapsAround) {
  const std::string text =
      "IESNA:LM-63-1995\nTILT=NONE\n1 1000 1 2 4 1 2 0 0 0\n1 1 10\n0 180\n"
      "0 90 180 270\n100 100\n200 200\n300 300\n200 200\n";
  const IesProfile p = parseIesProfile(text, "full.ies");
  EXPECT_NEAR(p.totalFlux(), 800 * kPi, 1e-9);
  EXPECT_NEAR(at(p, 90, 315), 150.0, 1e-9);
  EXPECT_NEAR(at(p, 90, 135), 250.0, 1e-9);
}

TEST(IesProfile, BilateralSymmetryFolds) {
  // Last H = 180: mirror about the 0-180 plane, so H = 270 reads the 90 plane.
  const std::string text =
      "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 2 3 1 2 0 0 0\n1 1 10\n0 90\n"
      "0 90 180\n10 10\n20 20\n30 30\n";
  const IesProfile p = parseIesProfile(text, "bilateral.ies");
  EXPECT_NEAR(at(p, 45, 270), 20.0, 1e-9);
  EXPECT_NEAR(at(p, 45, 225), 25.0, 1e-9);
}

TEST(IesProfile, BadInputNamesFileAndLine) {
  const std::string head = "IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 5 1 1 2 0 0 0\n1 1 10\n";
  // Only 3 of 5 vertical angles, then the horizontal angle line is read as more of them: the
  // count runs out at the end of the file (line 6).
  std::string m = messageOf(head + "0 45 90\n0\n", "short.ies");
  EXPECT_NE(m.find("short.ies:6"), std::string::npos) << m;
  EXPECT_NE(m.find("expected 5 vertical angles, found 4"), std::string::npos) << m;
  m = messageOf(head + "0 22.5 4x5 67.5 90\n0\n1 2 3 4 5\n", "bad.ies");
  EXPECT_NE(m.find("bad.ies:5"), std::string::npos) << m;
  EXPECT_NE(m.find("4x5"), std::string::npos) << m;
  m = messageOf(head + "0 22.5 45 67.5 90\n0\n1 2 3 4\n", "truncated.ies");
  EXPECT_NE(m.find("truncated.ies:7"), std::string::npos) << m;
  EXPECT_NE(m.find("found 4"), std::string::npos) << m;
  m = messageOf(head + "0 22.5 45 67.5 90\n0\n1 2 3 4 5 6\n", "extra.ies");
  EXPECT_NE(m.find("extra.ies:7"), std::string::npos) << m;
  m = messageOf("IESNA:LM-63-2002\nTILT=lamp.tlt\n1 -1 1 1 1 1 2 0 0 0\n1 1 10\n0\n0\n1\n",
                "t.ies");
  EXPECT_NE(m.find("t.ies:2"), std::string::npos) << m;
  EXPECT_NE(m.find("not supported"), std::string::npos) << m;
  m = messageOf("IESNA:LM-63-2002\n[TEST] x\n", "notilt.ies");
  EXPECT_NE(m.find("notilt.ies"), std::string::npos) << m;
  m = messageOf("IESNA:LM-63-2002\nTILT=NONE\n1 -1 1 1 1 7 2 0 0 0\n1 1 10\n0\n0\n1\n", "type.ies");
  EXPECT_NE(m.find("type.ies:3"), std::string::npos) << m;
  EXPECT_THROW(loadIesProfile(kIesDir + "missing.ies"), InputError);
}

}  // namespace
}  // namespace rad
