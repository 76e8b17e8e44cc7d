// The command-line rules of docs/conventions.md, checked on the real binary.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "testing/run_tool.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::CountLines;
using testing::RunTool;

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
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(CountLines(result.err), 1);
  EXPECT_THAT(result.err, HasSubstr("unknown command 'frobnicate'"));
  EXPECT_EQ(RunTool({"help", "frobnicate"}).exit_code, 2);
}

}  // namespace
}  // namespace splinecal
