// Visual-inertial alignment: metric scale, gravity, velocities and gyro bias from camera poses
// known only up to scale (monocular SLAM / SfM) and IMU readings. splinecal's initial guess when
// no metric pose source exists; VINS-Mono's initialisation [Qin18, Sec. V] [seed001] without its
// defects (docs/align.md).
//
// Inputs: camera poses T_c0_c(t_k), k = 0..n-1 (the first camera frame c0 is the reference;
// positions p_bar up to an unknown scale s, metric = s * p_bar), the IMU readings, and
// T_cam_imu = T_c_s (docs/conventions.md "Camera, time offset, rolling shutter"). Frame k's IMU
// pose in c0:
//
//   R_c0_sk = R_c0_ck R_c_s,     p_c0_sk = s p_bar_k + l_k,   l_k = R_c0_ck t_c_s           (1)
//
// Steps (docs/align.md explains each):
//   1. If asked, the camera-IMU rotation R_c_s by hand-eye (vio/hand_eye.h) from the relative
//      camera rotations and the preintegrated gyro; refused for rotation about one axis.
//   2. Gyro bias (and R_c_s when estimated) by Gauss-Newton on the relative rotations,
//          r_k = Log( dR_k(b_g)^T R_c_s^T R_ck_ck+1 R_c_s ),
//      re-preintegrating at every new bias until the step is below a tolerance.
//   3. Full preintegration (dp, dv, covariance) at that bias. With T_k the interval, v_k the IMU
//      velocity in c0 and g the gravity vector in c0 (docs/conventions.md "IMU model": points
//      down, norm g), the preintegration model (vio/preintegration.h) and (1) give, per pair k,
//          s dp_bar_k + dl_k = v_k T + g T^2/2 + R_c0_sk dp_k,   v_k+1 - v_k = g T + R_c0_sk dv_k
//      We divide by s and solve for u = 1/s, v'_k = u v_k, g' = u g (camera units):
//          r_p = R_c0_sk^T (v'_k T + g' T^2/2 - u dl_k - dp_bar_k) + u dp_k
//          r_v = R_c0_sk^T (v'_k+1 - v'_k - g' T) - u dv_k
//      linear in (v'_0..v'_n-1, g', u), with the measured camera positions only on the right-hand
//      side. (VINS-Mono multiplies the positions by s instead; then their noise sits in the
//      matrix: an errors-in-variables problem that biases s towards 0 and makes a degenerate
//      motion look well conditioned. Without noise both are the same.) The rows are weighted by
//      the inverse of the preintegration covariance of (dp, dv) plus the camera pose noise
//      (CameraNoise), and solved in O(n): block-tridiagonal elimination of the velocities, then
//      a 4x4 system. s = 1/u, g = g'/u, v = v'/u.
//   4. Gravity refinement with the known norm G: g = G d, d on the unit sphere with 2 tangent
//      coordinates w (estimation/gravity_tangent.h), g' = u G Retract(d, w) ~ G d u + G u0 B(d) w.
//      At every iteration the system is REBUILT at the current (d, u0), solved for (v', w, u), d
//      moved by w; stop when |w| < tolerance. (VINS-Mono keeps adding each iteration's rows to
//      those linearised at older estimates: internal::RefineGravityAccumulating.)
//   5. Acceptance checks that gate: the free system's condition number (excitation), s > 0,
//      | |g_free| - G | small, the refinement converged with s > 0, and three checks of the
//      refined scale's uncertainty (docs/align.md, "Uncertainty"): its standard deviation from
//      the covariance of the weighted least-squares solution scaled by the residual-estimated
//      noise,
//          Cov(y) = chi2 / dof * (S^-1 + A Sigma_shared A^T),   sigma_s = s^2 sigma_u      (2)
//      (S the Schur complement of the camera-unit system, A = dy/dr the solution's rows for y;
//      the u^2 between camera and metric units cancels in (2)). Sigma_shared is the residual
//      covariance the per-pair weights leave out: a camera position enters two consecutive
//      pairs with opposite signs, and the accelerometer bias walk accumulated before a pair
//      enters every later pair (docs/align.md, "Uncertainty"). The result must be a small
//      fraction of s; the residuals must be of the size
//      of the assumed noise; and imposing the known norm must not move the scale away from the
//      free solution's by more than the uncertainties allow (an unmodelled accelerometer bias
//      along gravity does that). The accelerometer bias is also estimated, b'_a = u b_a as 3 more
//      unknowns (linear: u dp(b_a) ~ u dp + J_dp_ba b'_a), for the messages: a value to pass.
//      A failed check gives success = false and a plain-words message.
//   6. R_w_c0: the yaw-free rotation taking g_c0 to (0, 0, -G); the IMU states in that world.
//
// Accelerometer bias: not estimated (over a short window it is nearly inseparable from gravity,
// as in VINS-Mono); AlignOptions::accel_bias is used as known (default 0).
//
// References: [Qin18] T. Qin, P. Li, S. Shen, VINS-Mono, IEEE T-RO 2018; [seed001] the gravity
// refinement notes; [Forster17] preintegration.
#ifndef SPLINECAL_VIO_ALIGN_H_
#define SPLINECAL_VIO_ALIGN_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/vio/preintegration.h"

