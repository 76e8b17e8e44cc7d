// Continuous-time fit of IMU data and a pose source (`splinecal fit`): the spline's control
// poses, the gyro and accelerometer biases, the gravity direction and, optionally, the time
// offset and the extrinsic between the pose source and the IMU, with standard deviations from
// ceres::Covariance and plain-words warnings where the data does not determine a parameter.
// docs/fit.md is the user's guide; this comment is the contract.
//
// The problem (docs/conventions.md for frames, units and the IMU model):
//
//   minimise  sum_k |r_gyro,k|^2 + |r_accel,k|^2       every IMU sample in the overlap
//           + sum_j |r_pose,j|^2                      every pose in the overlap
//           + sum_m |r_rw,m|^2                        bias-spline segments (BiasModel::kSpline)
//
// over the control poses T_i of the spline T_w_s(t) (IMU clock; uniform knots, SE3Manifold),
// the biases (constant or a bias spline), g_w (|g_w| fixed, GravityManifold), the time offset
// t_imu = t_pose + time_offset (optional) and the extrinsic T_m_s (optional). Residuals:
// estimation/detail/imu_costs.h (sigma = Kalibr density * sqrt(rate)), estimation/detail/pose_cost.h
// (pose_sigma_m, pose_sigma_rad), estimation/bias_costs.h (random walk).
//
// Initialisation (docs/fit.md, "Initialisation"): control poses by least squares on the poses
// (estimation/pose_fit.h); gravity g_w = g * unit(mean(a_w) - mean(R_w_s f)) over the whole
// overlap, mean(a_w) = (v_end - v_start) / duration from that spline (the platform's accelerations
// average out; no static period needed); biases zero; the time offset, when estimated, from the
// best alignment of the gyro's and the poses' angular speed within +-max_time_offset_s; the
// extrinsic rotation, when estimated, by hand-eye on relative rotations (vio/hand_eye.h).
//
// Errors. Throws splinecal::Error, with the likely cause in plain words, for: bad options;
// IMU and pose time ranges that do not overlap; data too short for the knot spacing; gyro or
// accelerometer units that disagree with the poses (deg/s vs rad/s, g vs m/s^2); a time offset
// at the edge of its search range; and a solver failure (Ceres failed, or residuals far beyond
// the noise: FitOptions::max_residual_noise_ratio).
#ifndef SPLINECAL_CALIB_FIT_H_
#define SPLINECAL_CALIB_FIT_H_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/estimation/knot_spacing.h"
#include "splinecal/estimation/options.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/estimation/spline_problem.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/vio/time_offset_correlation.h"

namespace splinecal {

// When a standard deviation exceeds its threshold the parameter is reported as not determined
// by the data (FitResult::warnings says why, in plain words).
struct ExcitationThresholds {
  double gyro_bias_std_rad_s = 2e-3;
  double accel_bias_std_m_s2 = 2e-2;
  double gravity_direction_std_deg = 0.5;
  double time_offset_std_s = 2e-3;
  double extrinsic_translation_std_m = 1e-2;
  double extrinsic_rotation_std_deg = 0.5;
  // |correlation| above this between two estimated quantities: they cannot be told apart.
  double max_correlation = 0.99;
};

struct FitOptions {
  // Knots (0: chosen from the data), gravity magnitude, IMU noise, bias model.
  SplineModelOptions model;
  // Initial g_w (its norm is replaced by model.gravity_m_s2); unset: from the specific force
  // (file comment).
  std::optional<Eigen::Vector3d> initial_gravity_w;
  Eigen::Vector3d initial_gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d initial_accel_bias = Eigen::Vector3d::Zero();
  // Pose source noise: position [m] per axis, rotation [rad] per axis.
  double pose_sigma_m = 1e-3;
  double pose_sigma_rad = 1e-3;
  // Time offset t_imu = t_pose + time_offset [s]: the fixed value, or the initial guess when
  // estimated (then also the centre of the correlation search).
  bool estimate_time_offset = false;
  double time_offset_s = 0.0;
  double max_time_offset_s = 0.1;  // search range +-max [s] when estimated
  // Extrinsic T_m_s: the IMU s in the pose source's frame m (docs/conventions.md "Frames and
  // notation"; maps IMU-frame points into m). Fixed, or the initial guess when estimated.
  // result.yaml writes it under the key T_pose_imu.
  bool estimate_extrinsic = false;
  SE3d T_m_s;
  // Levenberg-Marquardt, up to 4 rounds (pose residuals re-attached after the time offset moved
  // them across knots). The residuals are weighted by their noise, so Gauss-Newton steps are
  // good from the start: a first trust region of 1e6 (Ceres' default is 1e4) saves one or two
  // iterations on the reference problem (docs/fit.md, "Speed").
  SolverOptions solver = [] {
    SolverOptions solver;
    solver.initial_trust_region_radius = 1e6;
    solver.max_rounds = 4;
    return solver;
  }();
  CovarianceOptions covariance;
  ExcitationThresholds excitation;
  // Residual RMS above this many times the noise std (gyro or accel) is a failed fit (Error).
  // EuRoC's MAV vibrations leave the accelerometer at ~30x its white noise: 100 keeps real data
  // and catches wrong units, wrong trajectories and missed time offsets (typically 1000x).
  double max_residual_noise_ratio = 100.0;
  // Warn when the IMU residuals exceed the given noise (calibrate's initial guess does not: the
  // calibration measures and reports the IMU noise itself).
  bool warn_imu_residual_noise = true;
  // Keep per-sample predictions and residuals in FitResult (for residuals.csv / report.html).
  bool keep_samples = true;
  // Implementation choices with the same objective (tests and benchmarks compare them).
  ResidualOptions residuals;
};

// Per-axis root mean square of the residuals (unweighted, in the sensor's units) and the noise
// std the weights assumed.
struct ResidualStats {
  double gyro_rad_s = 0.0;
  double accel_m_s2 = 0.0;
  double position_m = 0.0;
  double rotation_rad = 0.0;
};

// One IMU sample after the fit.
struct FitImuSample {
  int64_t t_ns = 0;
  Eigen::Vector3d gyro_measured = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_fitted = Eigen::Vector3d::Zero();  // w_s + b_g
  Eigen::Vector3d accel_measured = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_fitted = Eigen::Vector3d::Zero();  // R^T (a_w - g_w) + b_a
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
};

// One pose after the fit (pose-source clock).
struct FitPoseSample {
  int64_t t_ns = 0;
  Eigen::Vector3d position_error_m = Eigen::Vector3d::Zero();    // p_pred - p_measured (world)
  Eigen::Vector3d rotation_error_rad = Eigen::Vector3d::Zero();  // Log(R_measured^T R_pred)
};

struct FitResult {
  // The spline T_w_s(t), IMU clock, in the trajectory model the fit used.
  KnotLayout layout;
  TrajectoryModel trajectory = TrajectoryModel::kSE3;
  std::vector<SE3d> control_poses;
  SE3Splined MakeSpline() const {
    return SE3Splined(control_poses, layout.t0_ns, layout.dt_ns, trajectory);
  }
  double knot_spacing_s = 0.0;
  std::string knot_spacing_rule;  // how dt was chosen, in words

