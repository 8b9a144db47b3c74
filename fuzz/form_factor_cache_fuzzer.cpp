// A form-factor cache file, of either kind (a table of patches, or master rows by node), with its
// checksum fixed up and loaded for the key it names. The loader never throws; a table it accepts
// must be one the solver can use: finite, non-negative, columns in range, rows summing to at
// most kMaxCachedRowSum.
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "fuzz_support.h"
#include "patch/form_factor_cache.h"

namespace {

constexpr size_t kKeyAt = 16, kRowsAt = 32;

void checkUsable(const rad::FormFactorTable& table, size_t patches) {
  if (table.rows() != patches) std::abort();
  for (uint32_t c : table.columnArray())
    if (c >= patches) std::abort();
  for (size_t i = 0; i < table.rows(); ++i) {
    const double sum = table.rowSum(i);
    if (!(sum >= 0.0 && sum <= rad::kMaxCachedRowSum)) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  rad::fuzz::fixChecksum(bytes);
  rad::FormFactorCacheKey key;
  uint64_t rows = 0;
  if (bytes.size() >= kRowsAt + 8) {
    std::memcpy(&key.high, bytes.data() + kKeyAt, 8);
    std::memcpy(&key.low, bytes.data() + kKeyAt + 8, 8);
    std::memcpy(&rows, bytes.data() + kRowsAt, 8);
  }
  const std::string file = rad::fuzz::writeInput("cache.bin", bytes);
  const rad::FormFactorCacheLoad table = rad::loadFormFactorTable(file, key, size_t(rows));
  if (table.table) checkUsable(*table.table, size_t(rows));
  const rad::MasterRowsLoad master = rad::loadMasterRows(file, key);
  if (master.rows)
    for (const auto& [address, row] : *master.rows)
      for (const auto* hits : {&row.hits, &row.exact})
        for (const rad::HemisphereHit& h : *hits)
          if (!(h.weight >= 0.0f && std::isfinite(h.weight))) std::abort();
  return 0;
}
