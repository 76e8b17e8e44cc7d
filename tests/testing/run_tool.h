// Runs the splinecal binary in a child process and captures its exit code, stdout and stderr:
// the command-line tests drive the tool exactly as a user does.
#ifndef SPLINECAL_TESTS_TESTING_RUN_TOOL_H_
#define SPLINECAL_TESTS_TESTING_RUN_TOOL_H_

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

struct ToolResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ShellQuote(const std::string& arg) {
  std::string quoted = "'";
  for (char c : arg) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// Runs `splinecal args...` (testing/paths.h) with stdin from /dev/null.
inline ToolResult RunTool(const std::vector<std::string>& args) {
  TempDir capture;
  std::string command = ShellQuote(ToolPath());
  for (const std::string& arg : args) command += " " + ShellQuote(arg);
  command +=
      " </dev/null >" + ShellQuote(capture.File("out")) + " 2>" + ShellQuote(capture.File("err"));
  const int status = std::system(command.c_str());
  ToolResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  result.out = ReadFileText(capture.File("out"));
  result.err = ReadFileText(capture.File("err"));
  return result;
}

// Number of lines in `text` (a trailing newline does not start a line).
inline int CountLines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  if (!text.empty() && text.back() != '\n') ++lines;
  return lines;
}

// Bad input refused as every command promises (docs/conventions.md "Command line"): exit code 2
// and one line on stderr that contains `message` (the file, line and problem).
inline ::testing::AssertionResult RefusedInOneLine(const ToolResult& result,
                                                   const std::string& message) {
  if (result.exit_code == 2 && CountLines(result.err) == 1 &&
      result.err.find(message) != std::string::npos) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure()
         << "expected exit code 2 and one line containing \"" << message << "\"; got exit code "
         << result.exit_code << " and stderr:\n"
         << result.err;
}

// One bad invocation: the flags after the command, and what its one line of error must contain.
struct BadInvocation {
  std::vector<std::string> args;
  std::string message;
};

// Runs `splinecal command_line... case.args...` for every case: each is refused in one line
// (RefusedInOneLine) and leaves no `output_file` behind (nothing half-written).
inline void ExpectEachRefusedWritingNothing(const std::vector<std::string>& command_line,
                                            const std::vector<BadInvocation>& cases,
                                            const std::string& output_file) {
  for (const BadInvocation& c : cases) {
    std::vector<std::string> args = command_line;
    args.insert(args.end(), c.args.begin(), c.args.end());
    EXPECT_TRUE(RefusedInOneLine(RunTool(args), c.message)) << c.message;
    EXPECT_FALSE(std::filesystem::exists(output_file)) << c.message;
  }
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_RUN_TOOL_H_
