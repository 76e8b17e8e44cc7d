// Visual-inertial alignment: metric scale, gravity, velocities and gyro bias from camera poses
// known only up to scale (monocular SLAM / SfM) and IMU readings. splinecal's initial guess when
// no metric pose source exists; VINS-Mono's initialisation done right [Qin18] [seed001].
//
// Inputs: camera poses T_c0_c(t_k), k = 0..n-1 (the first camera frame c0 is the reference;
// positions up to an unknown scale s, so the metric position is s * p_c0_c), the IMU readings,
// T_cam_imu = T_c_s (CONVENTIONS.md). Frame k's IMU pose in c0:
//
//   R_c0_sk = R_c0_ck R_c_s,     p_c0_sk = s p_c0_ck + R_c0_ck t_c_s                       (1)
//
// Steps (docs/align.md explains each):
//   1. Preintegrate the gyro between consecutive frames; if asked, the camera-IMU rotation R_c_s
//      by hand-eye (calib/hand_eye.h), refused for rotation about one axis.
//   2. Gyro bias (and R_c_s when estimated) by Gauss-Newton on the relative rotations,
//          r_k = Log( dR_k(b_g)^T R_c_s^T R_ck_ck+1 R_c_s ),
//      re-preintegrating at every new bias until the step is below a tolerance.
//   3. Full preintegration (dp, dv, covariance) at that bias; for each pair k, with T_k the
//      interval, v_k the IMU velocity in c0 [m/s], g the gravity vector in c0 (CONVENTIONS.md:
//      points down, norm g), the residuals in s_k (calib/preintegration.h)
//          r_p = R_c0_sk^T (p_c0_sk+1 - p_c0_sk - v_k T_k - g T_k^2 / 2) - dp_k
//          r_v = R_c0_sk^T (v_k+1 - v_k - g T_k) - dv_k
//      are linear in (v_0..v_n-1, g, s) by (1). Weighted by the inverse covariance of (dp, dv),
//      solved in O(n) (block-tridiagonal elimination of the velocities, then a 4x4 system).
//   4. Gravity refinement with the known norm: g = |g| d, d on the unit sphere, 2 tangent
//      coordinates w (calib/gravity_tangent.h); at every iteration the system is REBUILT at the
//      current d (g ~ |g| d + |g| B(d) w), solved for (v, w, s), and d moved by w; stop when
//      |w| < tolerance. (VINS-Mono accumulates the rows of every iteration instead, which biases
//      the answer towards the first linearisation: internal::RefineGravityAccumulating.)
//   5. Acceptance checks that gate: scale > 0; | |g_free| - g | small; the (scaled) system
//      well conditioned. A failed check gives success = false and a plain-words message.
//   6. R_w_c0: the yaw-free rotation taking g_c0 to (0, 0, -g); aligned IMU states T_w_s.
//
// Accelerometer bias: not estimated (it is nearly inseparable from gravity over a short window,
// as in VINS-Mono); AlignOptions::accel_bias is used as known (default 0).
#ifndef SPLINECAL_CALIB_ALIGN_H_
#define SPLINECAL_CALIB_ALIGN_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "splinecal/calib/preintegration.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

struct AlignOptions {
  double gravity_m_s2 = 9.81;  // known gravity magnitude g [m/s^2]
  // T_cam_imu = T_c_s. Its rotation is the initial guess when estimate_rotation_extrinsic; its
  // translation is always used as known (metric).
  SE3d T_cam_imu;
  bool estimate_rotation_extrinsic = false;
  // Camera timestamps are in the camera's clock: t_imu = t_cam + timeshift (Kalibr).
  double timeshift_cam_imu_s = 0.0;
  ImuNoise noise;                                          // weights (Kalibr densities)
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();    // known [m/s^2]
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
  // Condition number of the scaled (v eliminated) system for gravity and scale: above this, the
  // motion did not excite scale and gravity (constant velocity, too little acceleration).
  double max_condition_number = 1e3;
  // Hand-eye refusal thresholds (calib/hand_eye.h).
  double min_hand_eye_second_axis_ratio = 0.1;
  double min_hand_eye_second_axis_rotation_rad = 0.05;
};

// The per-frame data of the linear problem.
struct AlignmentFrame {
  int64_t t_ns = 0;                                   // IMU time
  SO3d R_c0_c;                                        // camera rotation
  Eigen::Vector3d p_c0_c = Eigen::Vector3d::Zero();   // camera position, up to scale
};

