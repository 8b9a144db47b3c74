#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace rad {

namespace {

namespace fs = std::filesystem;

fs::path temporaryPathFor(const fs::path& target) {
  // The pid separates processes, the counter threads and repeated writes within one process.
  static std::atomic<uint64_t> counter{0};
  const uint64_t n = counter.fetch_add(1, std::memory_order_relaxed);
  // Appended piecewise: GCC 12 reports a spurious -Wrestrict for `"." + std::string`.
  std::string name(1, '.');
  name += target.filename().string();
  name += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n);
  return target.parent_path() / name;
}

// Without the fsync, a crash shortly after the rename can leave an empty file under the final
// name on file systems that reorder metadata and data writes.
void flushToDisk(const fs::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;  // best effort: the content is already written
  (void)::fsync(fd);
  ::close(fd);
}

void removeQuietly(const fs::path& file) {
  std::error_code ignored;
  fs::remove(file, ignored);
}

}  // namespace

void writeFileAtomically(const fs::path& target,
                         const std::function<void(const fs::path& temporary)>& write) {
  if (target.filename().empty())
    throw std::runtime_error("cannot write '" + target.string() + "': not a file name");
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec))
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" +
                             directory.string() + "' does not exist");

  const fs::path temporary = temporaryPathFor(target);
  try {
    write(temporary);
    if (!fs::exists(temporary, ec))
      throw std::runtime_error("cannot write '" + target.string() +
                               "': the writer produced no file");
    flushToDisk(temporary);
    fs::rename(temporary, target, ec);
    if (ec) throw std::runtime_error("cannot write '" + target.string() + "': " + ec.message());
  } catch (...) {
    removeQuietly(temporary);
    throw;
  }
}

void writeBytesAtomically(const fs::path& target, std::span<const char> bytes) {
  writeFileAtomically(target, [&](const fs::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out)
      throw std::runtime_error("cannot write '" + target.string() + "': " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (out.fail())
      throw std::runtime_error("cannot write '" + target.string() + "': write failed (disk full?)");
  });
}

void writeTextAtomically(const fs::path& target, const std::string& text) {
  writeBytesAtomically(target, std::span<const char>(text.data(), text.size()));
}

}  // namespace rad
