// The further IMUs of a rig in `splinecal calibrate` (CalibrateOptions::further_imus; private to
// src/calib/): their parameter blocks (C_i_b, r_b, time offset, biases), initial guess,
// observability guard, model (FurtherImu::model), residuals (estimation/detail/further_imu_cost.h), standard deviations and
// results. The reference IMU (the first) stays SplineProblem's.
#ifndef SPLINECAL_SRC_CALIB_FURTHER_IMUS_H_
#define SPLINECAL_SRC_CALIB_FURTHER_IMUS_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/estimation/bias_spline.h"
#include "splinecal/estimation/detail/further_imu_cost.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/estimation/spline_problem.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace internal {

// A time offset that moved by more than this fraction of the knot spacing since the residuals
// were built has them rebuilt (further_imu_cost.h: u then leaves its segment).
constexpr double kFurtherImuRebuildFraction = 0.1;

// Refuses further IMUs the calibration cannot use: too few samples, timestamps not increasing,
// a rate more than 1% from the reference's (`reference_rate_hz`). Messages name the IMU.
void CheckFurtherImus(const std::vector<FurtherImu>& imus, double reference_rate_hz);

class FurtherImus {
 public:
  // The samples each IMU contributes: those whose stamp + any time offset in
  // [-max_time_offset_s, max_time_offset_s] lies inside the layout's valid range.
  FurtherImus(const std::vector<FurtherImu>& imus,
              const KnotLayout& layout,
              const BiasSpline& bias,
              TrajectoryModel model,
              double max_time_offset_s);

  bool empty() const { return imus_.empty(); }
  // The initial guess (calibrate.h, CalibrateOptions::further_imus) from the initial spline and
  // gravity; a failed correlation leaves the time offset at 0 with a warning.
  void Initialise(const SE3Splined& spline,
                  const Eigen::Vector3d& g_w,
                  std::vector<std::string>* warnings);
  // Holds at 0, with a warning, each lever arm whose std from the accelerometer information at
  // the current state exceeds max_std_m (the motion does not rotate enough to determine it).
  void HoldUndeterminedLeverArms(const SE3Splined& spline, double max_std_m,
                                 std::vector<std::string>* warnings);
  // Holds at nominal, with a warning naming the IMU and the parameters, each entry of a further
  // IMU's model that its residuals at the current state do not determine (the reference's guard,
  // estimation/imu_model_observability.h, on this IMU's own residuals).
  void HoldUndeterminedModelParameters(SplineProblem* spline, std::vector<std::string>* warnings);
  // Adds the blocks and residuals to spline->problem() (after spline->Reset()).
  void AddToProblem(SplineProblem* spline);
  // True when a time offset moved out of what the residuals were built for.
  bool NeedRebuild() const;
  // The blocks whose covariance is wanted, appended to `wanted` with their first row in
  // `offset`; *rows grows by their tangent sizes.
  void AddCovarianceBlocks(ceres::Problem* problem,
                           std::vector<const double*>* wanted,
                           std::map<const double*, int>* offset,
                           int* rows) const;
  // Fills the estimates (values, biases, residual RMS); then StdFrom adds the stds.
  void Collect(const SplineProblem& spline, std::vector<FurtherImuEstimate>* out) const;
  void StdFrom(const Eigen::MatrixXd& cov,
               const std::map<const double*, int>& offset,
               std::vector<FurtherImuEstimate>* out) const;

 private:
  struct State {
    std::string name;
    ImuNoise noise;
    double rate_hz = 0.0;
    double sigma_gyro = 1.0;
    double sigma_accel = 1.0;
    std::vector<ImuSample> samples;
    std::vector<double> gyro_bias;  // 3 per bias point
    std::vector<double> accel_bias;
    std::array<double, 4> q_i_b = {0.0, 0.0, 0.0, 1.0};
    Eigen::Vector3d r_b = Eigen::Vector3d::Zero();
    double time_offset_s = 0.0;
    double built_time_offset_s = 0.0;
    double initial_time_offset_s = 0.0;
    Eigen::Matrix3d initial_C_i_b = Eigen::Matrix3d::Identity();
    bool lever_arm_held = false;
    ImuModelKind kind = ImuModelKind::kCalibrated;
    ImuModelParameters model;  // its model's blocks, nominal initially (unused for calibrated)
    std::map<const double*, std::vector<int>> held_model;  // model entries held at nominal
  };
  // The model's blocks (further_imu_cost.h's order after the time offset; none for calibrated).
  static std::vector<double*> ModelBlocks(State* imu);
  // The residual segments of one IMU at its current time offset.
  std::vector<FurtherImuSegment> Segments(const State& imu) const;
  // The blocks of one segment's cost (further_imu_cost.h's order).
  std::vector<double*> Blocks(State* imu,
                              const FurtherImuSegment& segment,
                              const std::vector<double*>& control_blocks,
                              double* gravity) const;

  KnotLayout layout_;
  BiasSpline bias_;
  TrajectoryModel model_;
  double max_time_offset_s_;
  mutable std::vector<State> imus_;  // Collect evaluates through the blocks' addresses
  SO3Manifold so3_manifold_;
  std::shared_ptr<ceres::Manifold> time_offset_manifold_;
  std::vector<std::unique_ptr<ceres::Manifold>> held_manifolds_;  // of the current problem
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_FURTHER_IMUS_H_