namespace splinecal {

// Noise of the camera poses, per frame and axis: part of the weights (docs/align.md, "Weights").
// Camera noise, not IMU noise, dominates the position rows: 5 mm per frame is ~100x the
// preintegrated position noise over 0.1 s, so weighting by the preintegration covariance alone
// trusts the position rows far too much against the velocity rows (in simulation, 2 s windows:
// gravity and scale errors 2.5x larger). The defaults suit monocular SLAM; overestimating the
// noise costs little accuracy.
struct CameraNoise {
  double position_std_m = 0.005;    // metric [m]
  double rotation_std_rad = 0.002;  // [rad] (0.11 deg)
};

struct AlignOptions {
  double gravity_m_s2 = kDefaultGravity;  // known gravity magnitude g [m/s^2]
  // T_cam_imu = T_c_s. Its rotation is the initial guess when estimate_rotation_extrinsic; its
  // translation is always used as known (metric).
  SE3d T_cam_imu;
  bool estimate_rotation_extrinsic = false;
  // Camera timestamps are in the camera's clock: t_imu = t_cam + time_offset_s (Kalibr's
  // timeshift_cam_imu).
  double time_offset_s = 0.0;
  ImuNoise noise;                                        // weights (Kalibr densities)
  CameraNoise camera_noise;                              // weights
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // known [m/s^2]
  Eigen::Vector3d initial_gyro_bias = Eigen::Vector3d::Zero();

  // Gyro bias: stop when the Gauss-Newton step is below this [rad/s] (1e-13 rad/s is ~1e-4 of
  // the rounding floor of a 0.1 s preintegration, so noise-free data converge to rounding).
  double gyro_bias_tolerance_rad_s = 1e-13;
  int max_gyro_bias_iterations = 30;
  // Gravity refinement: stop when the tangent step is below this [rad].
  double gravity_tolerance_rad = 1e-13;
  int max_gravity_iterations = 30;

