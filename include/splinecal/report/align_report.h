// result.yaml of `splinecal align` (docs/align.md, "Outputs"): the metric scale, gravity in the
// first camera frame, the gyro bias, R_w_c0 (and R_cam_imu when estimated) as unit quaternions
// w x y z with w >= 0, the solver's figures and the options the alignment assumed.
// aligned_poses.csv comes from io/euroc.h (WriteEurocGroundTruth of AlignResult::states_w).
#ifndef SPLINECAL_REPORT_ALIGN_REPORT_H_
#define SPLINECAL_REPORT_ALIGN_REPORT_H_

#include <string>

#include "splinecal/vio/align.h"

namespace splinecal {

// For a successful alignment (result.success).
std::string AlignResultYaml(const AlignResult& result, const AlignOptions& options);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_ALIGN_REPORT_H_
