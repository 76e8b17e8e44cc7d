// SplineProblem: the estimation problem every continuous-time estimate of splinecal is built on
// (`fit`, `calibrate`, and a user's own). It owns the parameter blocks of the IMU trajectory --
// the control poses of T_w_s(t) (spline/se3_spline.h, SE3Manifold; interpolated by the coupled
// SE(3) or the split SO(3) x R^3 model, spline/trajectory_model.h), the bias model's control
// points (estimation/bias_spline.h) and gravity g_w (GravityManifold, |g_w| fixed) -- the
// ceres::Problem over them, and the evaluation callback that refreshes the spline's knot caches
// once per evaluation point (estimation/spline_evaluation_callback.h). It adds the IMU residuals
// (estimation/detail/imu_costs.h, docs/conventions.md "IMU model") and the bias random-walk prior
// (estimation/bias_costs.h):
//
//   minimise  sum_k |r_gyro,k|^2 + |r_accel,k|^2  +  sum_m |r_rw,m|^2  +  what the caller adds.
//
// A caller adds its own parameter blocks and residuals to problem() after Reset() -- pose
// residuals (fit), reprojection residuals (calibrate), anything else -- and solves it with
// estimation/solve_rounds.h; estimation/marginal_covariance.h gives the standard deviations.
//
//   SplineProblem spline_problem(layout, initial_control_poses, BiasSpline(), {});
//   spline_problem.SetGravity(g_w);
//   ceres::Problem& problem = spline_problem.Reset();
//   spline_problem.AddImuResiduals(imu, sigma_gyro, sigma_accel);
//   problem.AddResidualBlock(my_cost, nullptr, spline_problem.control_block(3), ...);
//
// Reset() starts a new ceres::Problem over the same values: callers whose residuals must be
// attached to other control poses after a solve (a time offset moved) rebuild with it.
#ifndef SPLINECAL_ESTIMATION_SPLINE_PROBLEM_H_
#define SPLINECAL_ESTIMATION_SPLINE_PROBLEM_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <unordered_map>
#include <vector>

#include "splinecal/estimation/bias_spline.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// The residuals' inputs (estimation/detail/imu_costs.h, estimation/detail/pose_cost.h).
struct ImuResidualSegment;
struct ImuResidualSample;
struct PoseResidualData;

// How the IMU residuals are handed to Ceres (the same objective either way).
enum class ImuResidualLayout {
  kPerSegment,  // one gyro and one accel block per spline segment (default, fastest)
  kPerSample,   // one gyro and one accel block per IMU sample
};

// Cost functions built in place of the analytic residuals (estimation/detail/imu_costs.h,
// estimation/detail/pose_cost.h), one block per IMU sample or pose; the caller of a factory owns
// what it returns. The tests and the benchmark give the automatic-differentiation twins
// (tests/testing/autodiff_costs.h) to compare whole problems with the analytic ones: the library
// itself holds no automatic differentiation of these residuals. gyro and accel go together.
struct ReplacementCosts {
  // bias_blocks: 1 (constant biases) or 4 (the bias spline's segment).
  std::function<ceres::CostFunction*(
      int bias_blocks, const ImuResidualSegment& segment, const ImuResidualSample& sample)>
      gyro, accel;
  std::function<ceres::CostFunction*(const PoseResidualData& data)> pose;  // fit's poses
};

// Implementation choices that do not change the objective (tests and benchmarks compare them).
struct ResidualOptions {
  ImuResidualLayout layout = ImuResidualLayout::kPerSegment;
  ReplacementCosts replacement;  // empty: the analytic costs
  // Share the knot caches between residuals through the evaluation callback (analytic only).
  bool share_knot_caches = true;
};

// The IMU model at one sample, at the problem's current values.
struct ImuPrediction {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // w_s + b_g
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // R^T (a_w - g_w) + b_a
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
};

// The residual blocks SplineProblem adds, by kind (the groups of variance components,
// estimation/variance_components.h).
enum class ImuResidualKind {
  kNotImu = -1,          // a caller's own residual
  kGyro = 0,             // AddImuResiduals
  kAccel = 1,            // AddImuResiduals
  kGyroRandomWalk = 2,   // AddBiasRandomWalkResiduals
  kAccelRandomWalk = 3,  // AddBiasRandomWalkResiduals
};
inline constexpr int kNumImuResidualKinds = 4;

