// The classes of bad input of docs/reliability.md, each a transformation of a small valid file,
// and the valid files of every kind (tests/cli/bad_input_test.cc runs them against every
// command).
#ifndef SPLINECAL_TESTS_CLI_BAD_INPUT_CLASSES_H_
#define SPLINECAL_TESTS_CLI_BAD_INPUT_CLASSES_H_

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

// ---- Valid inputs of each kind (small, well-formed) ----

inline std::string ValidImu() {
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

inline std::string ValidGroundTruth() {
  std::string text = "#time(ns),px,py,pz,qw,qx,qy,qz,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz\n";
  for (int i = 0; i < 40; ++i) {
    text += std::to_string(1403715273262142976LL + i * 50000000LL) + "," +
            std::to_string(0.01 * i) + ",0,1,1,0,0,0,0.2,0,0,0,0,0,0,0,0\n";
  }
  return text;
}

inline std::string ValidSpline() {
  std::string text = "#t_ns,px,py,pz,qw,qx,qy,qz\n";
  for (int i = 0; i < 12; ++i) {
    text += std::to_string(1403715273262142976LL + i * 50000000LL) + "," + std::to_string(0.1 * i) +
            ",0,1,1,0,0,0\n";
  }
  return text;
}

// Ten frames of cam0 at 20 Hz, each with eight points of the target.
inline std::string ValidObservations() {
  std::string text = "#t_ns,cam_id,point_id,u,v\n";
  for (int frame = 0; frame < 10; ++frame) {
    for (int point = 0; point < 8; ++point) {
      text += std::to_string(1403715273262142976LL + frame * 50000000LL) + ",0," +
              std::to_string(point) + "," + std::to_string(300.0 + 20 * point + frame) + "," +
              std::to_string(200.0 + 10 * point) + "\n";
    }
  }
  return text;
}

// allan's plain columns: gyro xyz, accel xyz of a resting IMU, no timestamps.
inline std::string ValidColumns() {
  std::string text = "# gyro x,y,z [rad/s], accel x,y,z [m/s^2]\n";
  for (int i = 0; i < 400; ++i) {
    text += std::to_string(1e-3 * std::sin(0.7 * i)) + ",0.002,-0.001,0.05," +
            std::to_string(0.02 * std::cos(0.3 * i)) + ",9.81\n";
  }
  return text;
}

// The bundled YAML files (data/): a camchain, an aprilgrid and EuRoC's sensor.yaml.
inline std::string DataText(const std::string& relative_path) {
  return ReadFileText(testing::SourceDir() + "/data/" + relative_path);
}
inline std::string ValidCamchain() { return DataText("calibration/camchain_guess.yaml"); }
inline std::string ValidTarget() { return DataText("calibration/aprilgrid.yaml"); }
inline std::string ValidImuYaml() { return DataText("euroc_v1_01_easy_20s/sensor.yaml"); }

// ---- Editing helpers (line-based) ----

inline std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) lines.push_back(line);
  return lines;
}

