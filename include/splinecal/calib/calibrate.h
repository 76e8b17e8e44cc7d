// Camera-IMU calibration in continuous time, rolling shutter included (`splinecal calibrate`,
// [Lovegrove13], [seed002]). docs/calibrate.md is the user's guide; this comment is the
// contract.
//
// The problem (docs/conventions.md for frames, units, T_cam_imu, the time offset, line_delay):
//
//   minimise  sum_k |r_gyro,k|^2 + |r_accel,k|^2        every IMU sample (estimation/detail/imu_costs.h)
//           + sum_m |r_rw,m|^2                         bias random walk (estimation/bias_costs.h)
//           + sum_f sum_c rho(|r_c,f|^2)               target corners, per frame
//           + sum_o rho(|r_o|^2)                       landmark observations
//                                                      (estimation/reprojection_cost.h, Huber rho)
//
// over the control poses of T_w_s(t) (IMU clock, SE3Manifold), the biases (constant or a bias
// spline), gravity g_w (|g_w| fixed, GravityManifold), and per camera T_cam_imu, the time
// offset t_imu = t_cam + time_offset_s (unless fixed) and line_delay (with rolling_shutter; else
// fixed at the camchain's value, normally 0), plus the inverse depths of natural landmarks. The
// world is the target's frame (T_w_t = identity, fixed: it removes the 6 gauge freedoms of world
// position and orientation; gravity is estimated in it). Without a target the first control pose is
// held fixed instead. The result is then rotated into a gravity-aligned world (CalibrationResult::
// T_w_target). A line delay that reaches a bound is held there while the rest is solved, and
// freed again when the cost's gradient points inside (an active set: Ceres' projection of steps
// onto bounds otherwise creeps along the bound). IMU residuals are weighted by Kalibr's densities
// (sigma = density sqrt(rate)), pixels by pixel_sigma_px: given, or estimated from the residuals
// (1.4826 x the median absolute pixel error, robust to outliers) and the problem solved again with
// it, so that the reported standard deviations reflect the data's own pixel noise.
//
// Initialisation (target present): the target's pose in every frame by PnP (camera/pnp.h); those
// camera poses as the pose source of `splinecal fit` (calib/fit.h) with the time offset (gyro vs
// camera angular-speed correlation, then least squares) and the extrinsic (hand-eye rotation,
// then least squares) estimated: it gives the trajectory, the biases, gravity, T_cam_imu and the
// time offset; the full problem refines them together with the line delay. Landmarks are
// initialised from their reference observation and a depth triangulated from the initial
// trajectory. Without a target the caller supplies the initial guess (CalibrationInitialGuess),
// e.g. InitialGuessFromImuPoses on `splinecal align`'s output.
//
// Time windows: each residual holds the control poses of its possible exposure times
// (estimation/reprojection_cost.h); after a solve in which the time offset or line delay moved them
// out of their windows (or the pixel sigma changed by more than 10%), the problem is rebuilt and
// solved again (at most max_rounds rounds).
//
// Errors and warnings. Throws splinecal::Error, in plain words, for: a camchain/observations
// mismatch (a cam_id without a camera); observations outside the IMU's time range; a target
// given but never seen (no point id of the target in the observations); too few usable frames;
// too little rotation (the gyro's RMS rate about its weakest axis below
// min_rotation_rate_rad_s: T_cam_imu's rotation and the time offset cannot be determined); and
// solver failure. Parameters the data does not determine well (a standard deviation above
// its threshold) get a warning in CalibrationResult::warnings.
#ifndef SPLINECAL_CALIB_CALIBRATE_H_
#define SPLINECAL_CALIB_CALIBRATE_H_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/calib/imu_covariance.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/reprojection_sample.h"
#include "splinecal/camera/target.h"
#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/estimation/options.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/camchain_yaml_covariance.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {

