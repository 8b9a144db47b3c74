// The radiosity command-line tool. All the work is in runCli (cli.h), which tests call in-process.
#include <string>
#include <vector>

#include "cli.h"
#include "mpi_processes.h"

int main(int argc, char** argv) {
  rad::cli::MpiProcesses::start(argc, argv);
  const int status = rad::cli::runCli(std::vector<std::string>(argv + 1, argv + argc));
  rad::cli::MpiProcesses::finish(status);
  return status;
}
