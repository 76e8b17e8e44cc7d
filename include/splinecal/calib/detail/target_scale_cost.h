// The target's scale against the IMU in `splinecal calibrate` (CalibrateOptions::target_scale):
// a target frame's reprojection residuals with the target's points scaled by s, p_t -> s p_t.
//
// Every camera model projects a ray: pi(s x) = pi(x) for s > 0. The point the camera sees,
//   x_c = T_c_s T_s_w(t) T_w_t (s p_t) = s (T_c_s / s)(T_s_w(t) / s)(T_w_t / s) p_t,
// where T / s is T with its translation divided by s, so the residuals at scale s are the
// unscaled frame's residuals at the control poses, T_cam_imu and T_w_t with their translations
// divided by s. Scaling translations is an automorphism of SE(3) that commutes with Exp and Log,
// so the spline of the scaled control poses is the scaled spline, in both trajectory models
// (spline/trajectory_model.h), with the same exposure times (the pixels do not change). With a
// held camera chain (ReprojectionOptions::T_cam_cref) the chain's translation scales with the
// target too: it came from a camera calibration with the same target.
//
// Jacobians from the unscaled frame's ambient pose Jacobians J' (translation columns J'_t, at
// the scaled translations t' = t / s): d r / d t = J'_t / s, the quaternion columns unchanged,
// and d r / d s = -(1/s) sum_poses J'_t t'. The frame may be compact (estimation/
// compact_frame_cost.h): the composition keeps J^T J and J^T r of the rows, and rows() gives the
// scaled rows for whatever reads them.
#ifndef SPLINECAL_CALIB_DETAIL_TARGET_SCALE_COST_H_
#define SPLINECAL_CALIB_DETAIL_TARGET_SCALE_COST_H_

#include <ceres/cost_function.h>

#include <memory>
#include <vector>

#include "splinecal/estimation/detail/compact_frame_cost.h"

namespace splinecal {

// Parameter blocks: the frame's (num_poses control poses, T_cam_imu, time offset, line delay,
// T_w_t[, intrinsics]; estimation/reprojection_cost.h), then s (1).
class TargetScaleCostFunction : public ceres::CostFunction, public CompactResidual {
 public:
  TargetScaleCostFunction(std::unique_ptr<ceres::CostFunction> frame, int num_poses);
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;
  const ceres::CostFunction& rows() const override { return rows_ ? *rows_ : *this; }

 private:
  // A view of a frame owned elsewhere (the rows of a compact frame).
  TargetScaleCostFunction(const ceres::CostFunction* frame, int num_poses);
  void Init();

  std::unique_ptr<ceres::CostFunction> owned_;
  const ceres::CostFunction* frame_ = nullptr;
  int num_poses_ = 0;
  std::vector<int> pose_blocks_;  // the frame's blocks whose translation scales
  std::unique_ptr<TargetScaleCostFunction> rows_;
};

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_DETAIL_TARGET_SCALE_COST_H_
