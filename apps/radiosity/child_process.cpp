#include "child_process.h"

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>

extern char** environ;

namespace rad::cli {

std::string selfExecutable() {
  return std::filesystem::read_symlink("/proc/self/exe").string();
}

void runToCompletion(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0)
    throw std::runtime_error(fmt::format("cannot start {}", argv[0]));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        fmt::format("'{} {}' failed", argv[0], argv.size() > 1 ? argv[1] : ""));
}

}  // namespace rad::cli