// How calibrate treats a quantity the camchain gives (the intrinsics, the camera chain):
//   kHeld   fixed at the camchain's value, treated as exact;
//   kPrior  estimated, with a Gaussian prior at the camchain's value: the residual
//           L^-1 (theta - theta_0), Sigma = L L^T the camchain's covariance, joins the problem,
//           so the standard deviations of everything else include its uncertainty;
//   kFree   estimated from this recording alone, starting at the camchain's value;
//   kConsider  (intrinsics only) held at the camchain's value, with the camchain's covariance
//           Sigma_c carried into the others' ("consider" parameters, Schmidt): each reported
//           covariance is Sigma_theta|c + S Sigma_c S^T, S = d theta / d c = -H_tt^-1 H_tc from
//           this problem's information at the solution (calib/consider_covariance.h). The
//           corners count once: no prior made from them joins the problem that fits them again.
enum class ParameterMode { kHeld, kPrior, kFree, kConsider };
const char* ParameterModeName(ParameterMode mode);  // "held", "prior", "free", "consider"
// The target's scale s (p_t -> s p_t) against the IMU (CalibrateOptions::target_scale):
//   kCheck  estimated, refused beyond the thresholds, then held at 1 (the default);
//   kFree   estimated and kept in the result (metric scale from the accelerometer);
//   kHeld   held at 1, not checked.
enum class TargetScaleMode { kCheck, kFree, kHeld };
const char* TargetScaleModeName(TargetScaleMode mode);  // "check", "free", "held"

// A further IMU of the rig (several IMUs; docs/calibrate.md "Several IMUs"): every IMU after the
// first, which is the reference (the spline's frame b). Its pose T_i_b (C_i_b, lever arm r_b),
// time offset and biases are estimated with Kalibr's `calibrated` model
// (estimation/detail/further_imu_cost.h); it must have the reference's rate within 1%.
struct FurtherImu {
  std::string name;                // for messages and results (its file or topic)
  std::vector<ImuSample> samples;  // its own clock: t_reference = t_stamp + time_offset
  ImuNoise noise;                  // its Kalibr densities, weighting its residuals as given
  // Its Kalibr model (imu/imu_model_kind.h): its own M_a, M_g, A, C_gyro_i (ry_i, rz_i) at its
  // pose (estimation/detail/further_imu_cost.h), nominal initially.
  ImuModelKind model = ImuModelKind::kCalibrated;
};

