// readSensorCsv: sensor points from a spreadsheet's CSV, a row a point (x,y,z,nx,ny,nz[,name]).
#include <fmt/format.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>
#include <radiosity/scene_builder.h>
#include <radiosity/sensors.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtx/component_wise.hpp>
#include <map>

#include "scene/io/text_file.h"

namespace rad {

namespace {

// A CSV field without the blanks and the quotes a spreadsheet puts around it.
std::string_view trimmedField(std::string_view field) {
  while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
  while (!field.empty() && (field.back() == ' ' || field.back() == '\t' || field.back() == '\r'))
    field.remove_suffix(1);
  if (field.size() >= 2 && field.front() == '"' && field.back() == '"')
    field = field.substr(1, field.size() - 2);
  return field;
}

std::vector<std::string_view> csvFields(std::string_view line) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  for (size_t comma = line.find(','); comma != std::string_view::npos;
       comma = line.find(',', start)) {
    fields.push_back(trimmedField(line.substr(start, comma - start)));
    start = comma + 1;
  }
  fields.push_back(trimmedField(line.substr(start)));
  return fields;
}

// A row's point, or the reason it is not one (named by the caller with the file and line).
SensorPoint sensorRow(const std::vector<std::string_view>& fields, const std::string& where) {
  static const char* const kColumns[] = {"x", "y", "z", "nx", "ny", "nz"};
  float v[6];
  for (int i = 0; i < 6; ++i) {
    const std::optional<double> number = parseNumber(fields[size_t(i)]);
    if (!number || !std::isfinite(*number))
      throw InputError(where, fmt::format("column {} ({}): expected a finite number, got {}", i + 1,
                                          kColumns[i], quotedToken(fields[size_t(i)])));
    v[i] = float(*number);
  }
  SensorPoint p{Vec3(v[0], v[1], v[2]), Vec3(v[3], v[4], v[5])};
  if (!(glm::compMax(glm::abs(p.position)) <= kMaxSceneCoordinate))
    throw InputError(where, fmt::format("position beyond {:g} scene units", kMaxSceneCoordinate));
  const float length = glm::length(p.normal);
  if (!(length > 0.0f) || !std::isfinite(length))
    throw InputError(where, "the normal (nx, ny, nz) must be a non-zero vector");
  p.normal /= length;
  return p;
}

}  // namespace

std::vector<SensorSet> readSensorCsv(const std::string& path) {
  const std::string text = readTextFile(path, "sensor file");
  std::vector<SensorSet> sets;
  std::map<std::string, size_t, std::less<>> setOf;
  size_t lineNumber = 0, start = 0;
  bool first = true;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = trimmedField(std::string_view(text).substr(start, end - start));
    start = end + 1;
    ++lineNumber;
    if (line.empty() || line.front() == '#') continue;
    const std::vector<std::string_view> fields = csvFields(line);
    const bool header = first && !parseNumber(fields.front());
    first = false;
    if (header) continue;
    const std::string where = fmt::format("{}:{}", path, lineNumber);
    if (fields.size() != 6 && fields.size() != 7)
      throw InputError(where,
                       fmt::format("expected x,y,z,nx,ny,nz[,name], got {} fields", fields.size()));
    const std::string name(fields.size() == 7 && !fields[6].empty() ? fields[6] : fileStem(path));
    auto [it, added] = setOf.try_emplace(name, sets.size());
    if (added) sets.push_back({name, {}});
    sets[it->second].points.push_back(sensorRow(fields, where));
  }
  if (sets.empty()) throw InputError(path, "no sensor rows (expected x,y,z,nx,ny,nz[,name])");
  return sets;
}

}  // namespace rad
