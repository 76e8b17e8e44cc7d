// Runs the splinecal binary in a child process and captures its exit code, stdout and stderr:
// the command-line tests drive the tool exactly as a user does.
#ifndef SPLINECAL_TESTS_TESTING_RUN_TOOL_H_
#define SPLINECAL_TESTS_TESTING_RUN_TOOL_H_

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
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
  command += " </dev/null >" + ShellQuote(capture.File("out")) + " 2>" +
             ShellQuote(capture.File("err"));
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

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_RUN_TOOL_H_
