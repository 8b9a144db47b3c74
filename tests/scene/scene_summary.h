#pragma once
// Test helpers: order-independent summaries of a loaded scene, so that the same geometry read
// from different formats (or built in code) can be compared.

#include <gtest/gtest.h>
#include <radiosity/error.h>
#include <radiosity/scene.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <tuple>

namespace rad::test {

inline const std::string kData = std::string(RADIOSITY_TEST_DATA_DIR) + "/scene/";

/// Position rounded to a grid of `step`, as a sortable key.
inline std::tuple<long, long, long> key(const Vec3& p, double step) {
  return {std::lround(p.x / step), std::lround(p.y / step), std::lround(p.z / step)};
}

/// For one object: area by (rounded) front normal, the set of corner positions, its material.
struct ObjectSummary {
  std::map<std::tuple<long, long, long>, double> areaByNormal;
  std::set<std::tuple<long, long, long>> positions;
  double area = 0.0;
  double volume = 0.0;  ///< signed: > 0 for a closed surface whose fronts face out
  size_t triangles = 0;
  const Material* material = nullptr;
};

inline std::map<std::string, ObjectSummary> summarize(const Scene& s, double positionStep) {
  std::map<std::string, ObjectSummary> out;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) {
    ObjectSummary& o = out[s.objects[s.faceOf(t).object].name];
    const double a = s.triangleArea(t);
    o.area += a;
    const Vec3d p0 = s.positions[s.triangles[t].x], p1 = s.positions[s.triangles[t].y],
                p2 = s.positions[s.triangles[t].z];
    o.volume += glm::dot(p0, glm::cross(p1, p2)) / 6.0;
    o.areaByNormal[key(s.triangleNormal(t), 1e-3)] += a;
    for (int k = 0; k < 3; ++k)
      o.positions.insert(key(s.positions[s.triangles[t][k]], positionStep));
    ++o.triangles;
    o.material = &s.materialOf(t);
  }
  return out;
}

/// A fresh directory for files a test writes.
inline std::filesystem::path scratchDir(const std::string& name) {
  // One folder per test: ctest runs the tests of a suite in parallel processes.
  const testing::TestInfo* test = testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir =
      std::filesystem::path(testing::TempDir()) /
      ("rad_scene_" + name + "_" + test->test_suite_name() + "_" + test->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path.string();
}

/// The InputError message `f` throws, or "(no error)".
inline std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace rad::test
