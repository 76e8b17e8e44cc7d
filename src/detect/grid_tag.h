// One decoded tag of a Kalibr AprilGrid and its place on the grid (private to src/detect/).
#ifndef SPLINECAL_SRC_DETECT_GRID_TAG_H_
#define SPLINECAL_SRC_DETECT_GRID_TAG_H_

#include <algorithm>

#include <opencv2/core.hpp>

#include "splinecal/camera/target.h"

namespace splinecal {

// A tag's id and its corners in the order of camera/target.h's tag-local corners: (0, 0),
// (1, 0), (1, 1), (0, 1) in units of the tag side, i.e. the corner ids 2r (2 cols) + 2c, +1,
// +2 cols + 1, +2 cols for tag row r and column c.
struct GridTag {
  int id = 0;
  cv::Point2d corners[4];
  bool kept = true;
};

// Corner k's tag-local position (x to the right, y up the printed grid).
constexpr int kLocalX[4] = {0, 1, 1, 0};
constexpr int kLocalY[4] = {0, 0, 1, 1};

inline double MeanSide(const GridTag& tag) {
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) sum += cv::norm(tag.corners[k] - tag.corners[(k + 1) % 4]);
  return sum / 4.0;
}

// The tag's shortest side [px]: along it the small squares beside the tag are narrowest, and
// their junctions nearest to each other.
inline double ShortestSide(const GridTag& tag) {
  double shortest = cv::norm(tag.corners[0] - tag.corners[1]);
  for (int k = 1; k < 4; ++k) {
    shortest = std::min(shortest, cv::norm(tag.corners[k] - tag.corners[(k + 1) % 4]));
  }
  return shortest;
}

// Corner k of tag `id` on the grid's plane, in tag sides (tag 0's corner 0 at the origin);
// `pitch` is the tag-to-tag step, 1 + tagSpacing.
inline cv::Point2d TagCorner(const CalibrationTarget& target, int id, int k, double pitch) {
  return {(id % target.grid_cols) * pitch + kLocalX[k], (id / target.grid_cols) * pitch + kLocalY[k]};
}

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_GRID_TAG_H_
