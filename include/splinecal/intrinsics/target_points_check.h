// Do the target's corners sit where its file puts them? A score test of every point's position,
// at the solution that takes the file's layout as exact.
//
// For a point p seen in views v, with r_v the corner's weighted residual (observed minus
// predicted pixel, over the camera's pixel sigma) and J_v = d(predicted pixel) / d(point) / sigma
// = (d uv / d p_c) R_c_t / sigma its derivative along a displacement delta of the point in the
// target frame, the one-step estimate of the displacement with everything else held and the
// drop in chi-square it buys are
//
//   delta_p = I_p^-1 s_p,   T_p = s_p^T I_p^-1 s_p,   I_p = sum_v J_v^T J_v,   s_p = sum_v J_v^T r_v
//
// (the Lagrange-multiplier or score test [Rao 1948; Silvey 1959]). On a target that is its
// file, sum_p T_p follows chi-square with 3 n - 7 degrees of freedom (n points; the target
// poses absorb a similarity of all the points: 6 rigid directions and the scale, which a camera
// alone does not see), so T / dof is about 1; a print or a detector that puts the corners
// elsewhere makes it large, and the intrinsics fitted to the file's layout are biased by it
// (docs/intrinsics.md, "Every point free": EuRoC's target, 0.93 mm RMS off its file, moved
// cam0's principal point by 3.3 px). The held poses and intrinsics absorb part of each
// displacement, so delta_p understates it somewhat.
#ifndef SPLINECAL_INTRINSICS_TARGET_POINTS_CHECK_H_
#define SPLINECAL_INTRINSICS_TARGET_POINTS_CHECK_H_

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/intrinsics/target_view.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

// Above this T / dof the intrinsics step warns and names --target-deformation points: the
// points' displacements are on average twice what the recording resolves of them, beyond what
// errors shared by a view's corners (blur, a detector's bias) make of the statistic.
inline constexpr double kTargetPointsWarnRatio = 4.0;

struct TargetPointsCheck {
  int points = 0;             // points tested: seen in at least min_views of the views
  int dof = 0;                // 3 points - 7 (0 below 3 points)
  double chi_square = 0.0;    // sum_p T_p
  double rms_offset_m = 0.0;  // RMS over the points of |delta_p|
  double max_offset_m = 0.0;  // the largest |delta_p|
  // Per tested point (by id): its position in the file, delta_p and the std of delta_p's
  // coordinates (sqrt of I_p^-1's diagonal), for the report's figure.
  std::map<int64_t, Eigen::Vector3d> file_points_m;
  std::map<int64_t, Eigen::Vector3d> offsets_m;
  std::map<int64_t, Eigen::Vector3d> offsets_std_m;
  double RatioToDof() const { return dof > 0 ? chi_square / dof : 0.0; }
};

// One view at the solution: its camera (intrinsics as solved), the target's pose in it, its
// corners (target points as the file has them) and the camera's pixel sigma.
struct TargetPointsCheckView {
  Camera camera;
  SE3d T_c_t;
  const TargetView* view = nullptr;
  double sigma_px = 1.0;
};

// The test over every point seen in at least min_views views (a point seen in fewer, or whose
// I_p is not positive definite, is left out). Corners whose projection fails are skipped.
TargetPointsCheck CheckTargetPoints(const std::vector<TargetPointsCheckView>& views,
                                    int min_views);

// The warning when check.RatioToDof() exceeds kTargetPointsWarnRatio (naming the offsets, the
// statistic and --target-deformation points), else empty.
std::string TargetPointsWarning(const TargetPointsCheck& check);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TARGET_POINTS_CHECK_H_
