#include "splinecal/camera/target.h"

#include <cmath>
#include <string>

#include "splinecal/error.h"

namespace splinecal {

bool CalibrationTarget::IsPlanar() const {
  for (const auto& [id, p] : points) {
    if (p.z() != 0.0) return false;
  }
  return true;
}

CalibrationTarget MakeAprilGrid(int tag_cols,
                                int tag_rows,
                                double tag_size_m,
                                double tag_spacing_ratio) {
  if (tag_cols < 1 || tag_rows < 1) {
    throw Error("aprilgrid: tagCols and tagRows must be >= 1, got " + std::to_string(tag_cols) +
                " x " + std::to_string(tag_rows));
  }
  if (!(tag_size_m > 0.0) || !std::isfinite(tag_size_m)) {
    throw Error("aprilgrid: tagSize must be a positive length [m]");
  }
  if (!(tag_spacing_ratio >= 0.0) || !std::isfinite(tag_spacing_ratio)) {
    throw Error("aprilgrid: tagSpacing (a ratio of tagSize) must be >= 0");
  }
  CalibrationTarget target;
  target.type = "aprilgrid";
  target.grid_cols = tag_cols;
  target.grid_rows = tag_rows;
  target.tag_size_m = tag_size_m;
  target.tag_spacing_ratio = tag_spacing_ratio;
  const double pitch = (1.0 + tag_spacing_ratio) * tag_size_m;
  const int grid_cols = 2 * tag_cols;
  for (int r = 0; r < 2 * tag_rows; ++r) {
    for (int c = 0; c < grid_cols; ++c) {
      const double x = (c / 2) * pitch + (c % 2) * tag_size_m;
      const double y = (r / 2) * pitch + (r % 2) * tag_size_m;
      target.points[static_cast<int64_t>(r) * grid_cols + c] = Eigen::Vector3d(x, y, 0.0);
    }
  }
  return target;
}

CalibrationTarget MakeCheckerboard(int cols, int rows, double col_spacing_m, double row_spacing_m) {
  if (cols < 2 || rows < 2) {
    throw Error("checkerboard: targetCols and targetRows must be >= 2, got " +
                std::to_string(cols) + " x " + std::to_string(rows));
  }
  if (!(col_spacing_m > 0.0) || !(row_spacing_m > 0.0) || !std::isfinite(col_spacing_m) ||
      !std::isfinite(row_spacing_m)) {
    throw Error("checkerboard: colSpacingMeters and rowSpacingMeters must be positive [m]");
  }
  CalibrationTarget target;
  target.type = "checkerboard";
  target.grid_cols = cols;
  target.grid_rows = rows;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      target.points[static_cast<int64_t>(r) * cols + c] =
          Eigen::Vector3d(c * col_spacing_m, r * row_spacing_m, 0.0);
    }
  }
  return target;
}

}  // namespace splinecal
