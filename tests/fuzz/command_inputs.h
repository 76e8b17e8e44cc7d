// Fuzzing a subcommand's input stage (cli/command.h, Command::read_inputs): the files and flags
// it reads, checked up to where the heavy work would start. One fuzz input is a bundle of the
// command's files, so that the fuzzer mutates all of them and their combinations:
//
//   --start 2 --duration 1          optional: flags, one line before the first file
//   ===== imu                       a file for --imu follows, up to the next "===== " line
//   #timestamp [ns],...
//   ===== groundtruth
//   ...
//
// Each file is written to a temporary path and given to its flag; --out names a folder the input
// stage never creates. Bundles whose flags the command does not accept are skipped. Seeds are in
// tests/fuzz/corpus/<command>_inputs_fuzz/; tests/io/fuzz_corpus_test.cc replays them.
#ifndef SPLINECAL_TESTS_FUZZ_COMMAND_INPUTS_H_
#define SPLINECAL_TESTS_FUZZ_COMMAND_INPUTS_H_

#include <gflags/gflags.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "fuzz_input.h"
#include "splinecal/cli/command.h"
#include "splinecal/error.h"

namespace splinecal {
namespace fuzz {

// The command-line arguments a bundle stands for (file contents written to temporary files).
inline std::vector<std::string> BundleArguments(const std::string& bundle) {
  constexpr char kSeparator[] = "===== ";
  std::vector<std::string> args;
  std::string flags;
  std::string name;  // the flag of the file being collected; empty before the first
  std::string contents;
  int files = 0;
  auto finish_file = [&] {
    if (name.empty()) return;
    const std::string path = TempPath("file" + std::to_string(files++));
    WriteFileOrTrap(path, contents.data(), contents.size());
    args.push_back("--" + name);
    args.push_back(path);
  };
  size_t start = 0;
  while (start < bundle.size()) {
    size_t end = bundle.find('\n', start);
    end = end == std::string::npos ? bundle.size() : end + 1;
    const std::string line = bundle.substr(start, end - start);
    start = end;
    if (line.rfind(kSeparator, 0) == 0) {
      finish_file();
      name = line.substr(sizeof(kSeparator) - 1);
      while (!name.empty() && (name.back() == '\n' || name.back() == '\r')) name.pop_back();
      contents.clear();
      if (name.empty()) name = "-";  // refused by the flag parser below
    } else if (name.empty()) {
      flags += line;
    } else {
      contents += line;
    }
  }
  finish_file();
  std::istringstream words(flags);
  std::vector<std::string> flag_args;
  for (std::string word; words >> word;) flag_args.push_back(word);
  flag_args.insert(flag_args.end(), args.begin(), args.end());
  return flag_args;
}

enum class StageOutcome { kSkipped, kAccepted, kRefused };

// Runs the input stage of `command` on one bundle; `refusal` (may be nullptr) receives the
// message of a refused bundle.
inline StageOutcome RunCommandInputs(const std::string& command,
                                     const std::string& bundle,
                                     std::string* refusal = nullptr) {
  const cli::Command* found = nullptr;
  for (const cli::Command& c : cli::AllCommands()) {
    if (c.name == command) found = &c;
  }
  if (found == nullptr) __builtin_trap();
  // A flag naming a device or a kernel file could read forever: not a finding of ours.
  for (const char* endless : {"/dev/", "/proc/", "/sys/"}) {
    if (bundle.find(endless) != std::string::npos) return StageOutcome::kSkipped;
  }
  gflags::FlagSaver restore_flags_afterwards;
  bool help = false;
  std::string error;
  if (!cli::ParseFlags(*found, BundleArguments(bundle), &help, &error) || help) {
    return StageOutcome::kSkipped;
  }
  gflags::SetCommandLineOption("out", TempPath("out-never-created").c_str());
  gflags::SetCommandLineOption("quiet", "true");
  try {
    found->read_inputs();
  } catch (const Error& e) {
    if (refusal != nullptr) *refusal = e.what();
    return StageOutcome::kRefused;
  }
  return StageOutcome::kAccepted;
}

}  // namespace fuzz
}  // namespace splinecal

// The whole body of a command fuzz target.
#define SPLINECAL_COMMAND_INPUTS_FUZZER(command)                                               \
  extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {                    \
    splinecal::fuzz::RunCommandInputs(command,                                                 \
                                      std::string(reinterpret_cast<const char*>(data), size)); \
    return 0;                                                                                  \
  }

#endif  // SPLINECAL_TESTS_FUZZ_COMMAND_INPUTS_H_
