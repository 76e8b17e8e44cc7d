// Every file of the fuzz seed corpora and every input a fuzzer once found (tests/fuzz/) goes
// through every reader and through every command's input stage: each must return or throw
// splinecal::Error, nothing else. Each seed must also be accepted by what its own target fuzzes,
// so that the fuzzers start from valid inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz/command_inputs.h"
#include "fuzz/readers.h"
#include "splinecal/cli/command.h"
#include "splinecal/error.h"
#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

namespace fs = std::filesystem;

struct CorpusFile {
  std::string path;
  std::string target;  // the seed's fuzz target; empty for a kept finding (regressions/)
};

std::vector<CorpusFile> CorpusFiles() {
  std::vector<CorpusFile> files;
  const fs::path root = fs::path(testing::SourceDir()) / "tests" / "fuzz";
  for (const char* sub : {"corpus", "regressions"}) {
    if (!fs::exists(root / sub)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / sub)) {
      if (!entry.is_regular_file() || entry.path().filename() == ".keep") continue;
      const bool seed = std::string(sub) == "corpus";
      files.push_back(
          {entry.path().string(), seed ? entry.path().parent_path().filename().string() : ""});
    }
  }
  std::sort(files.begin(), files.end(), [](const CorpusFile& a, const CorpusFile& b) {
    return a.path < b.path;
  });
  return files;
}

TEST(FuzzCorpus, EveryReaderReturnsOrThrowsError) {
  const auto files = CorpusFiles();
  ASSERT_FALSE(files.empty());
  for (const CorpusFile& file : files) {
    for (const fuzz::Reader& reader : fuzz::Readers()) {
      const bool own_seed = file.target == std::string(reader.name) + "_fuzz";
      try {
        reader.read(file.path);
      } catch (const Error& e) {
        if (own_seed)
          ADD_FAILURE() << file.path << ": a seed of " << reader.name << ": " << e.what();
      } catch (const std::exception& e) {
        ADD_FAILURE() << file.path << ": " << reader.name << " threw " << e.what();
      }
    }
  }
}

TEST(FuzzCorpus, EveryCommandInputStageReturnsOrThrowsError) {
  const auto files = CorpusFiles();
  ASSERT_FALSE(files.empty());
  for (const CorpusFile& file : files) {
    const std::string bundle = testing::ReadFileText(file.path);
    for (const cli::Command& command : cli::AllCommands()) {
      const bool own_seed = file.target == command.name + "_inputs_fuzz";
      try {
        std::string refusal;
        const fuzz::StageOutcome outcome = fuzz::RunCommandInputs(command.name, bundle, &refusal);
        if (own_seed) {
          EXPECT_EQ(outcome, fuzz::StageOutcome::kAccepted)
              << file.path << ": a seed of " << command.name << "'s input stage: " << refusal;
        }
      } catch (const std::exception& e) {
        ADD_FAILURE() << file.path << ": " << command.name << "'s input stage threw " << e.what();
      }
    }
  }
}

}  // namespace
}  // namespace splinecal
