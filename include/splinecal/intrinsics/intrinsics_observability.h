// Which intrinsics a set of target views does not determine, from the information matrix
// (calib/calibrate_intrinsics.h, step 7).
//
// With J_i the Jacobian of a view's weighted residuals with respect to the active intrinsics
// and J_p with respect to the view's target pose (its right tangent), the information about the
// intrinsics once every pose is marginalised is
//
//   H = sum_views  J_i^T J_i - J_i^T J_p (J_p^T J_p)^-1 J_p^T J_i          (Schur complement)
//
// (each view's pose treated as its own unknown: for a rig this ignores what the other cameras
// tell about a shared pose, so it errs towards warning). H is diagonally scaled, decomposed
// into eigenvalues, and directions with an eigenvalue below 1e-12 of the largest count as
// undetermined (infinite standard deviation); otherwise std_j = sqrt((H^-1)_jj). A parameter
// is named when its std exceeds its threshold:
//   fu, fv, pu, pv:                  kUndeterminedPixelRatio x the image width
//   shape and distortion parameters: kUndeterminedShapeStd (they are of order 0.01 to 1)
// together with what the views lack: the largest tilt of the target against the image plane
// (focal length and distance trade off in fronto-parallel views), the share of the image the
// corners cover (distortion is seen only where corners are), and the number of views.
#ifndef SPLINECAL_INTRINSICS_INTRINSICS_OBSERVABILITY_H_
#define SPLINECAL_INTRINSICS_INTRINSICS_OBSERVABILITY_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/intrinsics/target_view.h"

namespace splinecal {

inline constexpr double kUndeterminedPixelRatio = 0.02;
inline constexpr double kUndeterminedShapeStd = 0.05;
// The coverage grid: the image in kCoverageCells x kCoverageCells cells.
inline constexpr int kCoverageCells = 8;

struct IntrinsicsObservability {
  Eigen::VectorXd std;            // per active intrinsic (in `active` order); inf: undetermined
  std::vector<int> undetermined;  // indices (layout of camera/camera_model.h) above threshold
  double max_tilt_deg = 0.0;      // largest angle between the target normal and the optical axis
  double coverage = 0.0;          // share of the coverage cells holding a corner
  int views = 0;
  std::string warning;  // empty when every parameter is determined
};

// `views` of one camera with their final T_c_t; residuals weighted by 1 / sigma_px.
IntrinsicsObservability AnalyseObservability(const std::string& camera_name,
                                             const Camera& camera,
                                             const std::vector<int>& active,
                                             const std::vector<const TargetView*>& views,
                                             double sigma_px);

// The name of intrinsics entry `index` for camera's model ("fu", "xi", "k1", "p2", "w", ...).
std::string IntrinsicName(const Camera& camera, int index);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_INTRINSICS_OBSERVABILITY_H_
