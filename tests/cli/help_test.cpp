// Each command's --help lists the settings its methods read and no others, and an on/off flag
// shows its default once, as its help says it.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "cli/cli_run.h"

namespace rad {
namespace {

using test::run;

std::string helpOf(const std::string& command) {
  const test::CliResult r = run({command, "--help"});
  EXPECT_EQ(r.status, 0) << r.err;
  return r.out;
}

// Whether a line of the help starts with the option (its name column, not another's text).
bool lists(const std::string& help, const std::string& flag) {
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    line.erase(0, line.find_first_not_of(' '));
    if (line.starts_with(flag + " ") || line.starts_with(flag + ",") || line == flag) return true;
  }
  return false;
}

void expectListed(const std::string& help, const std::vector<std::string>& flags, bool listed) {
  for (const std::string& flag : flags)
    EXPECT_EQ(lists(help, flag), listed)
        << flag << (listed ? " missing from" : " listed in") << "\n"
        << help;
}

TEST(Help, EachCommandListsTheSettingsItReads) {
  const std::string render = helpOf("render"), solve = helpOf("solve"), serve = helpOf("serve"),
                    animate = helpOf("animate");
  expectListed(render,
               {"--method", "--spp", "--max-depth", "--voxels", "--patches", "--group",
                "--light-groups", "--tolerance"},
               true);
  // solve and serve draw no pictures and run no path tracer.
  expectListed(
      solve,
      {"--method", "--voxels", "--patches", "--seed", "--group", "--light-groups", "--shading"},
      true);
  expectListed(solve, {"--spp", "--max-depth"}, false);
  expectListed(serve, {"--method", "--voxels", "--patches", "--tolerance"}, true);
  expectListed(serve, {"--spp", "--max-depth", "--group", "--light-groups"}, false);
  // animate relights the patch method only, its groups scaled in the lights.
  expectListed(animate, {"--spp", "--patches", "--group", "--shading"}, true);
  expectListed(animate,
               {"--method", "--max-depth", "--voxels", "--sphere-radius", "--light-groups"}, false);
}

TEST(Help, AnOnOffFlagShowsItsDefaultOnce) {
  for (const std::string command : {"render", "solve", "serve", "animate"}) {
    const std::string help = helpOf(command);
    EXPECT_EQ(help.find("{false}"), std::string::npos) << command << "\n" << help;
    EXPECT_EQ(help.find("{true}"), std::string::npos) << command << "\n" << help;
  }
  const std::string solve = helpOf("solve");
  const size_t normalize = solve.find("--normalize,--no-normalize");
  ASSERT_NE(normalize, std::string::npos) << solve;
  const std::string line = solve.substr(normalize, solve.find('\n', normalize) - normalize);
  EXPECT_NE(line.find("(default true)"), std::string::npos) << line;
  const size_t groups = solve.find("--light-groups,--no-light-groups");
  ASSERT_NE(groups, std::string::npos) << solve;
  EXPECT_NE(solve.find("(default false)", groups), std::string::npos);
}

TEST(Help, ASettingTheCommandDoesNotReadIsAnError) {
  const test::CliResult spp = run({"solve", "cornell", "--spp", "4"});
  EXPECT_EQ(spp.status, 2);
  EXPECT_NE(spp.err.find("--spp"), std::string::npos) << spp.err;
  EXPECT_EQ(run({"serve", "cornell", "--group", "light=0.5"}).status, 2);
}

}  // namespace
}  // namespace rad