// Residuals of the IMU samples at the problem's current values.
struct ImuResidualStatistics {
  double gyro_rms = 0.0;   // RMS per axis of measured - predicted [rad/s]
  double accel_rms = 0.0;  // [m/s^2]
  Eigen::Vector3d mean_gyro_bias = Eigen::Vector3d::Zero();   // time average over the samples
  Eigen::Vector3d mean_accel_bias = Eigen::Vector3d::Zero();
};

class SplineProblem {
 public:
  // control_poses: the initial T_w_s at the layout's knots (layout.num_control_poses of them),
  // interpolated by `trajectory` (the accelerometer residuals and Spline() follow it; a caller's
  // own residuals read it from trajectory_model()). Biases start at zero, gravity at
  // (0, 0, -9.81). Throws splinecal::Error on a size mismatch or an invalid layout.
  SplineProblem(const KnotLayout& layout,
                const std::vector<SE3d>& control_poses,
                const BiasSpline& bias,
                const ResidualOptions& options = {},
                TrajectoryModel trajectory = TrajectoryModel::kSE3);
  ~SplineProblem();
  SplineProblem(const SplineProblem&) = delete;
  SplineProblem& operator=(const SplineProblem&) = delete;

  const KnotLayout& layout() const { return layout_; }
  const BiasSpline& bias_spline() const { return bias_; }
  const ResidualOptions& residual_options() const { return options_; }
  TrajectoryModel trajectory_model() const { return trajectory_; }
  int num_control_poses() const { return layout_.num_control_poses; }

  // Parameter blocks (stable addresses for the object's lifetime).
  double* control_block(int i) { return control_blocks_[i]; }
  const std::vector<double*>& control_blocks() const { return control_blocks_; }
  double* gyro_bias(int m) { return &gyro_bias_values_[3 * m]; }
  double* accel_bias(int m) { return &accel_bias_values_[3 * m]; }
  const double* gyro_bias(int m) const { return &gyro_bias_values_[3 * m]; }
  const double* accel_bias(int m) const { return &accel_bias_values_[3 * m]; }
  double* gravity() { return gravity_.data(); }
  // The manifold of 7-parameter pose blocks {p, q}: a caller's own pose blocks use it too.
  SE3Manifold* se3_manifold() { return &se3_manifold_; }
  // The knot caches shared by the analytic residuals (nullptr when not shared).
  SplineEvaluationCallback* evaluation_callback() const { return callback_.get(); }

  // Kalibr's IMU model of the residuals (imu/imu_model_kind.h). kCalibrated, the default, is the
  // analytic residuals of estimation/detail/imu_costs.h; another model makes its parameters
  // (ImuModelParameters, at their current values) blocks of the problem at Reset() and
  // AddImuResiduals adds estimation/detail/imu_model_costs.h's residuals, one gyro and one accel block
  // per segment. Call Reset() after changing it.
  void SetImuModel(ImuModelKind kind) { imu_model_kind_ = kind; }
  ImuModelKind imu_model_kind() const { return imu_model_kind_; }
  ImuModelParameters* imu_model() { return &imu_model_; }
  const ImuModelParameters& imu_model() const { return imu_model_; }
  // The model's blocks in problem(), in the order m_a, m_g, a, phi_gyro_i (, ry_i, rz_i); empty
  // for kCalibrated.
  std::vector<double*> ImuModelBlocks();
  // Holds entry `index` of model block `block` at its nominal value from the next Reset() on (a
  // parameter the recording does not determine, estimation/imu_model_observability.h): the
  // block gets a ceres::SubsetManifold, or is constant when every entry is held.
  void HoldImuModelEntry(double* block, int index);
  // The held entries of `block`, increasing (its tangent skips them).
  std::vector<int> HeldImuModelEntries(const double* block) const;

