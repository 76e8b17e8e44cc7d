// Every class of bad input against every command that reads it (docs/reliability.md): exit code
// 2, exactly one line on stderr naming the file (and the line where there is one), and no result
// written. Each row of the reliability table is one instance of this parametrised test.
#include <filesystem>
#include <functional>
#include <map>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "testing/run_tool.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::CountLines;
using testing::RunTool;
using testing::TempDir;

// ---- Valid inputs of each kind (small, well-formed) ----

std::string ValidImu() {
  std::string text =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  for (int i = 0; i < 400; ++i) {
    text += std::to_string(1403715273262142976LL + i * 5000000LL) + "," +
            std::to_string(0.01 * std::sin(0.05 * i)) + ",0.02,-0.01,0.1," +
            std::to_string(0.2 * std::cos(0.03 * i)) + ",9.81\n";
  }
  return text;
}

std::string ValidGroundTruth() {
  std::string text = "#time(ns),px,py,pz,qw,qx,qy,qz,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz\n";
  for (int i = 0; i < 40; ++i) {
    text += std::to_string(1403715273262142976LL + i * 50000000LL) + "," +
            std::to_string(0.01 * i) + ",0,1,1,0,0,0,0.2,0,0,0,0,0,0,0,0\n";
  }
  return text;
}

std::string ValidSpline() {
  std::string text = "#t_ns,px,py,pz,qw,qx,qy,qz\n";
  for (int i = 0; i < 12; ++i) {
    text += std::to_string(1403715273262142976LL + i * 50000000LL) + "," +
            std::to_string(0.1 * i) + ",0,1,1,0,0,0\n";
  }
  return text;
}

// ---- Bad variants: a transformation of the valid text (line-based) ----

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) lines.push_back(line);
  return lines;
}

std::string Join(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Replaces the k-th comma-separated field of data line `row` (0 = header).
std::string ReplaceField(const std::string& text, int row, int k, const std::string& value) {
  auto lines = Lines(text);
  std::vector<std::string> fields;
  std::stringstream stream(lines[row]);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  fields[k] = value;
  std::string joined;
  for (size_t i = 0; i < fields.size(); ++i) joined += (i ? "," : "") + fields[i];
  lines[row] = joined;
  return Join(lines);
}

struct BadClass {
  std::string name;
  // Returns the bad text; `expect` is a substring the error line must contain (besides the file).
  std::function<std::string(const std::string& valid)> make;
  std::string expect;
  bool applies_to_imu_only = false;
};

const std::vector<BadClass>& BadClasses() {
  static const std::vector<BadClass> classes = {
      {"EmptyFile", [](const std::string&) { return std::string(); }, "at least"},
      {"HeaderOnly", [](const std::string& v) { return Lines(v)[0] + "\n"; }, "at least"},
      {"WrongColumnCount",
       [](const std::string& v) {
         auto lines = Lines(v);
         lines[3] = lines[3].substr(0, lines[3].rfind(','));
         return Join(lines);
       },
       ":4: expected"},
      {"NonNumericField", [](const std::string& v) { return ReplaceField(v, 3, 2, "abc"); },
       ":4:"},
      {"NaN", [](const std::string& v) { return ReplaceField(v, 3, 2, "nan"); }, "not a finite"},
      {"Inf", [](const std::string& v) { return ReplaceField(v, 3, 3, "-inf"); }, "not a finite"},
      {"HugeValue", [](const std::string& v) { return ReplaceField(v, 3, 1, "1e300"); },
       "beyond the plausible"},
      {"TimestampsEqual",
       [](const std::string& v) {
         auto lines = Lines(v);
         lines[4] = lines[3];
         return Join(lines);
       },
       ":5:1: timestamps not increasing"},
      {"TimestampsBackwards",
       [](const std::string& v) {
         auto lines = Lines(v);
         std::swap(lines[4], lines[5]);
         return Join(lines);
       },
       ":6:1: timestamps not increasing"},
      {"Gap",
       [](const std::string& v) {
         auto lines = Lines(v);
         // Shift everything after data row 20 by 10 s.
         for (size_t i = 21; i < lines.size(); ++i) {
           const size_t comma = lines[i].find(',');
           lines[i] = std::to_string(std::stoll(lines[i].substr(0, comma)) + 10000000000LL) +
                      lines[i].substr(comma);
         }
         return Join(lines);
       },
       ":22: gap of", true},
      {"AccelerometerInG",
       [](const std::string& v) {
         auto lines = Lines(v);
         for (size_t i = 1; i < lines.size(); ++i) {
           lines[i] = lines[i].substr(0, lines[i].rfind(',')) + ",1.0";
           const size_t a_y = lines[i].rfind(',', lines[i].rfind(',') - 1);
           lines[i] = lines[i].substr(0, a_y) + ",0.01,1.0";
         }
         return Join(lines);
       },
       "units of g", true},
  };
  return classes;
}

// ---- Commands and the file roles they read ----

struct FileRole {
  std::string flag;                       // e.g. "--imu"
  std::function<std::string()> valid;     // valid content
  bool is_imu = false;
  // Where a format diagnoses a class more precisely than the generic expectation (a spline.csv
  // reports a repeated or swapped knot as non-uniform spacing), the substring to expect instead.
  std::map<std::string, std::string> expect_instead = {};
};

struct CommandCase {
  std::string name;
  std::vector<std::string> extra_args;    // besides the files and --out
  std::vector<FileRole> roles;
};

const std::vector<CommandCase>& CommandCases() {
  static const std::vector<CommandCase> cases = {
      {"evaluate",
       {},
       {{"--spline",
         ValidSpline,
         false,
         {{"TimestampsEqual", ":5:1: knot spacing is not uniform"},
          {"TimestampsBackwards", ":5:1: knot spacing is not uniform"}}}}},
      {"simulate", {}, {{"--trajectory-file", ValidGroundTruth}}},
      {"integrate", {}, {{"--imu", ValidImu, true}, {"--groundtruth", ValidGroundTruth}}},
      {"allan", {}, {{"--imu", ValidImu, true}}},
      {"fit", {}, {{"--imu", ValidImu, true}, {"--poses", ValidGroundTruth}}},
      {"align", {}, {{"--imu", ValidImu, true}, {"--camera-poses", ValidGroundTruth}}},
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
        if (bad.applies_to_imu_only && !role.is_imu) continue;
        rows.push_back({&command, &role, &bad, ""});
      }
      rows.push_back({&command, &role, nullptr, "MissingFile"});
      rows.push_back({&command, &role, nullptr, "Directory"});
    }
    rows.push_back({&command, nullptr, nullptr, "UnwritableOutput"});
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
        path = dir.Write(name, row.bad->make(role.valid()));
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
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(CountLines(result.err), 1) << result.err;
  EXPECT_THAT(result.err, HasSubstr("splinecal " + row.command->name + ": "));
  if (!bad_path.empty()) EXPECT_THAT(result.err, HasSubstr(bad_path));
  if (row.bad != nullptr) {
    const auto instead = row.role->expect_instead.find(row.bad->name);
    EXPECT_THAT(result.err, HasSubstr(instead != row.role->expect_instead.end() ? instead->second
                                                                                 : row.bad->expect));
  }
  if (row.special == "UnwritableOutput") EXPECT_THAT(result.err, HasSubstr("a-file"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("out/result.yaml")));
}

INSTANTIATE_TEST_SUITE_P(EveryCommand, BadInput, ::testing::ValuesIn(AllRows()), RowName);

}  // namespace
}  // namespace splinecal