struct CalibrateOptions {
  // Knots every 0.05 s (0: chosen from the data), gravity magnitude, IMU noise, bias spline.
  SplineModelOptions model = [] {
    SplineModelOptions model;
    model.knot_spacing_s = 0.05;
    model.bias_model = BiasModel::kSpline;
    return model;
  }();
  bool rolling_shutter = false;           // estimate line_delay (else fixed at the camchain's)
  bool estimate_time_offset = true;       // else time_offset_s fixed at the camchain's
  double max_time_offset_s = 0.1;         // |time_offset_s| bound and correlation search range
  double pixel_sigma_px = 0.0;            // pixel noise std [px]; 0 = estimated from the residuals
  double huber_px = 2.0;                  // Huber threshold [px]; 0 = plain least squares
  int min_corners_per_frame = 8;          // frames with fewer target corners are not used
  double min_rotation_rate_rad_s = 0.05;  // refuse data rotating less about its weakest axis
  // A rig whose cameras' relative poses are known (`splinecal intrinsics`' T_cn_cnm1), camera
  // 0's entry the identity. Empty: every camera's T_cam_imu is estimated on its own (kFree).
  // camera_chain says how it is used (below).
  std::vector<SE3d> camera_chain_T_cn_c0;
  // The camchain's covariances (io/camchain_yaml_covariance.h), one entry per camera (nullopt:
  // none; an empty vector: none at all). They make the priors of kPrior below.
  std::vector<std::optional<CameraCovariance>> camchain_covariances;
  // The cameras' intrinsics (the entries each model uses; ParameterMode). nullopt, the default:
  // kPrior for a camera whose covariance is given, else kHeld (a camchain without a covariance,
  // e.g. Kalibr's published one, is treated as exact: it comes from a dedicated recording).
  // Estimated intrinsics need target corners only (no natural landmarks: a landmark's reference
  // ray is taken at the given intrinsics).
  std::optional<ParameterMode> intrinsics;
  // Deprecated alias of intrinsics = kFree (the --estimate-intrinsics of earlier versions);
  // ignored when `intrinsics` is set.
  bool estimate_intrinsics = false;
  // The cameras' relative poses T_cn_cnm1 (needs camera_chain_T_cn_c0 for kHeld and kPrior):
  //   kHeld   one T_cam_imu is estimated, cam0's; camera n's is T_cn_c0 * T_c0_imu;
  //   kPrior  every T_cam_imu estimated, with a prior on each T_cn_cnm1 = T_cn_imu T_cnm1_imu^-1
  //           (the covariance's T_cn_cnm1 rows, the right tangent T_cn_cnm1 Exp([rho; phi]));
  //   kFree   every T_cam_imu estimated on its own.
  // nullopt, the default: kPrior when the chain is given and every camera n > 0 has a
  // covariance with T_cn_cnm1 rows, kHeld when the chain is given without them, else kFree.
  std::optional<ParameterMode> camera_chain;
  // The target's scale against the IMU (TargetScaleMode). The accelerometer fixes metric scale:
  // the problem is solved with the target's points scaled by a free s (p_t -> s p_t), and with
  // kCheck the calibration is refused when |s - 1| exceeds both target_scale_sigmas standard
  // deviations and max_target_scale_error; then s is held at 1 and the problem solved again,
  // so that the target's printed size, not the accelerometer's scale, sets the metric scale of
  // the result (a consumer accelerometer's own scale error can reach a few percent; there is no
  // IMU scale model: max_target_scale_error covers it).
  TargetScaleMode target_scale = TargetScaleMode::kCheck;
  double target_scale_sigmas = 3.0;
  double max_target_scale_error = 0.05;
  // For the refusal's message: the target's name (its file) and an AprilGrid's tagSize [m] (0:
  // not an AprilGrid), so that it can say which size would fit.
  std::string target_name = "the target's description";
  double target_tag_size_m = 0.0;
  // Levenberg-Marquardt with SPARSE_NORMAL_CHOLESKY, up to 6 rounds (time windows rebuilt and
  // the pixel noise re-estimated between them).
  SolverOptions solver = [] {
    SolverOptions solver;
    solver.linear_solver = LinearSolver::kSparseNormalCholesky;
    solver.max_rounds = 6;
    return solver;
  }();
  // Always the Schur backend (calibrate.cc, ComputeCovariance, says why).
  CovarianceOptions covariance;
  // Warnings when a standard deviation exceeds these.
  double warn_rotation_std_deg = 0.1;
  double warn_translation_std_m = 0.005;
  double warn_time_offset_std_s = 0.001;
  double warn_line_delay_relative_std = 0.05;
  bool keep_residuals = true;  // per-observation and per-IMU-sample residuals in the result
  // Kalibr's IMU model (--imu-model; imu/imu_model_kind.h, docs/imu_models.md). kCalibrated is
  // the analytic IMU residuals; another model adds its parameters (M_a, M_g, A, C_gyro_i; ry_i,
  // rz_i with the size effect) to the problem, starting at nominal, with analytic residuals
  // (estimation/detail/imu_model_costs.h).
  ImuModelKind imu_model = ImuModelKind::kCalibrated;
  // Model parameters held at nominal whatever the recording determines (no std reported), by
  // their names in estimation/imu_model_observability.h ("A(1,2)", "C_gyro_i(z)"); a bare
  // matrix name ("A", "M_a", "C_gyro_i") holds all its entries. For studies of what a parameter
  // does to the rest (docs/imu_models.md, "On real data"). An unknown name throws Error.
  std::vector<std::string> imu_model_held;
  // The rig's further IMUs (FurtherImu; empty: one IMU). Their initial guess: C_i_b by aligning
  // their gyro with the initial spline's angular velocity (closed-form Kabsch), the time offset
  // from the gyro-rate correlation (vio/time_offset_correlation.h, within max_time_offset_s),
  // r_b = 0. A lever arm the motion does not determine (std above max_lever_arm_std_m, from the
  // accelerometer's information at the initial guess: too little rotation) is held at 0 with a
  // warning.
  std::vector<FurtherImu> further_imus;
  double max_lever_arm_std_m = 0.01;
  // For the reports only: the command line these options came from (empty: the library's
  // caller did not say).
  std::string command_line;
};