  // Acceptance checks (docs/align.md, "Acceptance").
  // | |g_free| - g | must not exceed this [m/s^2]: 1.0 (~10%) is VINS-Mono's bound; a larger
  // error means wrong units, a wrong T_cam_imu or a time offset rather than noise.
  double max_gravity_norm_error_m_s2 = 1.0;
  // Condition number of the free system for (g', u) after eliminating the velocities, scaled to
  // a unit diagonal (NormalEquations::Solve). Above this the motion did not excite scale and
  // gravity. In simulation (docs/align.md, "Acceptance"; 10 s, 10 Hz, camera noise 5 mm and
  // 0.1 deg) constant velocity gives 5e3..1e4, 0.1 m/s^2 of acceleration change ~700 (scale
  // within 3%), 1 m/s^2 ~70 (0.3%); 1e3 refuses motion whose scale would be off by ~10% or more.
  double max_condition_number = 1e3;
  // The refined scale's standard deviation (2) relative to the scale must not exceed this: 5%
  // is what an initial guess for `fit` / `calibrate` tolerates (docs/align.md, "Uncertainty").
  double max_scale_relative_std = 0.05;
  // sqrt(chi2 / dof) of the metric residuals, i.e. how many times the assumed noise (camera
  // noise plus preintegrated IMU noise) the residuals are, must not exceed this. Larger means
  // unmodelled errors (accelerometer bias, vibration, a wrong time offset or extrinsic) that
  // the standard deviation cannot describe. Noise as assumed gives ~1.
  double max_residual_noise_ratio = 3.0;
  // Below this, a warning: the residuals are a fraction of the assumed noise, so the inputs are
  // more accurate than camera_noise (or the IMU densities) say, typically exact or filtered poses
  // with the default 5 mm. The weights then under-weight the IMU, and the standard deviation,
  // scaled by chi2 / dof as a whole, no longer describes the error: on exact simulated poses
  // with the defaults (ratio 0.31) the scale was 1.3% off at 5.9 standard deviations, and 0.03%
  // told the poses' noise (docs/align.md, "Uncertainty"). With the noise as assumed, the ratio
  // is 1 within a few percent (hundreds of degrees of freedom).
  double min_residual_noise_ratio = 0.5;
  // The refined scale minus the free one (the known norm moves an unmodelled accelerometer
  // bias along gravity into the scale, docs/align.md "Limits"): more than this many standard
  // deviations of their difference (the two variances added, conservative as the estimates
  // share data) is refused when the shift also exceeds max_scale_relative_std of the scale, and
  // a warning otherwise. 3 sigma: 0.3% false alarms for Gaussian noise.
  double max_accel_bias_scale_shift_sigmas = 3.0;
  // Hand-eye refusal thresholds (vio/hand_eye.h).
  double min_hand_eye_second_axis_ratio = 0.1;
  double min_hand_eye_second_axis_rotation_rad = 0.05;
};

// The per-frame data of the linear problem.
struct AlignmentFrame {
  int64_t t_ns = 0;                                  // IMU time
  SO3d R_c0_c;                                       // camera rotation
  Eigen::Vector3d p_c0_c = Eigen::Vector3d::Zero();  // camera position, up to scale
};

// A solution of the linear or the refined problem.
struct AlignmentSolution {
  std::vector<Eigen::Vector3d> v_c0;                     // IMU velocity per frame, c0 [m/s]
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();  // [m/s^2]
  double scale = 0.0;
  // sqrt(lambda_max / lambda_min) of the (gravity, u) system after eliminating the velocities
  // and scaling it to a unit diagonal; infinity when singular.
  double condition_number = 0.0;
  int iterations = 0;
  bool converged = false;
  // Uncertainty (align.h, step 5, equation (2)): the scale's standard deviation with the
  // residual-estimated noise, and sqrt(chi2 / dof) of the metric residuals (1 when the noise is
  // as assumed). 0 when the system is singular.
  double scale_std = 0.0;
  double residual_noise_ratio = 0.0;
  // SolveFreeGravityWithAccelBias only: the estimated accelerometer bias [m/s^2] (the
  // preintegration's plus the solved correction) and the standard deviation of each axis.
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias_std = Eigen::Vector3d::Zero();
};

// Steps 3-4 at a fixed gyro bias and extrinsic: the preintegrations and their weights.
class AlignmentProblem {
 public:
  // frames: at least 3, increasing times inside the IMU data (throws splinecal::Error).
  AlignmentProblem(const std::vector<ImuSample>& imu,
                   std::vector<AlignmentFrame> frames,
                   const SE3d& T_cam_imu,
                   const Eigen::Vector3d& gyro_bias,
                   const Eigen::Vector3d& accel_bias,
                   const ImuNoise& noise,
                   const CameraNoise& camera_noise = CameraNoise());

  // Step 3: velocities, free gravity (3 DoF) and scale.
  AlignmentSolution SolveFreeGravity() const;
  // Step 5's bias check: step 3 with the accelerometer bias as 3 more unknowns.
  AlignmentSolution SolveFreeGravityWithAccelBias() const;
  // Step 4: |g| = gravity_norm, starting from `initial` (its gravity direction and scale).
  AlignmentSolution RefineGravity(const AlignmentSolution& initial,
                                  double gravity_norm,
                                  double tolerance_rad,
                                  int max_iterations) const;

  int num_frames() const { return static_cast<int>(frames_.size()); }
  const std::vector<AlignmentFrame>& frames() const { return frames_; }
  const std::vector<ImuPreintegration>& preintegrations() const { return preintegrations_; }
  const SE3d& T_cam_imu() const { return T_cam_imu_; }

