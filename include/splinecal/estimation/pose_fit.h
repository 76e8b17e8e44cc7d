// Least-squares fit of spline control poses to timestamped poses (`splinecal simulate
// --trajectory-file`, and the analytic trajectories of sim/trajectories.h).
//
// Given poses T_m(t_j) (a motion-capture or ground-truth trajectory) and a knot layout
// (t0, dt, n), find the control poses T_0..T_{n-1} of the spline T(t) (spline/se3_spline.h)
// minimising
//
//     sum_j |p(t_j) - p_m(t_j)|^2 + w_R^2 |Log(R_m(t_j)^T R(t_j))|^2
//       + w_s^2 sum_{i=1..n-2} |Log(T_{i-1}^-1 T_i) - Log(T_i^-1 T_{i+1})|^2
//
// w_R [m/rad] weighs rotation against position; the last term (w_s, a weak smoothness prior on
// the second difference of the control poses) only decides directions the data leaves free
// (e.g. one pose per knot interval, or a gap): with the default w_s = 1e-3 it moves a
// well-determined fit by ~w_s^2 |second difference| / (poses per knot), below 1e-7 m for the
// trajectories of sim/trajectories.h.
//
// Solved with Ceres (Levenberg-Marquardt, sparse normal Cholesky; the problem is banded) on
// pose blocks {px, py, pz, qx, qy, qz, qw} with SE3Manifold (lie/se3_manifold.h, RIGHT
// perturbation). The spline is PoseFitOptions::trajectory's model (spline/trajectory_model.h;
// the smoothness prior is the same for both). One residual block per spline segment holds every
// pose in that segment; its Jacobians are analytic (spline/trajectory_evaluation.h
// EvaluatePoseJacobian):
//
//     T(P_k Exp(d)) = T Exp(J_k d)                        (J_k = J.blocks[k], rows [rho; phi])
//     d p / d d_k   = R J_k[rho rows]                      (T Exp(e) moves p by R rho)
//     d r / d d_k   = w_R Jr^-1(r) J_k[phi rows],          r = Log(R_m^T R)
//
// lifted to the ambient block by the manifold's MinusJacobian (MinusJacobian * PlusJacobian =
// I, so Ceres' chain rule gives back J_k). Initial control poses: the measured trajectory
// interpolated at the knot times (clamped to its ends).
#ifndef SPLINECAL_ESTIMATION_POSE_FIT_H_
#define SPLINECAL_ESTIMATION_POSE_FIT_H_

#include <ceres/cost_function.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

struct PoseFitOptions {
  // The spline's model: the coupled SE(3) spline or the split SO(3) x R^3 one.
  TrajectoryModel trajectory = TrajectoryModel::kSE3;
  double rotation_weight_m_per_rad = 1.0;  // w_R
  double smoothness_weight = 1e-3;         // w_s (0 disables the prior)
  int max_iterations = 50;
  int num_threads = 1;
  // Called once per solver iteration with a one-line summary (nullptr: silent).
  std::function<void(const std::string&)> progress;
};

struct PoseFitResult {
  std::vector<SE3d> control_poses;
  KnotLayout layout;
  TrajectoryModel trajectory = TrajectoryModel::kSE3;
  // Residuals of the fitted spline at the input poses (inside the spline's valid range).
  int64_t num_poses = 0;
  double position_rms_m = 0.0;
  double rotation_rms_deg = 0.0;
  double max_position_error_m = 0.0;
  double max_rotation_error_deg = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string solver_report;  // Ceres' BriefReport

  SE3Splined MakeSpline() const {
    return SE3Splined(control_poses, layout.t0_ns, layout.dt_ns, trajectory);
  }
};

// Fits the control poses of `layout` to `poses` (strictly increasing t_ns; poses outside the
// layout's valid range [t_1, t_{n-2}] are ignored). Throws splinecal::Error if the layout has
// fewer than 4 control poses or dt_ns <= 0, if the times are not strictly increasing, or if fewer
// than 2 poses fall in the valid range.
PoseFitResult FitControlPoses(const std::vector<StampedPose>& poses,
                              const KnotLayout& layout,
                              const PoseFitOptions& options = {});

// The fit's residual statistics for any spline (the same definitions as PoseFitResult's) over
// the poses inside its valid range.
void PoseFitErrors(const SE3Splined& spline,
                   const std::vector<StampedPose>& poses,
                   PoseFitResult* result);

namespace internal {

// The residual block of one segment (exposed for the Jacobian tests): poses at u[j] in the
// segment (knot spacing dt_s) of a `trajectory` spline, 6 rows each, over the four pose blocks
// {px, py, pz, qx, qy, qz, qw} of the segment's control poses. Ambient Jacobians as described in
// the file comment.
ceres::CostFunction* NewSegmentPoseCost(std::vector<double> u,
                                        std::vector<SE3d> measured,
                                        double dt_s,
                                        double rotation_weight_m_per_rad,
                                        TrajectoryModel trajectory = TrajectoryModel::kSE3);

// The smoothness prior of control poses i-1, i, i+1 (6 rows over three pose blocks): w_s times
// the second difference above, with analytic Jacobians (Jr^-1, Jl^-1 of SE(3)).
ceres::CostFunction* NewSmoothnessPriorCost(double weight);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_POSE_FIT_H_
