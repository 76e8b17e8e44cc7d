// Calibration targets: points with known coordinates p_t in the target frame `t`, each with the
// id a corner detector reports for it (observations.csv's point_id).
//
// Kinds (io/target_yaml.h reads them from Kalibr-style YAML):
//   aprilgrid     Kalibr's AprilGrid: tagCols x tagRows tags of side tagSize [m], separated by
//                 tagSpacing * tagSize (tagSpacing is a RATIO, as in Kalibr). Corner ids as Kalibr
//                 numbers them: the corners form a (2 tagRows) x (2 tagCols) grid, id = r (2
//                 tagCols) + c for grid row r and column c, at
//                   x = floor(c/2) (1 + tagSpacing) tagSize + (c mod 2) tagSize
//                   y = floor(r/2) (1 + tagSpacing) tagSize + (r mod 2) tagSize,   z = 0
//                 so tag 0 (bottom left) owns corners 0, 1, 2 tagCols, 2 tagCols + 1.
//   checkerboard  Kalibr's checkerboard: targetCols x targetRows inner corners, id = r cols + c
//                 at (c colSpacingMeters, r rowSpacingMeters, 0).
//   points        any 3-D points: [[id, x, y, z], ...] in metres.
#ifndef SPLINECAL_CAMERA_TARGET_H_
#define SPLINECAL_CAMERA_TARGET_H_

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>

namespace splinecal {

struct CalibrationTarget {
  std::string type;                           // "aprilgrid", "checkerboard" or "points"
  std::map<int64_t, Eigen::Vector3d> points;  // id -> p_t [m]

  // The printed layout of a grid target, which a corner detector (detect/) needs: aprilgrid:
  // tagCols x tagRows tags; checkerboard: targetCols x targetRows inner corners; 0 for points.
  int grid_cols = 0;
  int grid_rows = 0;
  // aprilgrid only: the black square's side [m] and the gap between tags as a ratio of it.
  double tag_size_m = 0.0;
  double tag_spacing_ratio = 0.0;

  // The point of `id`, or nullptr when the target has no such id.
  const Eigen::Vector3d* Find(int64_t id) const {
    const auto it = points.find(id);
    return it == points.end() ? nullptr : &it->second;
  }
  // True when every point has z = 0 (PnP then uses a homography).
  bool IsPlanar() const;
};

// Throws splinecal::Error for non-positive counts or sizes or a negative spacing.
CalibrationTarget MakeAprilGrid(int tag_cols,
                                int tag_rows,
                                double tag_size_m,
                                double tag_spacing_ratio);
CalibrationTarget MakeCheckerboard(int cols, int rows, double col_spacing_m, double row_spacing_m);

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_TARGET_H_
