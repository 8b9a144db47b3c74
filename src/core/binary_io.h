#pragma once
// The pieces of the project's binary files (form-factor caches, solution files): 128-bit keys
// that say what a file was computed for, a checksum of its bytes, and values appended to and
// read from a byte string in the machine's byte order. Hashes: FNV-1a (Fowler, Noll, Vo) for a
// key's high word and a 64-bit multiply-xorshift (the SplitMix64 finalizer, Steele et al.,
// OOPSLA 2014) for its low word and for checksums.

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace rad {

/// What a file was computed for, as a 128-bit hash.
struct Key128 {
  uint64_t high = 0, low = 0;
  std::string hex() const;
  bool operator==(const Key128&) const = default;
};

/// Hashes bytes into a Key128.
class Hasher {
 public:
  void bytes(const void* data, size_t size);
  template <typename T>
  void value(const T& v) {
    bytes(&v, sizeof(T));
  }
  void text(const std::string& s) {
    value(uint64_t(s.size()));
    bytes(s.data(), s.size());
  }
  Key128 key() const;

 private:
  uint64_t fnv_ = 0xcbf29ce484222325ULL, mixed_ = 0x9e3779b97f4a7c15ULL, word_ = 0, count_ = 0;
};

/// Checksum of a byte range.
uint64_t checksum(const char* data, size_t size);
/// True if the last 8 bytes of `bytes` (at least 8 long) are the checksum of the rest.
bool checksumMatches(const std::string& bytes);

template <typename T>
void put(std::string& out, const T& v) {
  out.append(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <typename T>
void putArray(std::string& out, std::span<const T> v) {
  out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
}
/// Reads a T at `at` and moves past it; the caller has checked that it is there.
template <typename T>
T get(const std::string& in, size_t& at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}
template <typename T>
std::vector<T> getArray(const std::string& in, size_t& at, size_t count) {
  std::vector<T> v(count);
  if (count > 0) std::memcpy(v.data(), in.data() + at, count * sizeof(T));  // data() may be null
  at += count * sizeof(T);
  return v;
}

/// Reads values from bytes[begin, end) in order, checking that each is there: what a file whose
/// counts cannot be trusted is read with.
class ByteReader {
 public:
  ByteReader(const std::string& bytes, size_t begin, size_t end)
      : bytes_(bytes), at_(begin), end_(end) {}
  /// Throws std::out_of_range ("truncated") where the value does not fit before the end.
  template <typename T>
  T get() {
    need(sizeof(T), 1);
    return rad::get<T>(bytes_, at_);
  }
  template <typename T>
  std::vector<T> array(uint64_t count) {
    need(sizeof(T), count);
    return getArray<T>(bytes_, at_, size_t(count));
  }
  std::string text() {
    const uint64_t size = get<uint64_t>();
    need(1, size);
    std::string s = bytes_.substr(at_, size_t(size));
    at_ += size_t(size);
    return s;
  }
  bool atEnd() const { return at_ == end_; }
  size_t position() const { return at_; }

 private:
  void need(size_t size, uint64_t count) const;
  const std::string& bytes_;
  size_t at_, end_;
};

/// Whether every value is finite and not negative: what the form factors, irradiances and
/// radiosities a file holds must be (a forged NaN, infinity or negative value would spread
/// through every solve, relight and picture made from it).
inline bool allFiniteNonNegative(std::span<const float> values) {
  for (float v : values)
    if (!(v >= 0.0f && v <= std::numeric_limits<float>::max())) return false;
  return true;
}

inline void putText(std::string& out, const std::string& s) {
  put(out, uint64_t(s.size()));
  out += s;
}

/// The whole file into `bytes`; false if it does not exist (an unreadable one, or one that is not
/// a regular file such as a directory or a FIFO, leaves `bytes` empty and returns true).
bool readWholeFile(const std::filesystem::path& file, std::string& bytes);

}  // namespace rad