inline std::string Join(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

// Replaces the k-th comma-separated field of data line `row` (0 = header).
inline std::string ReplaceField(const std::string& text, int row, int k, const std::string& value) {
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

// The index of the line holding `key:` (after indentation); -1 when there is none.
inline int YamlKeyLine(const std::vector<std::string>& lines, const std::string& key) {
  for (size_t i = 0; i < lines.size(); ++i) {
    const size_t start = lines[i].find_first_not_of(' ');
    if (start != std::string::npos && lines[i].compare(start, key.size() + 1, key + ":") == 0) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

// Replaces the line of `key` by `key: value` (value empty: removes the line; new_key: renames).
inline std::string EditYamlKey(const std::string& text,
                               const std::string& key,
                               const std::string& value,
                               const std::string& new_key = "") {
  auto lines = Lines(text);
  const int at = YamlKeyLine(lines, key);
  const std::string indent = lines[at].substr(0, lines[at].find_first_not_of(' '));
  if (value.empty()) {
    lines.erase(lines.begin() + at);
  } else {
    lines[at] = indent + (new_key.empty() ? key : new_key) + ": " + value;
  }
  return Join(lines);
}

// ---- The classes ----

// Which classes apply to a file.
enum FileKind : unsigned {
  kImuFile = 1,           // EuRoC IMU: every table class, gaps and units of g too
  kTableFile = 2,         // time-stamped rows (poses, ground truth, spline)
  kObservationsFile = 4,  // observations.csv: rows per point, not ordered in time
  kYamlFile = 8,
  kColumnsFile = 16,  // allan's plain columns: no timestamps, but units of g
};

struct FileRole {
  std::string flag;                    // e.g. "--imu"
  std::function<std::string()> valid;  // valid content
  FileKind kind = kTableFile;
  // Table files: the columns that get a non-number, NaN / inf and a huge value.
  std::array<int, 3> number_fields = {1, 2, 3};
  // YAML files: a required numeric key the classes break, and whether its value is a list.
  std::string yaml_key = "";
  bool yaml_list = false;
  // Where a format diagnoses a class more precisely than the generic expectation (a spline.csv
  // reports a repeated or swapped knot as non-uniform spacing), the substring to expect instead.
  std::map<std::string, std::string> expect_instead = {};
  // YAML files whose yaml_key may be left out (align's camchain): no "missing key" row.
  bool yaml_key_optional = false;
};

struct BadClass {
  std::string name;
  unsigned kinds;  // FileKind bits
  // Returns the bad text from the valid one.
  std::function<std::string(const std::string& valid, const FileRole& role)> make;
  // A substring the error line must contain (besides the file).
  std::string expect;
  // YAML classes whose error names the line of the broken key.
  bool at_key_line = false;
};

// A YAML value for the role's key: `item` alone, or as the second of four numbers of a list.
inline std::string YamlValue(const FileRole& role, const std::string& item) {
  return role.yaml_list ? "[458.654, " + item + ", 367.215, 248.375]" : item;
}

// A table class: `value` in the role's number_fields[which] of the fourth line.
inline BadClass FieldClass(const std::string& name,
                           int which,
                           const std::string& value,
                           const std::string& expect) {
  return {name,
          kImuFile | kTableFile | kObservationsFile | kColumnsFile,
          [which, value](const std::string& v, const FileRole& r) {
            return ReplaceField(v, 3, r.number_fields[which], value);
          },
          expect};
}

// A YAML class: the role's key set to `item` (in a list for list keys).
inline BadClass YamlValueClass(const std::string& name,
                               const std::string& item,
                               const std::string& expect) {
  return {name,
          kYamlFile,
          [item](const std::string& v, const FileRole& r) {
            return EditYamlKey(v, r.yaml_key, YamlValue(r, item));
          },
          expect,
          true};
}

inline const std::vector<BadClass>& BadClasses() {
  constexpr unsigned kCsv = kImuFile | kTableFile | kObservationsFile | kColumnsFile;
  constexpr unsigned kTimeSeries = kImuFile | kTableFile;
  using Role = const FileRole&;
  static const std::vector<BadClass> classes = {
      // Tables.
      {"EmptyFile", kCsv, [](const std::string&, Role) { return std::string(); }, "at least"},
      {"HeaderOnly",
       kCsv,
       [](const std::string& v, Role) { return Lines(v)[0] + "\n"; },
       "at least"},
      {"WrongColumnCount",
       kCsv,
       [](const std::string& v, Role) {
         auto lines = Lines(v);
         lines[3] = lines[3].substr(0, lines[3].rfind(','));
         return Join(lines);
       },
       ":4: expected"},
      FieldClass("NonNumericField", 1, "abc", ":4:"),
      FieldClass("NaN", 1, "nan", "not a finite"),
      FieldClass("Inf", 2, "-inf", "not a finite"),
      FieldClass("HugeValue", 0, "1e300", "beyond the plausible"),
      // In observations.csv a repeated row is the same point twice in one frame.
      {"TimestampsEqual",
       kTimeSeries | kObservationsFile,
       [](const std::string& v, Role) {
         auto lines = Lines(v);
         lines[4] = lines[3];
         return Join(lines);
       },
       ":5:1: timestamps not increasing"},
      {"TimestampsBackwards",
       kTimeSeries,
       [](const std::string& v, Role) {
         auto lines = Lines(v);
         std::swap(lines[4], lines[5]);
         return Join(lines);
       },
       ":6:1: timestamps not increasing"},
      {"Gap",
       kImuFile,
       [](const std::string& v, Role) {
         auto lines = Lines(v);
         // Shift everything after data row 20 by 10 s.
         for (size_t i = 21; i < lines.size(); ++i) {
           const size_t comma = lines[i].find(',');
           lines[i] = std::to_string(std::stoll(lines[i].substr(0, comma)) + 10000000000LL) +
                      lines[i].substr(comma);
         }
         return Join(lines);
       },
       ":22: gap of"},
      {"AccelerometerInG",
       kImuFile | kColumnsFile,
       [](const std::string& v, Role) {
         auto lines = Lines(v);
         for (size_t i = 1; i < lines.size(); ++i) {
           lines[i] = lines[i].substr(0, lines[i].rfind(',')) + ",1.0";
           const size_t a_y = lines[i].rfind(',', lines[i].rfind(',') - 1);
           lines[i] = lines[i].substr(0, a_y) + ",0.01,1.0";
         }
         return Join(lines);
       },
       "units of g"},
      // Observations: a negative id, a camera the camchain lacks.
      {"NegativeId",
       kObservationsFile,
       [](const std::string& v, Role) { return ReplaceField(v, 3, 2, "-1"); },
       ":4:23: point_id must be >= 0"},
      {"UnknownCamera",
       kObservationsFile,
       [](const std::string& v, Role) { return ReplaceField(v, 3, 1, "1"); },
       "cam_id 1 (frame t_ns 1403715273262142976) has no camera in"},
      // YAML.
      {"EmptyFile",
       kYamlFile,
       [](const std::string&, Role) { return std::string(); },
       "expected a YAML map"},
      {"SyntaxError",
       kYamlFile,
       [](const std::string& v, Role r) { return EditYamlKey(v, r.yaml_key, "[1, 2"); },
       "invalid YAML"},
      {"MissingKey",
       kYamlFile,
       [](const std::string& v, Role r) { return EditYamlKey(v, r.yaml_key, ""); },
       "missing key"},
      {"TypoKey",
       kYamlFile,
       [](const std::string& v, Role r) {
         const std::string value = Lines(v)[YamlKeyLine(Lines(v), r.yaml_key)];
         return EditYamlKey(v,
                            r.yaml_key,
                            value.substr(value.find(':') + 2),
                            r.yaml_key.substr(0, r.yaml_key.size() - 1));
       },
       "did you mean",
       true},
      {"WrongType",
       kYamlFile,
       [](const std::string& v, Role r) {
         return EditYamlKey(v, r.yaml_key, r.yaml_list ? "458.654" : "[1, 2]");
       },
       "must be a",
       true},
      YamlValueClass("NonNumericField", "abc", "must be a number, got 'abc'"),
      YamlValueClass("NaN", ".nan", "is not finite"),
      YamlValueClass("Inf", "-.inf", "is not finite"),
      YamlValueClass("HugeValue", "1e300", "beyond the plausible"),
  };
  return classes;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CLI_BAD_INPUT_CLASSES_H_
