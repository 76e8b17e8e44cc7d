// Reprojection residuals of `splinecal calibrate` with analytic Jacobians: a calibration-target
// corner or an inverse-depth landmark, seen by a (rolling-shutter) camera riding on the IMU
// spline T_w_s(t) ([Lovegrove13 §4-5], [seed002], docs/conventions.md "Camera, time offset,
// rolling shutter").
//
// Model. A point is a homogeneous world point X_w = (x_w, w):
//   target corner p_t:      X_w = (R_w_t p_t + t_w_t, 1)                   (T_w_t estimated)
//   inverse-depth landmark: X_w = T_w_s(t_r) T_s_c (r, rho)                 [seed002]
//                           r = the reference observation's ray (x, y, 1) (camera model's
//                           Unproject), rho = 1 / depth in the reference camera, t_r the
//                           reference exposure time (its row is OBSERVED, so t_r is explicit:
//                           t_frame_r + time_offset + line_delay * v_r).
// Seen in a frame stamped t_frame (camera clock) at the exposure time (camera/rolling_shutter.h)
//   t = t_frame + time_offset + tau,   tau = line_delay * v(t),
// the point in the IMU and camera frames and the pixel are
//   x_s = R_w_s^T (x_w - p_w_s w),   x_c = R_c_s x_s + t_c_s w,   uv = pi(x_c)
// (pi = Camera::Project; a homogeneous point projects like x_c / w for w > 0, and
// rho -> 0 is a point at infinity, no division by rho anywhere). Residual, 2 rows per point:
//   r = (uv - uv_observed) / sigma_px,
// robustified per point inside the cost function by Huber's loss with threshold huber_px
// (below).
//
// T_w_s(t) follows ReprojectionOptions::model (spline/trajectory_model.h): the pose, its
// control-pose Jacobian J_T_k and the body twist xi are that model's; nothing else depends on it.
//
// Jacobians (RIGHT perturbation everywhere, lie/se3.h; tangent [rho; phi]). At fixed tau, with
// J_pi = d uv / d x_c (2x3), R = R_w_s, x_s, w as above:
//   T_w_s(t) -> T_w_s Exp(e):    d x_c / d e = R_c_s [-w I, [x_s]x]          (J_uv_e = J_pi that)
//   control pose k:              d uv / d d_k = J_uv_e J_T_k   (spline/segment_jacobians.h)
//   T_c_s -> T_c_s Exp(d):       d x_c / d d = R_c_s [w I, -[x_s]x] = -(d x_c / d e)
//   time (at fixed parameters):  d uv / dt = J_uv_e xi,  xi = [v_s; w_s] the body twist
//                                (T(t + h) = T(t) Exp(h xi))
//   world point:                 d x_c / d x_w = R_c_s R^T,  d x_c / d w = t_c_s - R_c_s R^T p_w_s
//   T_w_t -> T_w_t Exp(d):       d x_w / d d = R_w_t [I, -[p_t]x]
//   landmark, with x_sr = R_s_c r + t_s_c rho, x_w = R_w_sr x_sr + p_w_sr rho, w = rho:
//     reference pose T_w_sr Exp(e_r):   d x_w / d e_r = A_r = R_w_sr [rho I, -[x_sr]x]
//     reference time t_r:               d x_w / d t_r = A_r xi_r;  d t_r / d time_offset = 1,
//                                       d t_r / d line_delay = v_r (observed row)
//     T_c_s in T_s_c = T_c_s^-1:        d x_w / d d = R_w_sr [-rho I, [x_sr]x]
//     rho:                              d x_w / d rho = R_w_sr t_s_c + p_w_sr, d w / d rho = 1
// Then the rolling-shutter implicit function (camera/rolling_shutter.h): every partial above is
// multiplied by M; the line delay gets M dG/d line_delay + g_dot v / D; the time shift's
// partial is d uv / dt (plus the landmark's reference-time term).
// Control-pose, extrinsic and target-pose Jacobians are lifted to the ambient blocks
// {px, py, pz, qx, qy, qz, qw} exactly by estimation/detail/pose_block_jacobian.h, so
// ceres::GradientChecker agrees with them through SE3Manifold.
//
// Robust loss inside the cost function. Several points share one residual block (a frame's
// target corners), but Ceres' LossFunction acts on a whole block. So each point's 2-vector r is
// replaced by r' = f(|r|) r with f = 1 for |r| <= k and f = sqrt(2 k |r| - k^2) / |r| beyond
// (k = huber_px / sigma_px): |r'|^2 is Huber's rho(|r|^2) exactly, f is C^1 at |r| = k, and
// d r' / d r = f I + (f'(n) / n) r r^T (n = |r|) is chained into every Jacobian. huber_px = 0
// disables it.
//
// Time windows. The exposure time moves with the time shift and the line delay, so a residual
// holds the control poses of a WINDOW of time (ControlPoseWindow) wide enough for every exposure
// time the solver may try; an evaluation whose segment leaves the window returns false (Ceres
// then rejects the step) and the problem builder (calib/calibrate.h) rebuilds the windows when
// the estimates have moved. Frame times are relative to the spline's t0 in seconds, computed
// from int64 nanoseconds before conversion.
#ifndef SPLINECAL_ESTIMATION_REPROJECTION_COST_H_
#define SPLINECAL_ESTIMATION_REPROJECTION_COST_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/rolling_shutter.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// What every reprojection residual of one camera shares.
struct ReprojectionOptions {
  const Camera* camera = nullptr;  // not owned
  KnotLayout layout;  // only dt and n matter: residual times are seconds since t0
  TrajectoryModel model = TrajectoryModel::kSE3;  // the pose spline's
  double sigma_px = 1.0;  // pixel noise std [px]: residuals are divided by it
  double huber_px = 0.0;  // Huber threshold [px]; 0 = plain least squares
  ExposureSolveOptions exposure;
  // Optional knot caches for this evaluation point (not owned; may be nullptr).
  const SplineEvaluationCallback* shared = nullptr;
  // A camera held rigidly to a reference camera of the rig: the residual's T_cam_imu block is
  // the REFERENCE camera's, and this camera's is T_c_s = T_cam_cref * block. The right
  // perturbation of the block is the right perturbation of T_c_s (T_cam_cref B Exp(d) =
  // T_c_s Exp(d)), so every Jacobian below holds as written. Identity: the block is this
  // camera's own.
  SE3d T_cam_cref;
  // TargetFrameCostFunction only: the camera's intrinsics are a parameter block (the layout
  // of camera/camera_model.h) after T_w_t, and `camera` gives the model and the image size.
  // Their Jacobian is the camera model's d uv / d intrinsics at the exposure, times the
  // rolling-shutter correction M like every other partial at fixed tau.
  bool estimate_intrinsics = false;
};

