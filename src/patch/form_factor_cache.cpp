// The disk cache of form-factor tables (keys and checksums: core/binary_io.h).
#include "patch/form_factor_cache.h"

#include <fmt/format.h>
#include <radiosity/cache_directory.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "core/binary_io.h"
#include "core/checksummed_file.h"
#include "scene/scene_hash.h"

namespace rad {

namespace {

constexpr char kMagic[8] = {'R', 'A', 'D', 'F', 'F', 'T', 'B', 'L'};
// 2: the emitters' columns exact (ExactColumns); 3: thresholded rows keep their sums.
constexpr uint32_t kVersion = 3;
constexpr size_t kHeaderBytes = 8 + 4 + 4 + 16 + 16 + 32;
// The master table's file: the rows of every node computed, by node address.
constexpr char kMasterMagic[8] = {'R', 'A', 'D', 'M', 'F', 'F', 'R', 'W'};
constexpr uint32_t kMasterVersion = 1;

std::string notUsed(const std::filesystem::path& file, const std::string& why) {
  return fmt::format("form-factor cache {} not used ({}); recomputing", file.string(), why);
}

// What every cache file starts with: its magic, its format version (and 4 spare bytes) and the
// key it was computed for; `at` is where what follows starts. `rejected` says why a file that
// exists cannot be used (empty when it may be, so far).
struct CacheFileStart {
  bool exists = false;
  std::string bytes;
  std::string rejected;
  FormFactorCacheKey key;
  size_t at = 0;
};
CacheFileStart readCacheFileStart(const std::filesystem::path& file, const char (&magic)[8],
                                  uint32_t version, size_t headerBytes) {
  CacheFileStart f;
  f.exists = readWholeFile(file, f.bytes);
  if (!f.exists) return f;
  if (f.bytes.empty()) {
    f.rejected = "unreadable";
  } else if (f.bytes.size() < headerBytes + 8) {
    f.rejected = "truncated";
  } else if (std::memcmp(f.bytes.data(), magic, 8) != 0) {
    f.rejected = "not a form-factor cache file";
  } else {
    f.at = 8;
    const uint32_t stored = get<uint32_t>(f.bytes, f.at);
    f.at += 4;
    if (stored != version)
      f.rejected = fmt::format("format version {}, expected {}", stored, version);
    else
      f.key = {get<uint64_t>(f.bytes, f.at), get<uint64_t>(f.bytes, f.at)};
  }
  return f;
}

// The reason a table read from disk cannot be right for `patches` rows, or "".
std::string checkTable(const std::vector<uint64_t>& offsets, const std::vector<uint32_t>& columns,
                       const std::vector<float>& values, size_t patches) {
  if (offsets.front() != 0 || offsets.back() != columns.size()) return "row offsets inconsistent";
  for (size_t i = 0; i + 1 < offsets.size(); ++i)
    if (offsets[i] > offsets[i + 1]) return "row offsets not increasing";
  for (uint32_t c : columns)
    if (c >= patches) return "column out of range";
  // Not v <= 1: a thresholded table gathers light redirected to small patches from large ones
  // (FormFactorTable::applyThreshold), which can exceed 1 where the table does not lose light.
  if (!allFiniteNonNegative(values)) return "form factor negative or not finite";
  // A row's sum is the fraction of the patch's light that reaches other patches: a forged row
  // far above 1 makes the solver diverge (a residual of NaN after its last sweep).
  for (size_t i = 0; i + 1 < offsets.size(); ++i) {
    double sum = 0.0;
    for (uint64_t k = offsets[i]; k < offsets[i + 1]; ++k) sum += values[k];
    if (sum > kMaxCachedRowSum)
      return fmt::format(
          "row {} sums to {:.3g}, above {} (a patch's form factors sum to 1 at most)", i, sum,
          kMaxCachedRowSum);
  }
  return "";
}

}  // namespace

FormFactorCacheKey formFactorCacheKey(const Scene& scene, const PatchMesh& mesh,
                                      const FormFactorSettings& settings, float threshold) {
  Hasher h;
  h.value(kVersion);
  hashGeometry(h, scene);
  for (const Face& f : scene.faces)
    h.value(uint8_t(scene.materials[f.material].emits()));  // the threshold keeps emitters
  h.value(mesh.patchSize());
  h.value(uint64_t(mesh.size()));
  for (const Patch& p : mesh.patches()) h.value(p.node);
  h.value(int(settings.estimator));
  h.value(uint64_t(settings.exactColumns.size()));
  h.bytes(settings.exactColumns.data(), settings.exactColumns.size() * sizeof(uint32_t));
  h.value(settings.rays);
  h.value(settings.seed);
  h.value(threshold);
  return h.key();
}

FormFactorCacheKey masterTableCacheKey(const Scene& scene, const PatchMesh& baseMesh, int levels,
                                       int rays, uint64_t seed) {
  Hasher h;
  h.value(kMasterVersion);
  hashGeometry(h, scene);
  h.value(baseMesh.patchSize());
  h.value(levels);
  h.value(rays);
  h.value(seed);
  return h.key();
}

std::filesystem::path masterTableCacheFile(const std::filesystem::path& dir,
                                           const FormFactorCacheKey& key) {
  return dir / ("masterff-" + key.hex() + ".bin");
}

MasterRowsLoad loadMasterRows(const std::filesystem::path& file, const FormFactorCacheKey& key) {
  MasterRowsLoad result;
  auto reject = [&](const std::string& why) {
    result.warning = notUsed(file, why);
    return result;
  };
  CacheFileStart f = readCacheFileStart(file, kMasterMagic, kMasterVersion, 8 + 4 + 4 + 16 + 8);
  if (!f.exists) return result;
  if (!f.rejected.empty()) return reject(f.rejected);
  const std::string& bytes = f.bytes;
  size_t at = f.at;
  const uint64_t count = get<uint64_t>(bytes, at);
  // The rows' layout first (a cut file is "truncated"), then the checksum, then the values.
  const size_t end = bytes.size() - 8, first = at;
  for (uint64_t r = 0; r < count; ++r) {
    if (end - at < 8 + 8 + 4 + 4 + 4) return reject("truncated");
    at += 20;
    const uint32_t hits = get<uint32_t>(bytes, at), exact = get<uint32_t>(bytes, at);
    if (uint64_t(hits) + exact > (end - at) / 12) return reject("truncated");
    at += 12 * (size_t(hits) + exact);
  }
  if (at != end) return reject("trailing bytes");
  if (!checksumMatches(bytes)) return reject("checksum mismatch: corrupt");
  if (!(f.key == key)) return reject("computed for other geometry or settings");
  MasterRows rows;
  at = first;
  // Weights are form factors: each finite and non-negative, a row's sum at most about 1.
  auto read = [&](std::vector<HemisphereHit>& out, uint32_t n) {
    out.resize(n);
    double sum = 0.0;
    for (HemisphereHit& h : out) {
      h.key = get<uint64_t>(bytes, at);
      h.weight = get<float>(bytes, at);
      if (!(h.weight >= 0.0f && std::isfinite(h.weight))) return false;
      sum += h.weight;
    }
    return sum <= kMaxCachedRowSum;
  };
  for (uint64_t r = 0; r < count; ++r) {
    const uint64_t address = get<uint64_t>(bytes, at);
    MasterRow& row = rows[address];
    row.exactSet = get<uint64_t>(bytes, at);
    const uint32_t flags = get<uint32_t>(bytes, at);
    row.hasHits = flags & 1;
    row.hasExact = flags & 2;
    const uint32_t hits = get<uint32_t>(bytes, at), exact = get<uint32_t>(bytes, at);
    if (!read(row.hits, hits) || !read(row.exact, exact))
      return reject(fmt::format("a form factor negative or not finite, or a row summing above {}",
                                kMaxCachedRowSum));
  }
  result.rows = std::move(rows);
  touchCacheFile(file);
  return result;
}

std::string saveMasterRows(const std::filesystem::path& file, const FormFactorCacheKey& key,
                           const MasterRows& rows) {
  std::string out;
  out.append(kMasterMagic, 8);
  put(out, kMasterVersion);
  put(out, uint32_t(0));
  put(out, key.high);
  put(out, key.low);
  put(out, uint64_t(rows.size()));
  auto write = [&](const std::vector<HemisphereHit>& hits) {
    for (const HemisphereHit& h : hits) {
      put(out, uint64_t{h.key});  // a copy: the packed field may lie on a 4-byte boundary
      put(out, float{h.weight});
    }
  };
  for (const auto& [address, row] : rows) {
    put(out, address);
    put(out, row.exactSet);
    put(out, uint32_t((row.hasHits ? 1 : 0) | (row.hasExact ? 2 : 0)));
    put(out, uint32_t(row.hits.size()));
    put(out, uint32_t(row.exact.size()));
    write(row.hits);
    write(row.exact);
  }
  return saveChecksummed(file, out, "form-factor cache");
}

std::filesystem::path defaultFormFactorCacheDir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return std::filesystem::path(xdg) / "radiosity";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "radiosity";
  return {};
}