  // Values.
  std::vector<SE3d> ControlPoses() const;
  void SetControlPoses(const std::vector<SE3d>& control_poses);  // same count; refreshes caches
  SE3Splined Spline() const;
  void SetBiases(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias);
  Eigen::Vector3d gravity_w() const { return Eigen::Map<const Eigen::Vector3d>(gravity_.data()); }
  void SetGravity(const Eigen::Vector3d& g_w);  // stored as given
  Eigen::Vector3d GyroBiasAt(int64_t t_ns) const;
  Eigen::Vector3d AccelBiasAt(int64_t t_ns) const;

  // A new ceres::Problem holding the control-pose, bias and gravity blocks (in that order) with
  // their manifolds; with hold_first_pose the first control pose is constant (the gauge when
  // nothing else fixes the world frame). The previous problem and its residuals are dropped.
  ceres::Problem& Reset(bool hold_first_pose = false);
  ceres::Problem& problem() { return *problem_; }

  // Gyro and accelerometer residuals of every sample in imu (inside the layout's valid range,
  // increasing times), weighted 1 / sigma per axis.
  void AddImuResiduals(const std::vector<ImuSample>& imu, double sigma_gyro, double sigma_accel);
  // The random-walk prior of the bias spline (nothing for a constant bias), Kalibr densities.
  void AddBiasRandomWalkResiduals(const ImuNoise& noise);

  // The sparse library for this problem's normal equations (estimation/solve_rounds.h): kEigen
  // with a bias spline, kSuiteSparse with constant biases.
  SparseLibrary PreferredSparseLibrary() const {
    return bias_.num_points() > 1 ? SparseLibrary::kEigen : SparseLibrary::kSuiteSparse;
  }
  // `solver` with kAuto resolved by PreferredSparseLibrary.
  SolverOptions ResolvedSolverOptions(SolverOptions solver) const {
    if (solver.sparse_library == SparseLibrary::kAuto) {
      solver.sparse_library = PreferredSparseLibrary();
    }
    return solver;
  }

  // Which of this object's residuals `id` is (kNotImu for the caller's own).
  ImuResidualKind ResidualKind(ceres::ResidualBlockId id) const;
  // The time window of `window_s` seconds (0, 1, ... from the layout's start) that residual
  // block `id` belongs to, by its first control-pose or bias block's knot time: the clusters of
  // the cluster-robust covariance (estimation/marginal_covariance.h). 0 for a residual with
  // neither.
  int TimeWindowOf(ceres::ResidualBlockId id, double window_s) const;

  // The IMU model at every sample (visit may be empty) and the residual statistics.
  ImuResidualStatistics EvaluateImu(
      const std::vector<ImuSample>& imu,
      const std::function<void(const ImuSample&, const ImuPrediction&)>& visit = {}) const;
  // d(mean bias over the samples) / d(control point m): the weights a reported average bias
  // gives each bias control point (all 1 for a constant bias).
  std::vector<double> MeanBiasWeights(const std::vector<ImuSample>& imu) const;
  // The same as a linear map (6 x 6 num_points): [mean gyro bias; mean accel bias] from the
  // tangent coordinates of every gyro bias point, then every accel bias point (the order a
  // covariance request lists them in; MarginalCovarianceOptions::reported_map).
  Eigen::MatrixXd MeanBiasMap(const std::vector<ImuSample>& imu) const;

 private:
  KnotLayout layout_;
  BiasSpline bias_;
  ResidualOptions options_;
  TrajectoryModel trajectory_;
  std::vector<double> control_values_;  // 7 per control pose
  std::vector<double*> control_blocks_;
  std::vector<double> gyro_bias_values_;   // 3 per control point
  std::vector<double> accel_bias_values_;
  std::array<double, 3> gravity_ = {0.0, 0.0, -kDefaultGravity};
  ImuModelKind imu_model_kind_ = ImuModelKind::kCalibrated;
  ImuModelParameters imu_model_;
  std::map<const double*, std::vector<int>> held_model_entries_;
  std::vector<std::unique_ptr<ceres::Manifold>> held_model_manifolds_;  // of the last Reset
  SE3Manifold se3_manifold_;
  GravityManifold gravity_manifold_;
  std::unique_ptr<SplineEvaluationCallback> callback_;
  std::unique_ptr<ceres::Problem> problem_;
  std::unordered_map<ceres::ResidualBlockId, ImuResidualKind> kinds_;  // of problem_'s blocks
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_SPLINE_PROBLEM_H_