// A solution of the linear or the refined problem.
struct AlignmentSolution {
  std::vector<Eigen::Vector3d> v_c0;                     // IMU velocity per frame, c0 [m/s]
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();  // [m/s^2]
  double scale = 0.0;
  // sqrt(lambda_max / lambda_min) of the gravity-scale system after eliminating the velocities
  // and scaling it to a unit diagonal; infinity when singular.
  double condition_number = 0.0;
  int iterations = 0;
  bool converged = false;
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
                   const ImuNoise& noise);

  // Step 3: velocities, free gravity (3 DoF) and scale.
  AlignmentSolution SolveFreeGravity() const;
  // Step 4: |g| = gravity_norm, starting from the direction of initial_gravity_c0.
  AlignmentSolution RefineGravity(const Eigen::Vector3d& initial_gravity_c0,
                                  double gravity_norm,
                                  double tolerance_rad,
                                  int max_iterations) const;

  int num_frames() const { return static_cast<int>(frames_.size()); }
  const std::vector<AlignmentFrame>& frames() const { return frames_; }
  const std::vector<ImuPreintegration>& preintegrations() const { return preintegrations_; }
  const SE3d& T_cam_imu() const { return T_cam_imu_; }

  // The weighted normal equations at a gravity model g = gravity_offset + gravity_basis * y_g
  // (y_g: 3 free coordinates or 2 tangent ones), solved for (v, y_g, s). Internal building block,
  // public for internal::RefineGravityAccumulating and tests.
  struct NormalEquations;
  NormalEquations Build(const Eigen::Vector3d& gravity_offset,
                        const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>& gravity_basis)
      const;

 private:
  std::vector<AlignmentFrame> frames_;
  SE3d T_cam_imu_;
  std::vector<ImuPreintegration> preintegrations_;  // pair k = frames k, k+1
  std::vector<Eigen::Matrix<double, 6, 6>> information_;  // inverse covariance of (dp, dv)
};

// Block-tridiagonal normal equations H x = b in x = (v_0..v_n-1, y), y = (y_g, s), m = |y| <= 4.
struct AlignmentProblem::NormalEquations {
  using MatrixY = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
  using Matrix3Y = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 4>;
  using VectorY = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 4, 1>;

  int m = 0;
  std::vector<Eigen::Matrix3d> D;  // H(v_k, v_k)
  std::vector<Eigen::Matrix3d> C;  // H(v_k, v_k+1)
  std::vector<Matrix3Y> H_vy;      // H(v_k, y), 3 x m
  MatrixY H_yy;                    // m x m
  std::vector<Eigen::Vector3d> b_v;
  VectorY b_y;

  // *this = factor * (*this + other) (same sizes): VINS-Mono's accumulation.
  void AccumulateScaled(const NormalEquations& other, double factor);
  // Solves for the velocities and y in O(n): block-tridiagonal elimination of the velocities,
  // then the m x m Schur complement S, scaled to a unit diagonal by H_yy's diagonal. Returns
  // the condition number sqrt(lambda_max / lambda_min) of the scaled S (infinity when singular;
  // then v and y are not meaningful).
  double Solve(std::vector<Eigen::Vector3d>* v, VectorY* y) const;
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

  double scale = 0.0;                                    // metric = scale * input positions
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();  // refined, |g| = options' g [m/s^2]
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // [rad/s]
  SO3d R_w_c0;
  SO3d R_cam_imu;                                        // estimated or the given one
  bool rotation_extrinsic_estimated = false;
  int iterations = 0;            // gravity refinement iterations
  int gyro_bias_iterations = 0;
  double condition_number = 0.0;  // of the refined system

  // The free-gravity (linear) solution, for diagnostics and comparisons.
  Eigen::Vector3d free_gravity_c0 = Eigen::Vector3d::Zero();
  double free_scale = 0.0;
  double free_condition_number = 0.0;
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
// basis of calib/gravity_tangent.h (VINS-Mono's own is 0/0 for gravity along -z).
AlignmentSolution RefineGravityAccumulating(const AlignmentProblem& problem,
                                            const Eigen::Vector3d& initial_gravity_c0,
                                            double gravity_norm,
                                            int iterations = 4);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_ALIGN_H_
