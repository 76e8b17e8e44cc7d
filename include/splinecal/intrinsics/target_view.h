// One view of the calibration target by one camera: its corners with their target coordinates,
// the target pose found by PnP, and what became of the view (calib/calibrate_intrinsics.h).
#ifndef SPLINECAL_INTRINSICS_TARGET_VIEW_H_
#define SPLINECAL_INTRINSICS_TARGET_VIEW_H_

#include <cstdint>
#include <vector>

#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

struct TargetView {
  int64_t t_ns = 0;
  int cam_id = 0;
  std::vector<int64_t> point_ids;                // parallel to corners
  std::vector<TargetCornerObservation> corners;  // target point and observed pixel
  SE3d T_c_t;                                    // PnP's pose (valid when pnp_ok)
  bool pnp_ok = false;
};

// The views of `observations` (grouped by timestamp and camera, in that order), each with the
// corners whose point id `target` has; *unknown_ids counts the others.
std::vector<TargetView> MakeTargetViews(const std::vector<Observation>& observations,
                                        const CalibrationTarget& target,
                                        int64_t* unknown_ids);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TARGET_VIEW_H_
