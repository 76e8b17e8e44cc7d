// The reprojection residual of `splinecal intrinsics`: the corners of one calibration-target view
// seen by camera n of a rigid multi-camera rig, with analytic Jacobians with respect to the
// camera's intrinsics, the target's pose in camera 0 and the rig extrinsic T_cn_c0.
//
// Model. The target's pose in camera 0 at the view's timestamp, T_c0_t, is one unknown per
// timestamp (every camera of the rig sees the target at the same instant); camera n sits at the
// fixed T_cn_c0 (identity for n = 0, no block); with a target shape (target_deformation.h) the
// corner's point p_t = (x, y, 0) is first moved to p_t + D(x, y) c: out of plane to
// (x, y, h(x, y)), h = c^T b(x, y) (D = e_z b^T), or in plane by the AprilGrid's layout map:
//
//   x_c = R_cn_c0 (R_c0_t p_t + t_c0_t) + t_cn_c0,     uv = pi(x_c; intrinsics)
//   r   = f(|e|) e / sigma_px,   e = uv - uv_observed              (2 rows per corner)
//
// with pi the camera model's projection (camera/camera_model.h) and f Huber's factor applied
// inside the cost function (estimation/reprojection_cost.h, RobustifyPoint), so that the corners
// of one view can share a residual block.
//
// Jacobians (RIGHT perturbations, lie/se3.h, tangent [rho; phi]):
//   T_c0_t -> T_c0_t Exp(d):   d x_c / d d = R_cn_c0 R_c0_t [I, -[p_t]x]
//   T_cn_c0 -> T_cn_c0 Exp(d): d x_c / d d = R_cn_c0 [I, -[x_c0]x],   x_c0 = T_c0_t p_t
//   target shape c (optional):  d x_c / d c   = R_cn_t D(x, y)
//   per-view inset d_v (optional): d x_c / d d_v = R_cn_t D_d(x, y), D's inset column
//   intrinsics:                d uv / d intrinsics from the camera model, analytic
// chained through J_pi = d uv / d x_c and Huber's 2x2 factor; pose blocks are lifted to their
// ambient {px, py, pz, qx, qy, qz, qw} blocks exactly (estimation/detail/pose_block_jacobian.h).
// A corner that does not project (outside the model's valid region) contributes a zero residual
// and zero Jacobian rows, and is counted by the caller's outlier pass.
#ifndef SPLINECAL_INTRINSICS_RIG_REPROJECTION_COST_H_
#define SPLINECAL_INTRINSICS_RIG_REPROJECTION_COST_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/intrinsics/target_deformation.h"

namespace splinecal {

struct RigViewOptions {
  Camera model;                // the camera model (projection, distortion, size); its values unused
  bool has_extrinsic = false;  // camera n > 0: a T_cn_c0 block follows the target pose
  double sigma_px = 1.0;       // pixel noise std [px]
  double huber_px = 0.0;       // Huber threshold [px]; 0 = plain least squares
  TargetShape shape;           // kind none: a flat target, no shape block
};

// Parameter blocks: T_c0_t (7), intrinsics (kNumIntrinsics, camera/camera_model.h layout), and
// with has_extrinsic T_cn_c0 (7), then with a shape its coefficients c (shape.size()), then with
// a per-view inset (target_deformation.h, in-plane-per-view) the view's d_v (1). The
// target pose comes first: estimation/marginal_covariance.h groups residual blocks by their first
// parameter block, and a view's pose is what its residuals have alone (the intrinsics, shared by
// every view, would make one huge group).
class RigViewCostFunction : public ceres::CostFunction {
 public:
  RigViewCostFunction(const RigViewOptions& settings,
                      std::vector<TargetCornerObservation> corners);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const std::vector<TargetCornerObservation>& corners() const { return corners_; }

 private:
  RigViewOptions settings_;
  std::vector<TargetCornerObservation> corners_;
};

// The pixel errors uv - uv_observed of every corner of a view (NaN for a corner that does not
// project) at the given values: for outlier rejection and the report.
std::vector<Eigen::Vector2d> RigViewErrors(const Camera& camera,
                                           const SE3d& T_cn_t,
                                           const std::vector<TargetCornerObservation>& corners);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_RIG_REPROJECTION_COST_H_