// One observed target corner.
struct TargetCornerObservation {
  Eigen::Vector3d p_t = Eigen::Vector3d::Zero();  // corner in the target frame [m]
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();   // observed pixel [px]
};

// Every target corner of one frame: 2 rows per corner.
// Parameter blocks: window.num_poses control poses (7 each, first_index first), T_cam_imu (7),
// time offset (1) [s], line_delay (1) [s/row], T_w_t (7), and with
// ReprojectionOptions::estimate_intrinsics the intrinsics (kNumIntrinsics).
class TargetFrameCostFunction : public ceres::CostFunction {
 public:
  // t_frame_s: the frame stamp (camera clock) in seconds since the spline's t0.
  TargetFrameCostFunction(const ReprojectionOptions& settings,
                          const ControlPoseWindow& window,
                          double t_frame_s,
                          std::vector<TargetCornerObservation> corners);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const ControlPoseWindow& window() const { return window_; }
  double t_frame_s() const { return t_frame_s_; }
  const std::vector<TargetCornerObservation>& corners() const { return corners_; }

  // The frame linearised through the body pose, for a GLOBAL-shutter frame (line_delay 0):
  // every corner is seen at the same exposure time t, so its rows depend on the control poses,
  // T_cam_imu and the time offset only through the right perturbation e of T_w_s(t):
  //   d r / d control pose k = A J_T_k,   d r / d T_cam_imu = -A,   d r / d time offset = A xi
  // with A = d r / d e (2 rows per corner x 6; the Huber scaling S and 1/sigma included), J_T_k
  // the spline's control-pose Jacobian and xi = [v_s; w_s] the body twist (header comment).
  // G = [A | d r / d T_w_t (tangent, 6) | d r / d intrinsics (ambient)], the last two only when
  // asked for. False where Evaluate would fail, or when the line delay is not 0.
  struct GlobalShutterLinearization {
    Eigen::VectorXd r;  // the residuals Evaluate returns
    Eigen::MatrixXd G;
    ControlPoseJacobian<6> J_pose;
    Eigen::Matrix<double, 6, 1> xi;
  };
  bool LinearizeGlobalShutter(double const* const* parameters,
                              bool with_target_pose,
                              bool with_intrinsics,
                              GlobalShutterLinearization* out) const;

