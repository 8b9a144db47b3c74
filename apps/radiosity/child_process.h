#pragma once
// Runs another program, or this one, to completion: the benchmarks that need a process of their
// own (a method's peak memory, a run under mpirun).

#include <string>
#include <vector>

namespace rad::cli {

/// This executable's path (/proc/self/exe).
std::string selfExecutable();
/// Runs argv[0] (searched in PATH) with the rest as its arguments, waits for it, and throws
/// std::runtime_error naming it if it cannot start or exits non-zero.
void runToCompletion(const std::vector<std::string>& argv);

}  // namespace rad::cli
