#include "core/binary_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include "core/rng.h"

namespace rad {

std::string Key128::hex() const {
  return fmt::format("{:016x}{:016x}", high, low);
}

void Hasher::bytes(const void* data, size_t size) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t k = 0; k < size; ++k) {
    fnv_ = (fnv_ ^ p[k]) * 0x100000001b3ULL;
    word_ |= uint64_t(p[k]) << (8 * (count_++ % 8));
    if (count_ % 8 == 0) {
      mixed_ = splitMix64(mixed_ ^ word_);
      word_ = 0;
    }
  }
}

Key128 Hasher::key() const {
  return {fnv_, splitMix64(mixed_ ^ word_ ^ count_)};
}

uint64_t checksum(const char* data, size_t size) {
  uint64_t h = 0x2545f4914f6cdd1dULL ^ size;
  size_t k = 0;
  for (; k + 8 <= size; k += 8) {
    uint64_t w;
    std::memcpy(&w, data + k, 8);
    h = splitMix64(h ^ w) + k;
  }
  uint64_t tail = 0;
  std::memcpy(&tail, data + k, size - k);
  return splitMix64(h ^ tail);
}

bool checksumMatches(const std::string& bytes) {
  uint64_t sum;
  std::memcpy(&sum, bytes.data() + bytes.size() - 8, 8);
  return sum == checksum(bytes.data(), bytes.size() - 8);
}

void ByteReader::need(size_t size, uint64_t count) const {
  if (count > (end_ - at_) / std::max<size_t>(size, 1)) throw std::out_of_range("truncated");
}

bool readWholeFile(const std::filesystem::path& file, std::string& bytes) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(file, ec);
  if (!std::filesystem::exists(status)) return false;
  bytes.clear();
  // A directory cannot be read, and opening a FIFO would wait for a writer forever.
  if (!std::filesystem::is_regular_file(status)) return true;
  std::ifstream in(file, std::ios::binary);
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) bytes.clear();
  return true;
}

}  // namespace rad