 private:
  ReprojectionOptions settings_;
  ControlPoseWindow window_;
  double t_frame_s_;
  std::vector<TargetCornerObservation> corners_;
};

// One inverse-depth landmark: its reference observation and one later (or earlier) observation.
struct LandmarkObservation {
  double t_reference_frame_s = 0.0;  // reference frame stamp, seconds since t0 (camera clock)
  Eigen::Vector3d ray = Eigen::Vector3d(0.0, 0.0, 1.0);  // reference ray (x, y, 1)
  double reference_row = 0.0;  // observed v of the reference observation [px]
  double t_frame_s = 0.0;      // observing frame stamp, seconds since t0 (camera clock)
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // observed pixel [px]
};

// 2 rows. Parameter blocks: the control poses listed in pose_indices (sorted, unique; they must
// contain both windows), T_cam_imu (7), time offset (1), line_delay (1), rho (1) [1/m].
class LandmarkCostFunction : public ceres::CostFunction {
 public:
  LandmarkCostFunction(const ReprojectionOptions& settings,
                       std::vector<int> pose_indices,
                       const LandmarkObservation& observation);

  // The sorted union of the two windows' control-pose indices.
  static std::vector<int> UnionOfWindows(const ControlPoseWindow& a, const ControlPoseWindow& b);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const std::vector<int>& pose_indices() const { return pose_indices_; }

 private:
  ReprojectionOptions settings_;
  std::vector<int> pose_indices_;
  LandmarkObservation observation_;
};

namespace internal {

// Pose and body twist of the IMU at one time.
struct BodyState {
  SE3d T_w_s;
  Eigen::Vector3d w_s = Eigen::Vector3d::Zero();  // body angular velocity [rad/s]
  Eigen::Vector3d v_s = Eigen::Vector3d::Zero();  // R_w_s^T dp_w_s/dt [m/s]
};

BodyState EvaluateBodyState(TrajectoryModel model,
                            const SegmentKnots<double>& knots,
                            const Segment<double>& segment);

// The projection of X_w = (x_w, w) from the body state through T_c_s, with what the Jacobians
// need (file comment).
struct PointProjection {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector2d uv_dot = Eigen::Vector2d::Zero();  // d uv / dt [px/s]
  Eigen::Matrix<double, 2, 6> J_uv_e;                // right tangent of T_w_s(t)
  Eigen::Matrix<double, 2, 3> J_uv_xw;               // d uv / d x_w
  Eigen::Vector2d J_uv_w = Eigen::Vector2d::Zero();  // d uv / d w
};

// False when the point is not in front of the camera. Jacobians only when with_jacobians
// (uv_dot always).
bool ProjectPoint(const Camera& camera,
                  const SE3d& T_c_s,
                  const BodyState& state,
                  const Eigen::Vector3d& x_w,
                  double w,
                  bool with_jacobians,
                  PointProjection* projection);

// Huber inside the cost function (file comment): r <- f r and, if J_scale is not null, the 2x2
// factor d r' / d r.
void RobustifyPoint(double k, Eigen::Vector2d* r, Eigen::Matrix2d* J_scale);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_REPROJECTION_COST_H_
