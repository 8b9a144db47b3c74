#pragma once
// The command line: `radiosity render|solve|animate|serve|info|bench ...` (contract in
// docs/ARCHITECTURE.md).

#include <iosfwd>
#include <string>
#include <vector>

namespace rad::cli {

/// Runs one command line (without the program name). Returns the exit status: 0 success,
/// 1 runtime failure, 2 bad input or usage. Never throws; errors go to `err` as one line.
int runCli(const std::vector<std::string>& args);
int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace rad::cli
