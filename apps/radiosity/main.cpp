// The radiosity command-line tool. All the work is in runCli (cli.h), which tests call in-process.
#include <string>
#include <vector>

#include "cli.h"

int main(int argc, char** argv) {
  return rad::cli::runCli(std::vector<std::string>(argv + 1, argv + argc));
}