  // Biases: the constant bias, or for BiasModel::kSpline the time average of the bias spline
  // over the IMU samples. Standard deviations per axis.
  BiasModel bias_model = BiasModel::kConstant;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_std = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_std = Eigen::Vector3d::Zero();
  // Bias spline (kSpline): control points at tb_m = bias_t0_ns + m * bias_dt_ns.
  int64_t bias_t0_ns = 0;
  int64_t bias_dt_ns = 0;
  std::vector<Eigen::Vector3d> gyro_bias_control_points;
  std::vector<Eigen::Vector3d> accel_bias_control_points;

  // Gravity in the pose source's world frame [m/s^2]; std per component, and of the direction.
  Eigen::Vector3d gravity_w = Eigen::Vector3d::Zero();
  Eigen::Vector3d gravity_w_std = Eigen::Vector3d::Zero();
  double gravity_direction_std_deg = 0.0;

  bool time_offset_estimated = false;
  double time_offset_s = 0.0;
  double time_offset_std_s = 0.0;

  bool extrinsic_estimated = false;
  SE3d T_m_s;  // FitOptions::T_m_s
  Eigen::Vector3d T_m_s_translation_std_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d T_m_s_rotation_std_rad = Eigen::Vector3d::Zero();

  // Joint covariance of the estimated global quantities in tangent coordinates, in this order:
  // gyro bias (3), accel bias (3) (the time averages for kSpline), gravity direction (2, rad),
  // time offset (1, s, when estimated), extrinsic [rho; phi] (6, m and rad, when estimated).
  // Empty when it could not be computed (covariance_ok = false: warnings say why).
  bool covariance_ok = false;
  Eigen::MatrixXd covariance;
  std::vector<std::string> covariance_labels;
  std::string covariance_method;  // which of the (equivalent) computations ran

  ResidualStats residual_rms;
  ResidualStats noise_std;  // what the weights assume (sigma per axis)
  // The IMU noise: given, measured from the residuals, and what weighted the solve.
  ImuNoiseEstimate imu_noise;
  // The largest factor by which a reported std exceeds the weights' (the measured noise or the
  // cluster-robust scatter over robust_clusters time windows; 1: the weights explain it).
  double std_inflation = 1.0;
  int robust_clusters = 0;
  double imu_rate_hz = 0.0;
  int num_imu_samples = 0;
  int num_poses = 0;

  SolveSummary solve;  // > 1 round when pose residuals were re-attached after a time-offset move
  double covariance_time_s = 0.0;

  std::vector<std::string> warnings;
  // Quantities the data does not determine (std above ExcitationThresholds, or a singular
  // information matrix), by their result.yaml keys: "gyro_bias", "accel_bias", "gravity_w",
  // "time_offset_s", "T_pose_imu" (T_m_s).
  std::vector<std::string> not_determined;

  std::vector<FitImuSample> imu_samples;    // when FitOptions::keep_samples
  std::vector<FitPoseSample> pose_samples;  // when FitOptions::keep_samples
};

// The fit as an object, for callers that want to inspect or replace the initial guess (tests,
// the benchmark). The constructor validates the data and builds the initial guess (throws
// splinecal::Error as described in the file comment); Solve() runs the solver, the covariance
// and the diagnostics.
class FitProblem {
 public:
  FitProblem(const std::vector<ImuSample>& imu,
             const std::vector<StampedPose>& poses,
             const FitOptions& options);
  ~FitProblem();
  FitProblem(const FitProblem&) = delete;
  FitProblem& operator=(const FitProblem&) = delete;

  const KnotLayout& layout() const;

  // Replace parts of the initial guess before Solve().
  void SetControlPoses(const std::vector<SE3d>& control_poses);  // same count as layout()
  void SetBiases(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias);
  void SetGravity(const Eigen::Vector3d& g_w);  // norm replaced by FitOptions::gravity_m_s2
  void SetTimeOffset(double time_offset_s);

  FitResult Solve();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// FitProblem(imu, poses, options).Solve().
FitResult Fit(const std::vector<ImuSample>& imu,
              const std::vector<StampedPose>& poses,
              const FitOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_FIT_H_