  // The weighted normal equations of step 3 for the gravity model
  //   g' = gravity_per_u * u + gravity_basis * y_g
  // (free: 0 and the identity; refinement: G d and G u0 B(d)), unknowns (v', y_g, u), or
  // (v', y_g, b'_a, u) with with_accel_bias (b'_a = u (b_a - the preintegration's b_a)).
  // Internal building block, public for internal::RefineGravityAccumulating and the tests.
  struct NormalEquations;
  NormalEquations Build(const Eigen::Vector3d& gravity_per_u,
                        const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>& gravity_basis,
                        bool with_accel_bias = false) const;

 private:
  std::vector<AlignmentFrame> frames_;
  SE3d T_cam_imu_;
  std::vector<ImuPreintegration> preintegrations_;        // pair k = frames k, k+1
  std::vector<Eigen::Matrix<double, 6, 6>> information_;  // inverse covariance of (dp, dv)
  double camera_position_variance_ = 0.0;                 // [m^2] per axis
  double accel_walk_variance_ = 0.0;                      // [m^2/s^5]
};

// Block-tridiagonal normal equations H x = b in x = (v'_0..v'_n-1, y), y = (y_g, [b'_a,] u),
// m = |y| <= 7; u is always y's last entry.
struct AlignmentProblem::NormalEquations {
  static constexpr int kMaxM = 7;
  using MatrixY = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxM, kMaxM>;
  using Matrix3Y = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxM>;
  using VectorY = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxM, 1>;

  int m = 0;
  std::vector<Eigen::Matrix3d> D;  // H(v_k, v_k)
  std::vector<Eigen::Matrix3d> C;  // H(v_k, v_k+1)
  std::vector<Matrix3Y> H_vy;      // H(v_k, y), 3 x m
  MatrixY H_yy;                    // m x m
  std::vector<Eigen::Vector3d> b_v;
  VectorY b_y;
  double rhs_weighted_sq = 0.0;  // sum of b^T W b over the pairs (for chi2)
  int num_rows = 0;              // 6 per pair

  // *this = factor * (*this + other) (same sizes): VINS-Mono's accumulation.
  void AccumulateScaled(const NormalEquations& other, double factor);
  // Solves for the velocities and y in O(n): block-tridiagonal elimination of the velocities,
  // then the m x m Schur complement S, scaled to a unit diagonal by H_yy's diagonal. Returns
  // the condition number sqrt(lambda_max / lambda_min) of the scaled S (infinity when singular;
  // then v and y are not meaningful). Optional outputs (nullptr: not wanted): S^-1, the
  // covariance of y if the pairs' residuals were independent with the weights' covariance;
  // chi2 = r^T W r at the solution (= b^T W b - x^T H x, as H x = b); the covariance of y
  // with the noise shared between pairs added (needs `pairs`, i.e. not after AccumulateScaled):
  //   S^-1 + sum_j A_y J^T W Sigma_shared W J A_y^T      (docs/align.md, "Uncertainty").
  double Solve(std::vector<Eigen::Vector3d>* v,
               VectorY* y,
               MatrixY* inverse_schur = nullptr,
               double* chi2 = nullptr,
               MatrixY* shared_noise_covariance = nullptr) const;
  int num_unknowns() const { return 3 * static_cast<int>(D.size()) + m; }

