#include <fcntl.h>
#include <radiosity/atomic_file.h>
#include <radiosity/error.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <set>
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

// The pid in a temporary's name (".<name>.tmp-<pid>-<n>"), or 0 when the name is not one.
pid_t writerOf(const std::string& name) {
  const size_t tag = name.rfind(".tmp-");
  if (name.empty() || name[0] != '.' || tag == std::string::npos) return 0;
  const std::string rest = name.substr(tag + 5);
  const size_t dash = rest.find('-');
  if (dash == 0 || dash == std::string::npos || dash + 1 == rest.size() ||
      rest.find_first_not_of("0123456789-") != std::string::npos)
    return 0;
  return pid_t(std::stol(rest.substr(0, dash)));
}

// Temporaries whose writer was killed (kill -9, a power cut) are removed the next time anything
// is written to their directory: once per directory and process, since that costs a listing.
void removeStaleTemporaries(const fs::path& directory) {
  static std::mutex mutex;
  static std::set<fs::path> swept;
  {
    const std::lock_guard lock(mutex);
    if (!swept.insert(fs::absolute(directory)).second) return;
  }
  std::error_code ec;
  for (fs::directory_iterator it(directory, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t pid = writerOf(it->path().filename().string());
    if (pid > 0 && pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH)
      removeQuietly(it->path());
  }
}

}  // namespace

namespace {
std::atomic<bool> writesFiles{true};
}  // namespace

void setWritesFiles(bool writes) {
  writesFiles = writes;
}

namespace {

// A writer's failure (the disk full, the device refusing) as what it is to the user: an output
// that cannot be written, like a bad output path (InputError: exit 2).
void asOutputError(const std::function<void()>& work) {
  try {
    work();
  } catch (const InputError&) {
    throw;
  } catch (const Cancelled&) {
    throw;
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
}

}  // namespace

void writeFileAtomically(const fs::path& target,
                         const std::function<void(const fs::path& temporary)>& write) {
  if (!writesFiles) return;
  if (target.filename().empty())
    throw std::runtime_error("cannot write '" + target.string() + "': not a file name");
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec))
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" +
                             directory.string() + "' does not exist");

  const fs::file_status status = fs::status(target, ec);
  if (fs::is_directory(status))
    throw std::runtime_error("cannot write '" + target.string() + "': it is a directory");
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    // A device or a pipe (/dev/null, /dev/stdout, a FIFO) is written to, never replaced.
    asOutputError([&] { write(target); });
    return;
  }
  removeStaleTemporaries(directory);
  const fs::path temporary = temporaryPathFor(target);
  try {
    asOutputError([&] {
      write(temporary);
      if (!fs::exists(temporary, ec))
        throw std::runtime_error("cannot write '" + target.string() +
                                 "': the writer produced no file");
      flushToDisk(temporary);
      fs::rename(temporary, target, ec);
      if (ec) throw std::runtime_error("cannot write '" + target.string() + "': " + ec.message());
    });
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