// A starting point for the whole state (required without a target; optional otherwise).
struct CalibrationInitialGuess {
  KnotLayout layout;
  // T_w_s at the layout's knots, in CalibrateOptions::model.trajectory's model.
  std::vector<SE3d> control_poses;
  Eigen::Vector3d gravity_w = Eigen::Vector3d(0.0, 0.0, -kDefaultGravity);
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Camchain camchain;  // T_cam_imu, time_offset_s, line_delay_s per camera
};

struct CameraEstimate {
  CameraCalibration calibration;  // the estimates (intrinsics as given)
  // Standard deviations: rotation of T_cam_imu in its right tangent (per axis, IMU frame) [deg],
  // translation t_cam_imu per axis (camera frame) [m]; NaN when not computed.
  Eigen::Vector3d rotation_std_deg =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d translation_std_m =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  double time_offset_std_s = std::numeric_limits<double>::quiet_NaN();
  // Camera n > 0: the stereo baseline |t| of T_cn_cnm1 = T_cn_imu T_cnm1_imu^-1 [m] and its std
  // from the joint covariance of the two T_cam_imu (0 with a held camera chain: the camchain's);
  // NaN for cam0 or when not computed.
  double baseline_m = std::numeric_limits<double>::quiet_NaN();
  double baseline_std_m = std::numeric_limits<double>::quiet_NaN();
  // The intrinsics: how they were treated, the camchain's values (before; `calibration` has
  // after), the prior's std (kPrior, kConsider) and the estimate's std (layout of
  // camera/camera_model.h; NaN where held or not in the prior; kConsider: the carried one).
  ParameterMode intrinsics_mode = ParameterMode::kHeld;
  IntrinsicsVector intrinsics_before = IntrinsicsVector::Zero();
  IntrinsicsVector intrinsics_prior_std =
      IntrinsicsVector::Constant(std::numeric_limits<double>::quiet_NaN());
  IntrinsicsVector intrinsics_std = IntrinsicsVector::Constant(std::numeric_limits<double>::quiet_NaN());
  bool intrinsics_estimated = false;  // intrinsics_mode is kPrior or kFree
  double line_delay_std_s = std::numeric_limits<double>::quiet_NaN();
  bool time_offset_estimated = false;
  bool line_delay_estimated = false;
  double reprojection_rms_px = 0.0;  // RMS of the 2-D pixel errors
  int num_frames = 0;
  int num_observations = 0;
};

