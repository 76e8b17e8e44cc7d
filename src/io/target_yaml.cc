#include "splinecal/io/target_yaml.h"

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Tag and corner counts beyond this per side are refused as implausible (a corrupt file).
constexpr int64_t kMaxGridSide = 10000;
// Point ids are integers stored in doubles by the YAML layer: exact up to 2^53.
constexpr double kMaxPointId = 9007199254740992.0;

int GridCount(const YamlDocument& yaml, const std::string& key) {
  const int64_t n = yaml.Integer(key);
  if (n < 1 || n > kMaxGridSide) {
    throw Error(yaml.path(),
                0,
                "'" + key + "' must be an integer in [1, " + std::to_string(kMaxGridSide) + "]");
  }
  return static_cast<int>(n);
}

}  // namespace

CalibrationTarget ReadTargetYaml(const std::string& path) {
  const YamlDocument yaml(path);
  const std::string type = yaml.String("target_type");
  try {
    if (type == "aprilgrid") {
      const double spacing = yaml.Number("tagSpacing");
      if (spacing < 0.0) throw Error(path, 0, "'tagSpacing' must be >= 0 (a ratio of tagSize)");
      return MakeAprilGrid(GridCount(yaml, "tagCols"),
                           GridCount(yaml, "tagRows"),
                           yaml.PositiveNumber("tagSize"),
                           spacing);
    }
    if (type == "checkerboard") {
      return MakeCheckerboard(GridCount(yaml, "targetCols"),
                              GridCount(yaml, "targetRows"),
                              yaml.PositiveNumber("colSpacingMeters"),
                              yaml.PositiveNumber("rowSpacingMeters"));
    }
  } catch (const Error& e) {
    if (!e.path().empty()) throw;
    throw Error(path, 0, e.message());
  }
  if (type != "points") {
    throw Error(
        path,
        0,
        "unsupported target_type '" + type + "' (supported: aprilgrid, checkerboard, points)");
  }
  CalibrationTarget target;
  target.type = "points";
  const std::vector<std::vector<double>> rows = yaml.Rows("points");
  for (size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double>& row = rows[i];
    const std::string where = "points[" + std::to_string(i) + "]";
    if (row.size() != 4) {
      throw Error(
          path,
          0,
          where + ": expected [id, x, y, z], got " + std::to_string(row.size()) + " numbers");
    }
    if (row[0] < 0.0 || row[0] != std::floor(row[0]) || row[0] > kMaxPointId) {
      throw Error(path, 0, where + ": the id must be an integer >= 0");
    }
    const int64_t id = static_cast<int64_t>(row[0]);
    if (!target.points.emplace(id, Eigen::Vector3d(row[1], row[2], row[3])).second) {
      throw Error(path, 0, where + ": duplicate point id " + std::to_string(id));
    }
  }
  if (target.points.size() < 4) {
    throw Error(
        path,
        0,
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
