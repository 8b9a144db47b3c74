#include "cli.h"

#include <iostream>

namespace rad::cli {

int runCli(const std::vector<std::string>& args) { return runCli(args, std::cout, std::cerr); }

int runCli(const std::vector<std::string>&, std::ostream&, std::ostream& err) {
  err << "radiosity: not built yet\n";
  return 1;
}

}  // namespace rad::cli
