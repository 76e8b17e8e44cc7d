// The command-line rules of docs/conventions.md, checked on the real binary.
#include <gflags/gflags.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "testing/run_tool.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::RefusedInOneLine;
using testing::RunTool;
using testing::TempDir;

TEST(FrontEnd, VersionAndHelpSucceed) {
  EXPECT_EQ(RunTool({"version"}).exit_code, 0);
  EXPECT_THAT(RunTool({"--version"}).out, HasSubstr("splinecal "));
  const auto help = RunTool({"help"});
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("usage: splinecal COMMAND"));
}

TEST(FrontEnd, NoCommandIsBadInput) {
  const auto result = RunTool({});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("usage"));
}

TEST(FrontEnd, UnknownCommandIsOneLineAndExitTwo) {
  const auto result = RunTool({"frobnicate", "--x=1"});
  EXPECT_TRUE(RefusedInOneLine(result, "unknown command 'frobnicate'"));
  EXPECT_EQ(RunTool({"help", "frobnicate"}).exit_code, 2);
}

const cli::Command& FindCommand(const std::string& name) {
  for (const cli::Command& command : cli::AllCommands()) {
    if (command.name == name) return command;
  }
  ADD_FAILURE() << "no command " << name;
  return cli::AllCommands().front();
}

// The gflags name of a flag as the usage line spells it (--imu-rate -> imu_rate).
std::string Underscored(std::string name) {
  for (char& c : name) {
    if (c == '-') c = '_';
  }
  return name;
}

// Each usage line names exactly the flags its --help documents. --quiet, taken by every command
// (cli/command.h), is in neither.
TEST(FrontEnd, UsageLineListsExactlyTheDocumentedFlags) {
  const std::regex flag_pattern("--([A-Za-z0-9_-]+)");
  for (const cli::Command& command : cli::AllCommands()) {
    std::set<std::string> in_usage;
    for (auto it = std::sregex_iterator(command.usage.begin(), command.usage.end(), flag_pattern);
         it != std::sregex_iterator();
         ++it) {
      in_usage.insert(Underscored((*it)[1].str()));
    }
    std::set<std::string> documented;
    for (const cli::FlagDoc& flag : command.flags) {
      if (flag.name != "quiet") documented.insert(flag.name);
    }
    for (const std::string& name : documented) {
      EXPECT_EQ(in_usage.count(name), 1u)
          << command.name << ": --" << name << " is documented but not in the usage line";
    }
    for (const std::string& name : in_usage) {
      EXPECT_EQ(documented.count(name), 1u)
          << command.name << ": --" << name << " is in the usage line but not documented";
    }
  }
}

// The value of --`flag` (read by `value`) after `command` parsed no arguments, i.e. that
// command's default; the flags are restored afterwards.
template <typename Value>
auto DefaultOf(const std::string& command, const char* flag, Value value) {
  gflags::FlagSaver restore_flags_afterwards;
  bool help = false;
  std::string error;
  EXPECT_TRUE(cli::ParseFlags(FindCommand(command), {}, &help, &error)) << error;
  EXPECT_TRUE(gflags::GetCommandLineFlagInfoOrDie(flag).is_default) << flag;
  return value();
}

// A shared flag keeps its meaning; only its default is the command's.
TEST(FrontEnd, KnotSpacingDefaultIsPerCommand) {
  const auto parsed_knot_spacing = [](const std::string& command) {
    return DefaultOf(command, "knot_spacing", [] { return FLAGS_knot_spacing; });
  };
  EXPECT_EQ(parsed_knot_spacing("fit"), 0.0);  // chosen from the IMU data
  EXPECT_EQ(parsed_knot_spacing("calibrate"), 0.05);
  EXPECT_EQ(parsed_knot_spacing("simulate"), 0.05);
  EXPECT_EQ(parsed_knot_spacing("fit"), 0.0);  // not left at the previous command's default

  EXPECT_THAT(RunTool({"calibrate", "--help"}).out,
              HasSubstr("0 chooses it from the IMU data (default: 0.05)"));
  EXPECT_THAT(RunTool({"fit", "--help"}).out,
              HasSubstr("0 chooses it from the IMU data (default: 0)"));
}

TEST(FrontEnd, SimulateRefusesKnotSpacingZero) {
  TempDir dir;
  const auto result = RunTool({"simulate", "--knot-spacing", "0", "--out", dir.File("sim")});
  EXPECT_TRUE(
      RefusedInOneLine(result, "--knot-spacing: 0 (chosen from the IMU data) needs IMU data"));
}

// --trajectory is simulate's motion and fit's and calibrate's spline model: each command's own
// default, and a model other than se3 or split is bad input (exit 2, one line naming the flag),
// refused before any file is read.
TEST(FrontEnd, TrajectoryIsPerCommandAndAnUnknownModelIsRefused) {
  const auto parsed_trajectory = [](const std::string& command) {
    return DefaultOf(command, "trajectory", [] { return FLAGS_trajectory; });
  };
  EXPECT_EQ(parsed_trajectory("fit"), "se3");
  EXPECT_EQ(parsed_trajectory("calibrate"), "se3");
  EXPECT_EQ(parsed_trajectory("simulate"), "vio_course");
  EXPECT_EQ(parsed_trajectory("fit"), "se3");  // not left at simulate's default

  TempDir dir;
  const std::vector<std::vector<std::string>> commands = {
      {"fit", "--imu", dir.File("imu.csv"), "--poses", dir.File("poses.csv")},
      {"calibrate",
       "--imu",
       dir.File("imu.csv"),
       "--observations",
       dir.File("observations.csv"),
       "--camchain",
       dir.File("camchain.yaml"),
       "--target",
       dir.File("target.yaml")}};
  for (std::vector<std::string> args : commands) {
    for (const std::string flag : {"--trajectory", "--out"}) {
      args.push_back(flag);
      args.push_back(flag == "--out" ? dir.File("out") : "vio_course");
    }
    const auto result = RunTool(args);
    EXPECT_TRUE(RefusedInOneLine(
        result, "splinecal " + args[0] + ": --trajectory: expected se3 or split, got 'vio_course'"))
        << args[0];
  }
}

}  // namespace
}  // namespace splinecal
