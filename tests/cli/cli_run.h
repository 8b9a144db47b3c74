#pragma once
// Running the command line in-process, and the files its tests write and read.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli.h"

namespace rad::test {

namespace fs = std::filesystem;

struct CliResult {
  int status;
  std::string out, err;
};

inline CliResult run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  const int status = rad::cli::runCli(args, out, err);
  return {status, out.str(), err.str()};
}

inline fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(::testing::TempDir()) / ("radiosity_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline fs::path writeFile(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

inline std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace rad::test
