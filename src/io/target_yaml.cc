#include "splinecal/io/target_yaml.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Tag and corner counts beyond this per side are refused as implausible (a corrupt file).
constexpr int64_t kMaxGridSide = 10000;
// An AprilGrid's tags are tag36h11's codes 0, 1, 2, ...: the family has 587 of them, so a larger
// grid cannot be printed (Kalibr's limit too).
constexpr int64_t kTag36h11Codes = 587;
// A checkerboard of more inner corners is no printable target (and would build 10^8 points).
constexpr int64_t kMaxCheckerboardCorners = 1'000'000;
// Point ids are integers stored in doubles by the YAML layer: exact up to 2^53.
constexpr double kMaxPointId = 9007199254740992.0;
// Sizes [m] and the tag spacing ratio beyond these are refused as implausible (a corrupt file or
// another unit); they keep every corner's coordinates finite.
constexpr double kMaxTargetSize = 1e3;
constexpr double kMaxTagSpacing = 1e2;
const std::vector<std::string> kTargetKeys = {"target_type",
                                              "tagCols",
                                              "tagRows",
                                              "tagSize",
                                              "tagSpacing",
                                              "targetCols",
                                              "targetRows",
                                              "rowSpacingMeters",
                                              "colSpacingMeters",
                                              "points"};

int GridCount(const YamlDocument& yaml, const std::string& key) {
  const int64_t n = yaml.Integer(key);
  if (n < 1 || n > kMaxGridSide) {
    throw Error(yaml.path(),
                yaml.Line(key),
                "'" + key + "' must be an integer in [1, " + std::to_string(kMaxGridSide) + "]");
  }
  return static_cast<int>(n);
}

}  // namespace

CalibrationTarget ReadTargetYaml(const std::string& path) {
  const YamlDocument yaml(path);
  yaml.CheckTypos("", kTargetKeys);
  const std::string type = yaml.String("target_type");
  try {
    if (type == "aprilgrid") {
      const double spacing = yaml.BoundedNumber("tagSpacing", kMaxTagSpacing, "(ratio)");
      if (spacing < 0.0) {
        throw Error(
            path, yaml.Line("tagSpacing"), "'tagSpacing' must be >= 0 (a ratio of tagSize)");
      }
      const int cols = GridCount(yaml, "tagCols"), rows = GridCount(yaml, "tagRows");
      if (int64_t{cols} * rows > kTag36h11Codes) {
        throw Error(path, yaml.Line("tagRows"),
                    "an aprilgrid of " + std::to_string(cols) + " x " + std::to_string(rows) +
                        " tags needs more than the 587 codes of tag family 36h11");
      }
      return MakeAprilGrid(cols, rows, yaml.PositiveNumber("tagSize", kMaxTargetSize, "m"),
                           spacing);
    }
    if (type == "checkerboard") {
      const int cols = GridCount(yaml, "targetCols"), rows = GridCount(yaml, "targetRows");
      if (int64_t{cols} * rows > kMaxCheckerboardCorners) {
        throw Error(path, yaml.Line("targetRows"),
                    "a checkerboard of " + std::to_string(cols) + " x " + std::to_string(rows) +
                        " inner corners is beyond the plausible " +
                        std::to_string(kMaxCheckerboardCorners));
      }
      return MakeCheckerboard(cols, rows,
                              yaml.PositiveNumber("colSpacingMeters", kMaxTargetSize, "m"),
                              yaml.PositiveNumber("rowSpacingMeters", kMaxTargetSize, "m"));
    }
  } catch (const Error& e) {
    if (!e.path().empty()) throw;
    throw Error(path, 0, e.message());
  }
  if (type != "points") {
    throw Error(
        path,
        yaml.Line("target_type"),
        "unsupported target_type '" + type + "' (supported: aprilgrid, checkerboard, points)");
  }
  CalibrationTarget target;
  target.type = "points";
  const std::vector<std::vector<double>> rows = yaml.Rows("points");
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double>& row = rows[i];
    const std::string where = "points[" + std::to_string(i) + "]";
    const int64_t line = yaml.Line("points/" + std::to_string(i));
    if (row.size() != 4) {
      throw Error(
          path,
          line,
          where + ": expected [id, x, y, z], got " + std::to_string(row.size()) + " numbers");
    }
    if (row[0] < 0.0 || row[0] != std::floor(row[0]) || row[0] > kMaxPointId) {
      throw Error(path, line, where + ": the id must be an integer >= 0");
    }
    const Eigen::Vector3d p(row[1], row[2], row[3]);
    if (p.cwiseAbs().maxCoeff() > kMaxPosition) {
      std::ostringstream message;
      message << where << ": a coordinate beyond the plausible " << kMaxPosition << " m";
      throw Error(path, line, message.str());
    }
    const int64_t id = static_cast<int64_t>(row[0]);
    if (!target.points.emplace(id, p).second) {
      throw Error(path, line, where + ": duplicate point id " + std::to_string(id));
    }
  }
  if (target.points.size() < 4) {
    throw Error(
        path,
        yaml.Line("points"),
        "a points target needs at least 4 points, got " + std::to_string(target.points.size()));
  }
  return target;
}

std::string TargetPointsYamlText(const CalibrationTarget& target) {
  std::ostringstream out;
  out << "target_type: points\npoints:\n";
  for (const auto& [id, p] : target.points) {
    out << "  - [" << id << ", " << FormatDouble(p.x()) << ", " << FormatDouble(p.y()) << ", "
        << FormatDouble(p.z()) << "]\n";
  }
  return out.str();
}

}  // namespace splinecal