// One IMU sample after the calibration (for report.html).
struct ImuResidualRecord {
  int64_t t_ns = 0;
  Eigen::Vector3d gyro_error = Eigen::Vector3d::Zero();   // predicted - measured [rad/s]
  Eigen::Vector3d accel_error = Eigen::Vector3d::Zero();  // [m/s^2]
  // The biases at t_ns (the bias spline's value, or the constant) [rad/s], [m/s^2]. NaN when not
  // recorded: the report then draws the means gyro_bias / accel_bias instead of their course.
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

// Standard deviations of an estimated IMU model, per entry (NaN where not a parameter or not
// computed): M_a, M_g (lower triangles), A, the rotation vector phi of C_gyro_i = Exp(phi)
// (estimation/detail/imu_model_costs.h), per axis [deg], ry_i, rz_i [m].
struct ImuModelStd {
  Eigen::Matrix3d M_a = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Matrix3d M_g = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Matrix3d A = Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d C_gyro_i_deg = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d ry_i = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d rz_i = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

// A further IMU's estimate (CalibrateOptions::further_imus, same order).
struct FurtherImuEstimate {
  std::string name;
  // Its model (FurtherImu::model) and intrinsics: C_i_b, r_b and the model's entries;
  // time_offset_s (imu/imu_intrinsics.h).
  ImuCalibration calibration;
  ImuModelStd model_std;  // the model's entries' stds (NaN for `calibrated`)
  // The joint covariance of C_i_b's phi [rad], r_b [m] (unless held), the time offset [s] and the
  // model's estimated entries, in that order (calib/imu_covariance.h); empty when not computed.
  ImuCovariance covariance;
  // Standard deviations: C_i_b's rotation in its right tangent C_i_b Exp(phi) (b axes) [deg],
  // r_b per axis [m] (NaN when held), the time offset [s]; NaN when not computed.
  Eigen::Vector3d rotation_std_deg = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d r_b_std_m = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  double time_offset_std_s = std::numeric_limits<double>::quiet_NaN();
  bool lever_arm_held = false;  // held at 0 (too little rotation to determine it)
  // Initial guess of the time offset (gyro-rate correlation) [s] and of C_i_b.
  double initial_time_offset_s = 0.0;
  Eigen::Matrix3d initial_C_i_b = Eigen::Matrix3d::Identity();
  // Biases: constant, or the time average of the bias spline over its samples.
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  double gyro_rms = 0.0;   // per-axis RMS of predicted - measured [rad/s]
  double accel_rms = 0.0;  // [m/s^2]
  int num_samples = 0;     // the samples used (inside the spline for any time offset in range)
  double rate_hz = 0.0;
  ImuNoise noise;          // the densities that weighted it
};

struct CalibrationResult {
  std::vector<CameraEstimate> cameras;
  Camchain camchain;  // the estimated camchain (intrinsics as given)

  KnotLayout layout;
  double knot_spacing_s = 0.0;
  std::string knot_spacing_rule;  // how it was chosen, in words
  // The world w is gravity-aligned (conventions.md): z up, gravity_w = (0, 0, -g), its yaw taken
  // from the target: T_w_target is a pure rotation, the smallest taking gravity_target to -z
  // followed by the rotation about z that zeroes its ZYX yaw (vio/align.h,
  // GravityAlignedRotation), so the target's x axis, seen from above, is the world's x axis.
  // Without a target, "target" is the frame the problem was solved in (the initial guess's).
  std::vector<SE3d> control_poses;  // T_w_s (spline.csv)
  TrajectoryModel trajectory = TrajectoryModel::kSE3;  // their interpolation (the solve's)
  SE3Splined MakeSpline() const {
    return SE3Splined(control_poses, layout.t0_ns, layout.dt_ns, trajectory);
  }
  Eigen::Vector3d gravity_w = Eigen::Vector3d::Zero();       // (0, 0, -g)
  Eigen::Vector3d gravity_target = Eigen::Vector3d::Zero();  // the estimate, target frame
  SE3d T_w_target;                                           // target points into the world
  // Biases: constant, or the time average of the bias spline; std per axis (NaN if unknown).
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias_std =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d accel_bias_std =
      Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());

  // The IMU noise densities that weighted the last round: re-estimated from the residuals
  // (variance components) unless model.estimate_imu_noise is false.
  ImuNoiseEstimate imu_noise;
  double pixel_sigma_px = 1.0;  // the weight used in the last round
  bool pixel_sigma_estimated = false;
  double reprojection_rms_px = 0.0;  // all cameras
  double gyro_rms = 0.0;             // per-axis RMS of the IMU residuals [rad/s]
  double accel_rms = 0.0;            // [m/s^2]
  int num_landmarks = 0;
  int num_imu_samples = 0;
  double imu_rate_hz = 0.0;  // 1 / the median sample period (imu/imu_rate.h)

