// One reprojection error after an estimate (calibrate, intrinsics): which corner of which frame,
// where it was seen and how far the estimate's projection lands from it. The reports draw these
// (report/reprojection_figures.h) and calibrate writes them to reprojection_errors.csv.
#ifndef SPLINECAL_CAMERA_REPROJECTION_SAMPLE_H_
#define SPLINECAL_CAMERA_REPROJECTION_SAMPLE_H_

#include <Eigen/Core>
#include <cstdint>

namespace splinecal {

struct ReprojectionSample {
  int64_t t_ns = 0;  // frame stamp, camera clock
  int cam_id = 0;
  int64_t point_id = 0;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();     // observed
  Eigen::Vector2d error = Eigen::Vector2d::Zero();  // predicted - observed [px]
};

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_REPROJECTION_SAMPLE_H_