  // What the noise shared between pairs needs (Solve's shared_noise_covariance): per pair k,
  // J_k^T W_k ((6 + m) x 6: the rows of v'_k, v'_k+1, then y), R_c0_sk^T (a camera position
  // noise n enters r_p of pair k as +R^T n for frame k+1 and -R^T n for frame k, metric) and
  // the metric rows' derivative [J_dp_ba; -J_dv_ba] with respect to an accelerometer bias
  // offset, and the pair's duration [s]. Empty after AccumulateScaled.
  struct Pair {
    Eigen::Matrix<double, Eigen::Dynamic, 6, 0, 6 + kMaxM, 6> JtW;
    Eigen::Matrix3d Rt;
    Eigen::Matrix<double, 6, 3> d_rows_d_accel_bias;
    double duration_s = 0.0;
  };
  std::vector<Pair> pairs;
  double camera_position_variance = 0.0;  // [m^2] per axis
  double accel_walk_variance = 0.0;       // accelerometer random walk density^2 [m^2/s^5]
};

struct GyroBiasEstimate {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  SO3d R_cam_imu;
  int iterations = 0;
  bool converged = false;
  double rms_rotation_residual_rad = 0.0;  // after the last step
};

// Step 2: gyro bias from the relative rotations (and R_cam_imu when estimate_rotation, starting
// from R_cam_imu_initial). frames as in AlignmentProblem.
GyroBiasEstimate EstimateGyroBias(const std::vector<ImuSample>& imu,
                                  const std::vector<AlignmentFrame>& frames,
                                  const SO3d& R_cam_imu_initial,
                                  bool estimate_rotation,
                                  const AlignOptions& options);

// The yaw-free rotation R_w_c0 with R_w_c0 g_c0 = (0, 0, -|g_c0|): the smallest rotation doing
// that, followed by a rotation about world z removing its yaw (ZYX Euler yaw 0).
SO3d GravityAlignedRotation(const Eigen::Vector3d& gravity_c0);

struct AlignResult {
  bool success = false;
  std::string message;  // plain words: why it failed, or a summary
  std::vector<std::string> warnings;  // concerns that did not refuse the alignment

  double scale = 0.0;                                    // metric = scale * input positions
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();  // refined, |g| = options' g [m/s^2]
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // [rad/s]
  SO3d R_w_c0;
  SO3d R_cam_imu;  // estimated or the given one
  bool rotation_extrinsic_estimated = false;
  int iterations = 0;  // gravity refinement iterations
  int gyro_bias_iterations = 0;
  // The excitation measure (AlignmentProblem::ExcitationConditionNumber), gated.
  double condition_number = 0.0;
  // Uncertainty (step 5, gated): the refined scale's standard deviation and the residuals'
  // size relative to the assumed noise.
  double scale_std = 0.0;
  double residual_noise_ratio = 0.0;
  // The free solution with an estimated accelerometer bias (step 5's bias check).
  double scale_with_accel_bias = 0.0;
  double scale_with_accel_bias_std = 0.0;
  Eigen::Vector3d accel_bias_estimate = Eigen::Vector3d::Zero();  // [m/s^2]
  Eigen::Vector3d accel_bias_estimate_std = Eigen::Vector3d::Zero();

  // The free-gravity (linear) solution, for diagnostics and comparisons.
  Eigen::Vector3d free_gravity_c0 = Eigen::Vector3d::Zero();
  double free_scale = 0.0;
  double free_scale_std = 0.0;
  double free_condition_number = 0.0;     // of the free system with the measured positions
  double refined_condition_number = 0.0;  // of the refined system with the measured positions
  double hand_eye_second_axis_ratio = 0.0;
  double rms_rotation_residual_rad = 0.0;
  int num_ignored_frames = 0;  // camera poses outside the IMU data

  // Per used camera frame: the IMU state in the gravity-aligned world (metric, velocities, the
  // gyro bias, the assumed accel bias), IMU time base. World origin = c0's origin.
  std::vector<GroundTruthState> states_w;
};

// Runs steps 1-6 on camera poses T_c0_c (camera clock, up to scale; the first pose need not be
// the identity: poses are re-expressed relative to the first used one). Throws splinecal::Error
// for unusable input (fewer than 3 camera poses inside the IMU data); returns success = false
// with a message when an acceptance check fails.
AlignResult Align(const std::vector<ImuSample>& imu,
                  const std::vector<StampedPose>& camera_poses,
                  const AlignOptions& options);

namespace internal {

// VINS-Mono's refinement, kept for comparison (docs/align.md): 4 iterations, each adding its
// rows (linearised at the current gravity) to those of all earlier iterations, everything scaled
// by 1000 after each addition, so the first linearisation dominates. Uses the well-conditioned
// basis of estimation/gravity_tangent.h (VINS-Mono's own is 0/0 for gravity along -z).
AlignmentSolution RefineGravityAccumulating(const AlignmentProblem& problem,
                                            const AlignmentSolution& initial,
                                            double gravity_norm,
                                            int iterations = 4);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_VIO_ALIGN_H_