std::filesystem::path formFactorCacheFile(const std::filesystem::path& dir,
                                          const FormFactorCacheKey& key) {
  return dir / ("formfactors-" + key.hex() + ".bin");
}

FormFactorCacheLoad loadFormFactorTable(const std::filesystem::path& file,
                                        const FormFactorCacheKey& key, size_t patches) {
  FormFactorCacheLoad result;
  auto reject = [&](const std::string& why) {
    result.warning = notUsed(file, why);
    return result;
  };
  CacheFileStart f = readCacheFileStart(file, kMagic, kVersion, kHeaderBytes);
  if (!f.exists) return result;
  if (!f.rejected.empty()) return reject(f.rejected);
  const std::string& bytes = f.bytes;
  size_t at = f.at;
  const uint64_t rows = get<uint64_t>(bytes, at), nnz = get<uint64_t>(bytes, at);
  ThresholdLoss loss;
  loss.entryFraction = get<double>(bytes, at);
  loss.sumFraction = get<double>(bytes, at);
  loss.worstRowFraction = get<double>(bytes, at);
  loss.rowsOverOnePercent = get<uint64_t>(bytes, at);
  if (rows > bytes.size() || nnz > bytes.size()) return reject("corrupt header");
  const uint64_t expected = kHeaderBytes + (rows + 1) * 8 + nnz * 8 + 8;
  if (bytes.size() != expected)
    return reject(bytes.size() < expected ? "truncated" : "trailing bytes");
  if (!checksumMatches(bytes)) return reject("checksum mismatch: corrupt");
  if (!(f.key == key) || rows != patches) return reject("computed for other geometry or settings");
  auto offsets = getArray<uint64_t>(bytes, at, rows + 1);
  auto columns = getArray<uint32_t>(bytes, at, nnz);
  auto values = getArray<float>(bytes, at, nnz);
  if (const std::string bad = checkTable(offsets, columns, values, patches); !bad.empty())
    return reject(bad);
  result.table =
      FormFactorTable::fromArrays(std::move(offsets), std::move(columns), std::move(values), loss);
  touchCacheFile(file);
  return result;
}

std::string saveFormFactorTable(const std::filesystem::path& file, const FormFactorCacheKey& key,
                                const FormFactorTable& table) {
  std::string out;
  out.reserve(kHeaderBytes + table.memoryBytes() + 8);
  out.append(kMagic, 8);
  put(out, kVersion);
  put(out, uint32_t(0));
  put(out, key.high);
  put(out, key.low);
  put(out, uint64_t(table.rows()));
  put(out, uint64_t(table.nonZeros()));
  put(out, table.thresholdLoss().entryFraction);
  put(out, table.thresholdLoss().sumFraction);
  put(out, table.thresholdLoss().worstRowFraction);
  put(out, table.thresholdLoss().rowsOverOnePercent);
  putArray(out, table.offsetArray());
  putArray(out, table.columnArray());
  putArray(out, table.valueArray());
  return saveChecksummed(file, out, "form-factor cache");
}

}  // namespace rad