  // How the camera chain was used (CalibrateOptions::camera_chain, resolved).
  ParameterMode camera_chain = ParameterMode::kFree;
  // The target's scale against the IMU: the estimate with all else free and its std (NaN when
  // not estimated: kHeld, or no target), and the scale the result is in (1 unless kFree).
  TargetScaleMode target_scale_mode = TargetScaleMode::kHeld;
  double target_scale = std::numeric_limits<double>::quiet_NaN();
  double target_scale_std = std::numeric_limits<double>::quiet_NaN();
  double target_scale_used = 1.0;

  // The IMU's model (CalibrateOptions::imu_model): the estimate (the single IMU is the reference:
  // C_i_b = I, r_b = 0, time_offset 0) and its standard deviations (NaN for kCalibrated).
  ImuCalibration imu_model;
  ImuModelStd imu_model_std;
  // The joint covariance of the model's estimated entries (calib/imu_covariance.h: M_a, M_g, A,
  // C_gyro_i's phi [rad], ry_i, rz_i; held entries have no row); empty for kCalibrated or when
  // the covariance was not computed.
  ImuCovariance imu_model_covariance;
  // The further IMUs (CalibrateOptions::further_imus; empty with one IMU).
  std::vector<FurtherImuEstimate> further_imus;

  SolveSummary solve;  // rounds: the time windows were rebuilt or the pixel noise re-estimated
  // The largest factor by which a reported std exceeds the noise model's (the cluster-robust
  // covariances over robust_clusters time windows and over view_clusters kinds of target view,
  // estimation/view_clusters.h; 1: the noise model explains the scatter).
  double std_inflation = 1.0;
  int robust_clusters = 0;
  int view_clusters = 0;  // 0: that covariance not computed (too few kinds of view)
  double covariance_time_s = 0.0;
  double initialisation_time_s = 0.0;
  bool covariance_ok = false;
  std::vector<std::string> warnings;

  std::vector<ReprojectionSample> reprojection_samples;  // when keep_residuals
  std::vector<ImuResidualRecord> imu_samples;            // when keep_residuals
};

// Calibrates. `target` may be nullptr (natural landmarks only: then `guess` is required).
// Throws splinecal::Error as the file comment lists.
CalibrationResult Calibrate(const std::vector<ImuSample>& imu,
                            const std::vector<Observation>& observations,
                            const Camchain& camchain,
                            const CalibrationTarget* target,
                            const CalibrateOptions& options,
                            const CalibrationInitialGuess* guess = nullptr);

// The initial guess the target path computes (PnP per frame + `splinecal fit`), exposed for
// tests and diagnostics. Throws splinecal::Error like Calibrate.
CalibrationInitialGuess InitialGuessFromTarget(const std::vector<ImuSample>& imu,
                                               const std::vector<Observation>& observations,
                                               const Camchain& camchain,
                                               const CalibrationTarget& target,
                                               const CalibrateOptions& options,
                                               std::vector<std::string>* warnings);

// The initial guess from IMU poses T_w_s in the IMU clock (e.g. `splinecal align`'s
// aligned_poses.csv from SLAM poses, or a motion-capture trajectory mapped to the IMU): the
// continuous-time fit of those poses and the IMU (calib/fit.h) gives the trajectory, biases and
// gravity; T_cam_imu, the time offset and the line delay start from the camchain. This is the
// way to calibrate from natural landmarks alone. Throws splinecal::Error like Calibrate.
CalibrationInitialGuess InitialGuessFromImuPoses(const std::vector<ImuSample>& imu,
                                                 const std::vector<StampedPose>& poses,
                                                 const std::vector<Observation>& observations,
                                                 const Camchain& camchain,
                                                 const CalibrateOptions& options,
                                                 std::vector<std::string>* warnings);

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CALIBRATE_H_
