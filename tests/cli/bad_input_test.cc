// Every class of bad input against every command that reads it (docs/reliability.md): exit code
// 2, exactly one line on stderr naming the file (and the line where there is one), and no result
// written. Each row of the reliability table is one instance of this parametrised test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <map>
#include <sstream>

#include "cli/bad_input_classes.h"
#include "testing/run_tool.h"

namespace splinecal {
namespace {

using testing::BadClass;
using testing::BadClasses;
using testing::FileRole;
using ::testing::HasSubstr;
using testing::kColumnsFile;
using testing::kImuFile;
using testing::kObservationsFile;
using testing::kTableFile;
using testing::kYamlFile;
using testing::Lines;
using testing::RefusedInOneLine;
using testing::RunTool;
using testing::TempDir;
using testing::ValidCamchain;
using testing::ValidColumns;
using testing::ValidGroundTruth;
using testing::ValidImu;
using testing::ValidImuYaml;
using testing::ValidObservations;
using testing::ValidSpline;
using testing::ValidTarget;
using testing::YamlKeyLine;

struct CommandCase {
  std::string name;
  std::vector<std::string> extra_args;  // besides the files and --out
  std::vector<FileRole> roles;
  bool unwritable_output_row = true;  // one per command
};

const std::vector<CommandCase>& CommandCases() {
  const FileRole imu = {"--imu", ValidImu, kImuFile};
  const FileRole imu_yaml = {"--imu-yaml", ValidImuYaml, kYamlFile, {}, "gyroscope_noise_density"};
  const FileRole camchain = {"--camchain", ValidCamchain, kYamlFile, {}, "intrinsics", true};
  const FileRole target = {"--target", ValidTarget, kYamlFile, {}, "tagSize"};
  const std::map<std::string, std::string> observations_instead = {
      {"EmptyFile", "no observations"},
      {"HeaderOnly", "no observations"},
      {"TimestampsEqual", ":5: point 2 of camera 0 appears twice"}};
  static const std::vector<CommandCase> cases = {
      {"evaluate",
       {},
       {{"--spline",
         ValidSpline,
         kTableFile,
         {1, 2, 3},
         "",
         false,
         {{"TimestampsEqual", ":5:1: knot spacing is not uniform"},
          {"TimestampsBackwards", ":5:1: knot spacing is not uniform"}}}}},
      {"simulate", {}, {{"--trajectory-file", ValidGroundTruth}, imu_yaml, camchain, target}},
      {"integrate", {}, {imu, {"--groundtruth", ValidGroundTruth}}},
      {"allan", {}, {imu}},
      {"allan",
       {"--rate", "200"},
       {{"--columns", ValidColumns, kColumnsFile, {0, 1, 2}}},
       /*unwritable_output_row=*/false},
      {"fit", {}, {imu, {"--poses", ValidGroundTruth}, imu_yaml}},
      // align reads only cam0's extrinsics from the camchain, each key optional.
      {"align",
       {},
       {imu,
        {"--camera-poses", ValidGroundTruth},
        imu_yaml,
        {"--camchain", ValidCamchain, kYamlFile, {}, "timeshift_cam_imu", false, {}, true}}},
      {"calibrate",
       {},
       {imu,
        {"--observations",
         ValidObservations,
         kObservationsFile,
         {3, 4, 3},
         "",
         false,
         observations_instead},
        camchain,
        target,
        imu_yaml,
        {"--initial-poses", ValidGroundTruth}}},
  };
  return cases;
}

struct Row {
  const CommandCase* command;
  const FileRole* role;
  const BadClass* bad;  // nullptr: missing file / directory handled by name
  std::string special;  // "MissingFile", "Directory", "UnwritableOutput"
};

std::vector<Row> AllRows() {
  std::vector<Row> rows;
  for (const CommandCase& command : CommandCases()) {
    for (const FileRole& role : command.roles) {
      for (const BadClass& bad : BadClasses()) {
        if ((bad.kinds & role.kind) == 0) continue;
        if (role.yaml_key_optional && bad.name == "MissingKey") continue;
        rows.push_back({&command, &role, &bad, ""});
      }
      rows.push_back({&command, &role, nullptr, "MissingFile"});
      rows.push_back({&command, &role, nullptr, "Directory"});
    }
    if (command.unwritable_output_row) {
      rows.push_back({&command, nullptr, nullptr, "UnwritableOutput"});
    }
  }
  return rows;
}

std::string RowName(const ::testing::TestParamInfo<Row>& info) {
  const Row& row = info.param;
  std::string name = row.command->name + "_";
  if (row.role != nullptr) name += row.role->flag.substr(2) + "_";
  name += row.bad != nullptr ? row.bad->name : row.special;
  for (char& c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  }
  return name;
}

// gtest prints a failing row by its name rather than as bytes.
void PrintTo(const Row& row, std::ostream* out) {
  *out << RowName(::testing::TestParamInfo<Row>(row, 0));
}

class BadInput : public ::testing::TestWithParam<Row> {};

TEST_P(BadInput, ExitsTwoWithOneLineAndWritesNothing) {
  const Row& row = GetParam();
  TempDir dir;
  std::vector<std::string> args = {row.command->name};
  std::string bad_path;
  for (const FileRole& role : row.command->roles) {
    const std::string name = role.flag.substr(2) + ".input";
    std::string path = dir.Write(name, role.valid());
    if (&role == row.role) {
      if (row.bad != nullptr) {
        path = dir.Write(name, row.bad->make(role.valid(), role));
      } else if (row.special == "MissingFile") {
        path = dir.File("missing-" + name);
      } else if (row.special == "Directory") {
        path = dir.path();
      }
      bad_path = path;
    }
    args.push_back(role.flag);
    args.push_back(path);
  }
  args.insert(args.end(), row.command->extra_args.begin(), row.command->extra_args.end());
  std::string out = dir.File("out");
  if (row.special == "UnwritableOutput") out = dir.Write("a-file", "x") + "/out";
  args.push_back("--out");
  args.push_back(out);
  args.push_back("--quiet");

  const auto result = RunTool(args);
  EXPECT_TRUE(RefusedInOneLine(result, "splinecal " + row.command->name + ": "));
  if (!bad_path.empty()) {
    EXPECT_THAT(result.err, HasSubstr(bad_path));
  }
  if (row.bad != nullptr) {
    const auto instead = row.role->expect_instead.find(row.bad->name);
    EXPECT_THAT(
        result.err,
        HasSubstr(instead != row.role->expect_instead.end() ? instead->second : row.bad->expect));
    if (row.bad->at_key_line) {
      const int line = YamlKeyLine(Lines(row.role->valid()), row.role->yaml_key) + 1;
      EXPECT_THAT(result.err, HasSubstr(bad_path + ":" + std::to_string(line) + ": "));
    }
  }
  if (row.special == "UnwritableOutput") {
    EXPECT_THAT(result.err, HasSubstr("a-file"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/result.yaml")));
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, BadInput, ::testing::ValuesIn(AllRows()), RowName);

}  // namespace
}  // namespace splinecal
