#include "cli.h"

#include <fmt/format.h>
#include <radiosity/atomic_file.h>
#include <radiosity/error.h>
#include <radiosity/message_text.h>
#include <radiosity/version.h>
#include <tbb/global_control.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "command_support.h"
#include "commands.h"
#include "console.h"
#include "mpi_processes.h"

namespace rad::cli {

namespace {

// CLI11's help, less the value a "--no-" flag sets ("--no-normalize{false}"): beside "(default
// true)" it read as the default.
class HelpFormatter : public CLI::Formatter {
 public:
  std::string make_option_name(const CLI::Option* option, bool positional) const override {
    std::string name = CLI::Formatter::make_option_name(option, positional);
    for (size_t open; (open = name.find('{')) != std::string::npos;)
      name.erase(open, name.find('}', open) - open + 1);
    return name;
  }
};

}  // namespace

int runCli(const std::vector<std::string>& args) {
  return runCli(args, std::cout, std::cerr);
}

int runCli(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  Console console(out, err);
  CLI::App app{"radiosity " RADIOSITY_VERSION " - global illumination by radiosity", "radiosity"};
  app.require_subcommand(1);
  app.fallthrough();
  app.formatter(std::make_shared<HelpFormatter>());  // before the subcommands, which copy it
  app.set_version_flag("--version", "radiosity " RADIOSITY_VERSION " (" RADIOSITY_BUILD_TYPE ")");
  int threads = 0;
  bool quiet = false, verbose = false;
  app.add_option("--threads", threads,
                 "Worker threads (default and 0: all cores; at most the cores)")
      ->check(nonNegativeNumber());
  app.add_flag("-q,--quiet", quiet,
               "Print errors only: no progress, summary or warnings (--stats still records the "
               "warnings)");
  app.add_flag("-v,--verbose", verbose, "Print the banner, timings and details");

  CommandAction action;
  addRenderCommand(app, console, action);
  addSolveCommand(app, console, action);
  addAnimateCommand(app, console, action);
  addServeCommand(app, console, action);
  addInfoCommand(app, console, action);
  addBenchCommand(app, console, action);

  try {
    std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 wants them reversed
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    out << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion&) {
    out << app.version() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    err << "radiosity: " << printableMessage(e.what()) << " (see radiosity --help)\n";
    return 2;
  }

  // In a run split among processes, rank 0 speaks and writes; the others compute their share.
  const bool speaks = MpiProcesses::rank() == 0;
  console.setQuiet(quiet || !speaks);
  console.setVerbose(verbose && speaks);
  console.setWarnings(speaks);
  setWritesFiles(speaks);
  if (MpiProcesses::split())
    console.info(fmt::format("split among {} processes (MPI ranks)", MpiProcesses::count()));
  console.detail("radiosity " RADIOSITY_VERSION " (" RADIOSITY_BUILD_TYPE " build)");
  std::optional<tbb::global_control> threadLimit;
  const int cores = int(std::thread::hardware_concurrency());
  if (cores > 0 && threads > cores) {
    console.warn(fmt::format("--threads {} is more than the {} cores here; using {}", threads,
                             cores, cores));
    threads = cores;
  }
  if (threads > 0)
    threadLimit.emplace(tbb::global_control::max_allowed_parallelism, size_t(threads));
  try {
    const int status = action();
    console.summarizeWarnings();
    return status;
  } catch (const InputError& e) {
    console.finishProgress();
    err << "radiosity: " << e.what() << "\n";
    return 2;
  } catch (const Cancelled& e) {
    console.finishProgress();
    err << "radiosity: interrupted; no output written"
        << (e.howToGoOn().empty() ? "" : "; " + e.howToGoOn()) << "\n";
    return 130;
  } catch (const std::bad_alloc&) {
    // Past the solvers' own estimates (an address-space limit, another process taking memory).
    console.finishProgress();
    err << "radiosity: out of memory; no output written (a coarser solution needs less: a larger "
           "voxel size, fewer voxels or fewer patches)\n";
    return 1;
  } catch (const std::exception& e) {
    console.finishProgress();
    err << "radiosity: error: " << printableMessage(e.what()) << "\n";
    return 1;
  }
}

}  // namespace rad::cli
