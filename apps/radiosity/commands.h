#pragma once
// One function per subcommand: each adds its options to the CLI11 app and returns the action
// that runs it once the command line has been parsed (exit status as the return value).

#include <functional>

#include "console.h"

namespace CLI {
class App;
}

namespace rad::cli {

using CommandAction = std::function<int()>;

void addRenderCommand(CLI::App& app, Console& console, CommandAction& action);
void addSolveCommand(CLI::App& app, Console& console, CommandAction& action);
void addAnimateCommand(CLI::App& app, Console& console, CommandAction& action);
void addServeCommand(CLI::App& app, Console& console, CommandAction& action);
void addInfoCommand(CLI::App& app, Console& console, CommandAction& action);
void addBenchCommand(CLI::App& app, Console& console, CommandAction& action);

}  // namespace rad::cli
