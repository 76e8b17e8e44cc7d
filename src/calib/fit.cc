#include "splinecal/calib/fit.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>
#include <glog/logging.h>

#include <Eigen/SVD>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>
#include <sstream>
#include <utility>

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/vio/hand_eye.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/estimation/interval_manifold.h"
#include "splinecal/estimation/detail/pose_cost.h"
#include "splinecal/estimation/solver_progress.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/estimation/spline_problem.h"
#include "fit_uncertainty.h"
#include "splinecal/error.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/memory_reuse.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"
#include "splinecal/estimation/knot_spacing.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/vio/time_offset_correlation.h"

namespace splinecal {

namespace {

// The data must span at least this many knot intervals, and hold at least this many poses.
constexpr int kMinKnotIntervals = 4;
constexpr int kMinPoses = 3;

// Units checks: RMS angular speeds below this [rad/s] are too slow to compare; the ratio of gyro
// to pose rotation rate, and of the mean specific force to g, must lie within these bounds.
constexpr double kMinRateForUnitsCheck = 0.05;
constexpr double kMaxRateRatio = 3.0;
constexpr double kMaxGravityRatio = 1.4;

// Residual RMS above this many noise stds draws a warning.
constexpr double kWarnResidualNoiseRatio = 3.0;

// A time offset within this fraction of the search range's edge is "at the edge".
constexpr double kEdgeFraction = 0.01;
// A re-estimated IMU noise weight that moved by more than this fraction triggers another round.
constexpr double kNoiseChangeForNewRound = 0.1;
// Jacobian entries (8 bytes each) above which fit returns freed memory to the system between its
// phases: 2e6 (16 MB of Jacobian values, about 45 s of 200 Hz IMU at 0.1 s knots), a quarter of
// where calibrate and fit switch to SPARSE_SCHUR for memory (SolverOptions). Below it the next
// allocations reuse the few tens of MB anyway, and faulting them back in cost more than the trim
// saved (120 fits of 20 s in a Monte-Carlo test: docs/performance.md, "The slow tests' CPU time").
constexpr double kTrimAboveJacobianEntries = 2e6;

SE3d PoseOf(const StampedPose& pose) { return SE3d(SO3d::FromQuaternion(pose.q), pose.p); }

void CheckIncreasing(const std::vector<ImuSample>& imu, const std::vector<StampedPose>& poses) {
  if (imu.size() < 2)
    throw Error("needs at least 2 IMU samples, got " + std::to_string(imu.size()));
  if (poses.size() < 2) {
    throw Error("needs at least 2 poses, got " + std::to_string(poses.size()));
  }
  for (size_t k = 1; k < imu.size(); ++k) {
    if (imu[k].t_ns <= imu[k - 1].t_ns) {
      throw Error("IMU timestamps must increase strictly (sample " + std::to_string(k) + ")");
    }
  }
  for (size_t k = 1; k < poses.size(); ++k) {
    if (poses[k].t_ns <= poses[k - 1].t_ns) {
      throw Error("pose timestamps must increase strictly (pose " + std::to_string(k) + ")");
    }
  }
}

void CheckOptions(const FitOptions& o) {
  CheckSplineModelOptions(o.model);
  CheckSolverOptions(o.solver);
  auto positive = [](double value, const std::string& name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw Error(name + " must be a positive number, got " + std::to_string(value));
    }
  };
  positive(o.pose_sigma_m, "pose sigma [m]");
  positive(o.pose_sigma_rad, "pose sigma [rad]");
  if (!std::isfinite(o.time_offset_s)) throw Error("time offset must be finite");
  if (o.estimate_time_offset) {
    positive(o.max_time_offset_s, "max time offset");
    if (std::abs(o.time_offset_s) >= o.max_time_offset_s) {
      throw Error("the initial time offset " + StringPrintf("%.6g", o.time_offset_s) +
                  " s is outside the search range +-" + StringPrintf("%.6g", o.max_time_offset_s) +
                  " s");
    }
  }
  if (o.initial_gravity_w.has_value() &&
      !(o.initial_gravity_w->norm() > 0.0 && o.initial_gravity_w->allFinite())) {
    throw Error("the initial gravity vector must be finite and nonzero");
  }
  positive(o.max_residual_noise_ratio, "max residual/noise ratio");
}

// Product of the gyro's rotations over [a_ns, b_ns] (IMU clock), piecewise constant rates with
// exact exponentials; bias not removed (used for initial guesses only).
SO3d IntegrateGyro(const std::vector<ImuSample>& imu, int64_t a_ns, int64_t b_ns) {
  SO3d R;
  auto it = std::upper_bound(
      imu.begin(), imu.end(), a_ns, [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  size_t k = it == imu.begin() ? 0 : static_cast<size_t>(it - imu.begin()) - 1;
  int64_t t = a_ns;
  while (t < b_ns && k < imu.size()) {
    const int64_t next = k + 1 < imu.size() ? std::min(imu[k + 1].t_ns, b_ns) : b_ns;
    if (next > t) R = R * SO3d::Exp(imu[k].gyro * (1e-9 * static_cast<double>(next - t)));
    t = next;
    ++k;
  }
  return R;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

// ---------------------------------------------------------------------------------------------

struct FitProblem::Impl {
  FitOptions options;
  std::vector<ImuSample> imu;      // samples inside the spline's valid range
  std::vector<StampedPose> poses;  // every input pose (pose clock)
  std::vector<int> used_poses;     // indices into poses with residuals
  std::vector<int> pose_segments;  // attached segment of each used pose
  double imu_rate_hz = 0.0;
  double sigma_g = 0.0;  // the given densities' per-sample stds (the residual checks use them)
  double sigma_a = 0.0;
  std::unique_ptr<ImuNoiseEstimator> imu_noise;  // the weights, measured from the residuals
  KnotLayout layout;
  double dt_s = 0.0;
  std::string knot_rule;
  std::vector<std::string> warnings;

  // Declared before the problem that refers to it, so that it outlives it.
  std::unique_ptr<IntervalManifold> time_offset_manifold;  // [-max, max] when estimated
  std::unique_ptr<SplineProblem> spline_problem;  // control poses, biases, gravity
  double time_offset = 0.0;
  std::array<double, 7> extrinsic = {0, 0, 0, 0, 0, 0, 1};

  // Diagnostics for failure messages.
  double gyro_rate_ratio = 1.0;
  double correlation_offset_s = std::numeric_limits<double>::quiet_NaN();
  bool correlation_at_edge = false;

  int num_control_poses() const { return layout.num_control_poses; }
  ceres::Problem* problem() const { return &spline_problem->problem(); }

  double PoseTimeSinceT0(int pose_index) const {
    return 1e-9 * static_cast<double>(poses[pose_index].t_ns - layout.t0_ns);
  }

  void Initialise(const std::vector<ImuSample>& all_imu, const std::vector<StampedPose>& all_poses);
  void BuildProblem();
  void AddImuResiduals();
  void AddPoseResiduals();
  FitResult Solve();
  std::string LikelyCauses(double gyro_ratio, double accel_ratio) const;
  void ComputeCovariance(FitResult* result);
};

void FitProblem::Impl::Initialise(const std::vector<ImuSample>& all_imu,
                                  const std::vector<StampedPose>& all_poses) {
  CheckOptions(options);
  CheckIncreasing(all_imu, all_poses);
  poses = all_poses;
  imu_rate_hz = ImuRateHz(all_imu);
  sigma_g = options.model.noise.GyroWhiteStd(imu_rate_hz);
  sigma_a = options.model.noise.AccelWhiteStd(imu_rate_hz);
  imu_noise =
      std::make_unique<ImuNoiseEstimator>(options.model.noise, imu_rate_hz, options.model.imu_noise);
  if (options.model.noise.update_rate_hz > 0.0 &&
      std::abs(options.model.noise.update_rate_hz - imu_rate_hz) > 0.1 * imu_rate_hz) {
    warnings.push_back("the IMU file's sample rate is " + StringPrintf("%.1f", imu_rate_hz) +
                       " Hz but the noise file says " +
                       StringPrintf("%.1f", options.model.noise.update_rate_hz) +
                       " Hz; the weights use the measured rate");
  }

  // Time offset: the correlation of angular speeds (an initial guess when estimated, a check
  // otherwise).
  time_offset = options.time_offset_s;
  {
    const double range = options.estimate_time_offset ? options.max_time_offset_s : 0.1;
    double offset = 0.0;
    bool at_edge = false;
    if (EstimateTimeOffsetByCorrelation(all_imu,
                                        all_poses,
                                        options.estimate_time_offset ? 0.0 : time_offset,
                                        range,
                                        &offset,
                                        &at_edge)) {
      correlation_offset_s = offset;
      correlation_at_edge = at_edge;
      if (options.estimate_time_offset) {
        if (at_edge) {
          throw Error(
              "the time offset between IMU and poses appears to be beyond the search "
              "range +-" +
              StringPrintf("%.3g", options.max_time_offset_s) +
              " s (the best alignment of gyro and pose rotation rates is at its edge): "
              "raise --max-time-offset or check that both files use the same clock");
        }
        time_offset = offset;
      } else if (std::abs(offset - time_offset) > 2.5 / imu_rate_hz && !at_edge) {
        warnings.push_back(
            "the gyro and the poses' rotation rates line up best with a time "
            "offset of " +
            StringPrintf("%.1f", 1e3 * offset) + " ms, not the " +
            StringPrintf("%.1f", 1e3 * time_offset) + " ms used: consider --estimate-time-offset");
      }
    }
  }

  // Overlap of the IMU and the poses (shifted onto the IMU clock).
  const int64_t offset_ns = std::llround(time_offset * 1e9);
  const int64_t margin_ns =
      options.estimate_time_offset ? std::llround(options.max_time_offset_s * 1e9) : 0;
  const int64_t imu_start = all_imu.front().t_ns;
  const int64_t imu_end = all_imu.back().t_ns;
  const int64_t pose_start = all_poses.front().t_ns + offset_ns;
  const int64_t pose_end = all_poses.back().t_ns + offset_ns;
  const int64_t start = std::max(imu_start, pose_start);
  const int64_t end = std::min(imu_end, pose_end);
  if (end <= start) {
    std::ostringstream message;
    message.precision(12);
    message << "the IMU data [" << 1e-9 * imu_start << ", " << 1e-9 * imu_end
            << "] s and the poses [" << 1e-9 * pose_start << ", " << 1e-9 * pose_end
            << "] s (IMU clock, time offset " << time_offset
            << " s) do not overlap: the files are from different recordings or use different "
               "time bases (seconds vs nanoseconds, another clock origin); the gap is "
            << 1e-9 * static_cast<double>(pose_end < imu_start ? imu_start - pose_end
                                                               : pose_start - imu_end)
            << " s";
    throw Error(message.str());
  }

  // Knot spacing.
  std::vector<ImuSample> overlap_imu;
  for (const ImuSample& s : all_imu) {
    if (s.t_ns >= start && s.t_ns <= end) overlap_imu.push_back(s);
  }
  if (overlap_imu.size() < 2) {
    throw Error("fewer than 2 IMU samples fall inside the pose data's time range");
  }
  if (options.model.knot_spacing_s > 0.0) {
    dt_s = options.model.knot_spacing_s;
    knot_rule = "given (--knot-spacing)";
  } else {
    dt_s = ChooseKnotSpacing(overlap_imu, options.model.noise, &knot_rule);
  }
  const int64_t dt_ns = std::llround(dt_s * 1e9);
  dt_s = 1e-9 * static_cast<double>(dt_ns);
  if (static_cast<double>(dt_ns) < 2e9 / imu_rate_hz * (1.0 - 1e-6)) {
    throw Error("knot spacing " + StringPrintf("%.6g", dt_s) + " s is below two IMU periods (" +
                StringPrintf("%.6g", 2.0 / imu_rate_hz) +
                " s): some segments would hold no IMU data");
  }
  const double overlap_s = 1e-9 * static_cast<double>(end - start);
  const int64_t min_span_ns = kMinKnotIntervals * dt_ns + 2 * margin_ns;
  int poses_inside = 0;
  for (const StampedPose& p : all_poses) {
    const int64_t t = p.t_ns + offset_ns;
    if (t - margin_ns >= start && t + margin_ns <= end) ++poses_inside;
  }
  if (end - start < min_span_ns || poses_inside < kMinPoses) {
    throw Error(
        "the data is too short for knot spacing " + StringPrintf("%.6g", dt_s) +
        " s: " + StringPrintf("%.6g", overlap_s) + " s of overlapping IMU and pose data with " +
        std::to_string(poses_inside) + " poses inside; needs at least " +
        StringPrintf("%.6g", 1e-9 * static_cast<double>(min_span_ns)) + " s (" +
        std::to_string(kMinKnotIntervals) + " knot intervals" +
        (margin_ns > 0 ? " plus the time-offset search range at both ends" : "") + ") and " +
        std::to_string(kMinPoses) + " poses: record longer or use a smaller --knot-spacing");
  }
  layout = KnotLayoutCovering(start, end, dt_ns);
  imu = std::move(overlap_imu);

  // Poses with residuals: inside [t_1, t_{n-2}] for every offset in the search range.
  const int64_t t_first = layout.t0_ns + layout.dt_ns;
  const int64_t t_last = layout.t0_ns + static_cast<int64_t>(layout.num_control_poses - 2) * dt_ns;
  for (size_t j = 0; j < poses.size(); ++j) {
    const int64_t t = poses[j].t_ns + offset_ns;
    if (t - margin_ns >= t_first && t + margin_ns <= t_last)
      used_poses.push_back(static_cast<int>(j));
  }

  // Extrinsic: the given value, its rotation from hand-eye when estimated.
  SE3d T_m_s = options.T_m_s;
  if (options.estimate_extrinsic) {
    std::vector<SO3d> R_m_pairs;
    std::vector<SO3d> R_s_pairs;
    constexpr int64_t kMinPairSpacingNs = 200'000'000;  // 0.2 s: rotations well above noise
    size_t a = 0;
    for (size_t b = 1; b < poses.size(); ++b) {
      if (poses[b].t_ns - poses[a].t_ns < kMinPairSpacingNs) continue;
      const int64_t ta = poses[a].t_ns + offset_ns;
      const int64_t tb = poses[b].t_ns + offset_ns;
      if (ta >= imu.front().t_ns && tb <= imu.back().t_ns) {
        R_m_pairs.push_back(SO3d::FromQuaternion(poses[a].q).inverse() *
                            SO3d::FromQuaternion(poses[b].q));
        R_s_pairs.push_back(IntegrateGyro(imu, ta, tb));
      }
      a = b;
    }
    const HandEyeRotationResult hand_eye = EstimateHandEyeRotation(R_m_pairs, R_s_pairs);
    if (hand_eye.ok) {
      T_m_s = SE3d(hand_eye.R_cam_imu, T_m_s.translation());
    } else {
      warnings.push_back("the extrinsic rotation could not be initialised by hand-eye (" +
                         hand_eye.message + "); starting from the given T_pose_imu");
    }
  }
  PoseToBlock(T_m_s, extrinsic.data());

  // Control poses: least squares on the poses mapped to the IMU (T_w_s = T_w_m T_m_s) and clock.
  std::vector<StampedPose> imu_poses(poses.size());
  for (size_t j = 0; j < poses.size(); ++j) {
    const SE3d T_w_s = PoseOf(poses[j]) * T_m_s;
    imu_poses[j].t_ns = poses[j].t_ns + offset_ns;
    imu_poses[j].p = T_w_s.translation();
    imu_poses[j].q = T_w_s.so3().quaternion();
  }
  PoseFitOptions pose_fit_options;
  pose_fit_options.rotation_weight_m_per_rad = options.pose_sigma_m / options.pose_sigma_rad;
  pose_fit_options.num_threads = options.solver.num_threads;
  pose_fit_options.trajectory = options.model.trajectory;
  const PoseFitResult initial = FitControlPoses(imu_poses, layout, pose_fit_options);
  spline_problem = std::make_unique<SplineProblem>(
      layout,
      initial.control_poses,
      BiasSpline(options.model.bias_model, layout, options.model.bias_knot_spacing_s),
      options.residuals,
      options.model.trajectory);
  const SE3Splined spline = spline_problem->Spline();

  // Units: gyro against the poses' rotation rate; mean specific force against g.
  double gyro_sq = 0.0;
  double pose_sq = 0.0;
  Eigen::Vector3d mean_Rf = Eigen::Vector3d::Zero();
  for (const ImuSample& s : imu) {
    const Segment<double> seg = spline.SegmentAtNs(s.t_ns);
    SE3d T_w_s;
    Eigen::Vector3d w_s;
    spline.Evaluate(seg, &T_w_s, &w_s);
    gyro_sq += s.gyro.squaredNorm();
    pose_sq += w_s.squaredNorm();
    mean_Rf += T_w_s.so3() * s.accel;
  }
  const double gyro_rms = std::sqrt(gyro_sq / imu.size());
  const double pose_rms = std::sqrt(pose_sq / imu.size());
  if (pose_rms > kMinRateForUnitsCheck) {
    gyro_rate_ratio = gyro_rms / pose_rms;
    if (gyro_rate_ratio > kMaxRateRatio || gyro_rate_ratio < 1.0 / kMaxRateRatio) {
      std::string hint;
      if (gyro_rate_ratio > 40.0 && gyro_rate_ratio < 80.0) {
        hint = ": the gyro seems to be in deg/s (use --gyro-unit deg/s)";
      } else if (gyro_rate_ratio > 1.0 / 80.0 && gyro_rate_ratio < 1.0 / 40.0) {
        hint = ": the gyro seems to be in rad/s but was read as deg/s (--gyro-unit rad/s)";
      } else {
        hint = ": wrong gyro units, or the poses are not this IMU's trajectory";
      }
      throw Error("the gyro's rotation rate (RMS " + StringPrintf("%.4g", gyro_rms) +
                  " rad/s) and the poses' (RMS " + StringPrintf("%.4g", pose_rms) +
                  " rad/s) differ by a factor " + StringPrintf("%.3g", gyro_rate_ratio) + hint);
    }
  }
  mean_Rf /= static_cast<double>(imu.size());
  // Mean world acceleration over the overlap: (v_end - v_start) / duration.
  Eigen::Vector3d v_start;
  Eigen::Vector3d v_end;
  SE3d ignored;
  spline.Evaluate(spline.SegmentAtNs(imu.front().t_ns), &ignored, nullptr, nullptr, &v_start);
  spline.Evaluate(spline.SegmentAtNs(imu.back().t_ns), &ignored, nullptr, nullptr, &v_end);
  const double duration = 1e-9 * static_cast<double>(imu.back().t_ns - imu.front().t_ns);
  const Eigen::Vector3d mean_a =
      duration > 0.0 ? Eigen::Vector3d((v_end - v_start) / duration) : Eigen::Vector3d::Zero();
  const Eigen::Vector3d g_estimate = mean_a - mean_Rf;  // f = R^T (a - g)  =>  g = a - R f
  const double g_ratio = g_estimate.norm() / options.model.gravity_m_s2;
  if (g_ratio > kMaxGravityRatio || g_ratio < 1.0 / kMaxGravityRatio) {
    std::string hint = ": wrong accelerometer units or a wrong --gravity";
    if (g_ratio > 1.0 / 12.0 && g_ratio < 1.0 / 8.0) {
      hint = ": the accelerometer seems to be in units of g (use --accel-unit g)";
    }
    throw Error("the mean specific force in the world frame has magnitude " +
                StringPrintf("%.4g", g_estimate.norm()) + " m/s^2 but gravity is " +
                StringPrintf("%.4g", options.model.gravity_m_s2) + " m/s^2" + hint);
  }
  Eigen::Vector3d g_init =
      options.initial_gravity_w.has_value() ? *options.initial_gravity_w : g_estimate;
  g_init = options.model.gravity_m_s2 * g_init.normalized();
  spline_problem->SetGravity(g_init);
  spline_problem->SetBiases(options.initial_gyro_bias, options.initial_accel_bias);
  BuildProblem();
}

void FitProblem::Impl::BuildProblem() {
  ceres::Problem& problem = spline_problem->Reset();
  problem.AddParameterBlock(extrinsic.data(), 7, spline_problem->se3_manifold());
  if (options.estimate_time_offset) {
    // The interval is kept by the block's Plus, not by Ceres' bounds
    // (estimation/interval_manifold.h: bounds would double the Jacobian evaluations).
    if (!time_offset_manifold) {
      time_offset_manifold = std::make_unique<IntervalManifold>(-options.max_time_offset_s,
                                                                options.max_time_offset_s);
    }
    problem.AddParameterBlock(&time_offset, 1, time_offset_manifold.get());
  } else {
    problem.AddParameterBlock(&time_offset, 1);
    problem.SetParameterBlockConstant(&time_offset);
  }
  if (!options.estimate_extrinsic) problem.SetParameterBlockConstant(extrinsic.data());
  spline_problem->AddImuResiduals(imu, imu_noise->gyro_sigma(), imu_noise->accel_sigma());
  AddPoseResiduals();
  spline_problem->AddBiasRandomWalkResiduals(imu_noise->densities());
}

void FitProblem::Impl::AddPoseResiduals() {
  pose_segments.clear();
  for (int j : used_poses) {
    PoseResidualData data;
    data.t_s = PoseTimeSinceT0(j);
    data.segment_index = layout.ClampedSegmentAt(data.t_s + time_offset);
    data.dt_s = dt_s;
    data.T_w_m = PoseOf(poses[j]);
    data.sigma_m = options.pose_sigma_m;
    data.sigma_rad = options.pose_sigma_rad;
    data.shared = spline_problem->evaluation_callback();
    data.model = options.model.trajectory;
    pose_segments.push_back(data.segment_index);
    const ReplacementCosts& replacement = options.residuals.replacement;
    ceres::CostFunction* cost = replacement.pose ? replacement.pose(data)
                                                 : new PoseCostFunction(data);
    const int i = data.segment_index;
    problem()->AddResidualBlock(cost,
                              nullptr,
                              {spline_problem->control_block(i - 1),
                               spline_problem->control_block(i),
                               spline_problem->control_block(i + 1),
                               spline_problem->control_block(i + 2),
                               &time_offset,
                               extrinsic.data()});
  }
}

std::string FitProblem::Impl::LikelyCauses(double gyro_ratio, double accel_ratio) const {
  std::vector<std::string> causes;
  if (options.estimate_time_offset &&
      std::abs(time_offset) >= (1.0 - kEdgeFraction) * options.max_time_offset_s) {
    causes.push_back("the time offset is beyond the search range");
  }
  if (!options.estimate_time_offset && std::isfinite(correlation_offset_s) &&
      std::abs(correlation_offset_s - time_offset) > 2.5 / imu_rate_hz) {
    causes.push_back("an unestimated time offset (the rotation rates line up best at " +
                     StringPrintf("%.1f", 1e3 * correlation_offset_s) +
                     " ms; try --estimate-time-offset)");
  }
  if (gyro_ratio > options.max_residual_noise_ratio) {
    causes.push_back(
        "gyro readings that do not match the poses' rotation (wrong --gyro-unit, "
        "an extrinsic rotation that was not estimated, or poses of another body)");
  }
  if (accel_ratio > options.max_residual_noise_ratio) {
    causes.push_back(
        "accelerometer readings that do not match the poses' motion (wrong "
        "--accel-unit or --gravity, or an extrinsic that was not estimated)");
  }
  causes.push_back("noise densities in --imu-yaml far below the sensor's");
  causes.push_back("too little excitation (the IMU barely moved or rotated)");
  std::string text;
  for (size_t c = 0; c < causes.size(); ++c) text += (c == 0 ? "" : "; ") + causes[c];
  return text;
}

FitResult FitProblem::Impl::Solve() {
  FitResult result;
  // Jacobian entries: 3 rows per gyro/accel sample times their tangent columns, 6 per pose.
  const int bias_points = spline_problem->bias_spline().points_per_segment();
  const double jacobian_entries =
      3.0 * static_cast<double>(imu.size()) * (2.0 * 24.0 + 6.0 * bias_points + 2.0) +
      6.0 * static_cast<double>(used_poses.size()) * 31.0;
  const SolverOptions solver = spline_problem->ResolvedSolverOptions(options.solver);
  SolveRounds rounds(solver, jacobian_entries);
  const bool trim_memory = jacobian_entries > kTrimAboveJacobianEntries;
  // Return what the initialisation freed (the pose fit's solver) before the main solve, whose
  // Jacobian is the peak memory of long recordings (docs/performance.md).
  if (trim_memory) ReturnFreedMemoryToSystem();
  for (int round = 0; round < solver.max_rounds; ++round) {
    rounds.Solve(problem(), "fit: ");
    if (rounds.failed()) {
      throw Error("the solver failed (" + rounds.last().message +
                  "); likely causes: " + LikelyCauses(0.0, 0.0));
    }
    bool moved = false;
    for (size_t p = 0; options.estimate_time_offset && p < used_poses.size(); ++p) {
      if (layout.ClampedSegmentAt(PoseTimeSinceT0(used_poses[p]) + time_offset) !=
          pose_segments[p]) {
        moved = true;
      }
    }
    // The IMU noise from the residuals (variance components, estimation/imu_noise_estimate.h).
    if (spline_problem->evaluation_callback()) spline_problem->evaluation_callback()->Update();
    const bool reweighted =
        imu_noise->Update(spline_problem.get(), solver.num_threads) > kNoiseChangeForNewRound;
    if (!moved && !reweighted) break;
    if (options.solver.progress) {
      options.solver.progress(moved ? "fit: time offset moved poses across knots; solving again"
                                    : "fit: IMU noise re-estimated; solving again");
    }
    BuildProblem();
  }
  result.solve = rounds.Summary();
  if (!rounds.NoConvergenceWarning().empty()) {
    result.warnings.push_back(rounds.NoConvergenceWarning());
  }
  if (spline_problem->evaluation_callback()) spline_problem->evaluation_callback()->Update();

  // Estimates.
  result.layout = layout;
  result.trajectory = options.model.trajectory;
  result.knot_spacing_s = dt_s;
  result.knot_spacing_rule = knot_rule;
  result.control_poses = spline_problem->ControlPoses();
  result.bias_model = options.model.bias_model;
  result.gravity_w = spline_problem->gravity_w();
  result.time_offset_estimated = options.estimate_time_offset;
  result.time_offset_s = time_offset;
  result.extrinsic_estimated = options.estimate_extrinsic;
  result.T_m_s = PoseFromBlock(extrinsic.data());
  result.imu_rate_hz = imu_rate_hz;
  result.num_imu_samples = static_cast<int>(imu.size());
  result.num_poses = static_cast<int>(used_poses.size());
  result.noise_std.gyro_rad_s = imu_noise->gyro_sigma();
  result.noise_std.accel_m_s2 = imu_noise->accel_sigma();
  result.imu_noise = imu_noise->estimate();
  result.noise_std.position_m = options.pose_sigma_m;
  result.noise_std.rotation_rad = options.pose_sigma_rad;
  if (options.model.bias_model == BiasModel::kSpline) {
    const BiasSpline& bias = spline_problem->bias_spline();
    result.bias_t0_ns = bias.t0_ns();
    result.bias_dt_ns = bias.dt_ns();
    for (int m = 0; m < bias.num_points(); ++m) {
      result.gyro_bias_control_points.push_back(
          Eigen::Map<const Eigen::Vector3d>(spline_problem->gyro_bias(m)));
      result.accel_bias_control_points.push_back(
          Eigen::Map<const Eigen::Vector3d>(spline_problem->accel_bias(m)));
    }
  }

  // Residuals at the solution (and the bias averages).
  if (options.keep_samples) result.imu_samples.reserve(imu.size());
  const ImuResidualStatistics imu_stats =
      spline_problem->EvaluateImu(imu, [&](const ImuSample& s, const ImuPrediction& p) {
        if (!options.keep_samples) return;
        FitImuSample out;
        out.t_ns = s.t_ns;
        out.gyro_measured = s.gyro;
        out.gyro_fitted = p.gyro;
        out.accel_measured = s.accel;
        out.accel_fitted = p.accel;
        out.gyro_bias = p.gyro_bias;
        out.accel_bias = p.accel_bias;
        result.imu_samples.push_back(out);
      });
  result.residual_rms.gyro_rad_s = imu_stats.gyro_rms;
  result.residual_rms.accel_m_s2 = imu_stats.accel_rms;
  result.gyro_bias = imu_stats.mean_gyro_bias;
  result.accel_bias = imu_stats.mean_accel_bias;
  const SE3Splined spline = spline_problem->Spline();
  const SE3d T_s_m = result.T_m_s.inverse();
  double position_sq = 0.0;
  double rotation_sq = 0.0;
  for (int j : used_poses) {
    const double t = PoseTimeSinceT0(j) + time_offset;
    const SE3d T_pred = spline.Pose(std::clamp(t, spline.start_time(), spline.end_time())) * T_s_m;
    const SE3d T_meas = PoseOf(poses[j]);
    const Eigen::Vector3d dp = T_pred.translation() - T_meas.translation();
    const Eigen::Vector3d dphi = (T_meas.so3().inverse() * T_pred.so3()).Log();
    position_sq += dp.squaredNorm();
    rotation_sq += dphi.squaredNorm();
    if (options.keep_samples) {
      FitPoseSample out;
      out.t_ns = poses[j].t_ns;
      out.position_error_m = dp;
      out.rotation_error_rad = dphi;
      result.pose_samples.push_back(out);
    }
  }
  const double n_poses = std::max<double>(1.0, static_cast<double>(used_poses.size()));
  result.residual_rms.position_m = std::sqrt(position_sq / (3.0 * n_poses));
  result.residual_rms.rotation_rad = std::sqrt(rotation_sq / (3.0 * n_poses));

  // Failure and warnings from the residuals.
  const double gyro_ratio = result.residual_rms.gyro_rad_s / sigma_g;
  const double accel_ratio = result.residual_rms.accel_m_s2 / sigma_a;
  if (options.estimate_time_offset &&
      std::abs(time_offset) >= (1.0 - kEdgeFraction) * options.max_time_offset_s) {
    throw Error("the time offset reached the edge of its search range (" +
                StringPrintf("%.6g", time_offset) + " s of +-" +
                StringPrintf("%.6g", options.max_time_offset_s) +
                " s): the true offset is probably beyond it; raise --max-time-offset or check that "
                "IMU and poses share a clock");
  }
  if (gyro_ratio > options.max_residual_noise_ratio ||
      accel_ratio > options.max_residual_noise_ratio) {
    throw Error("the solution does not explain the data: residual RMS is " +
                StringPrintf("%.3g", gyro_ratio) + "x the gyro noise and " +
                StringPrintf("%.3g", accel_ratio) + "x the accelerometer noise; likely causes: " +
                LikelyCauses(gyro_ratio, accel_ratio));
  }
  auto warn_ratio = [&](double ratio, const std::string& what) {
    if (ratio > kWarnResidualNoiseRatio) {
      result.warnings.push_back(what + " residuals are " + StringPrintf("%.2g", ratio) +
                                "x the assumed noise: the reported standard deviations assume "
                                "that noise and are too small by about that factor (unmodelled "
                                "vibration, noise densities that are too low, or a time offset "
                                "or extrinsic that was not estimated)");
    }
  };
  if (!options.warn_imu_residual_noise) {
    // The caller measures and reports the IMU noise itself.
  } else if (options.model.imu_noise == ImuNoiseMode::kGiven) {
    warn_ratio(gyro_ratio, "gyro");
    warn_ratio(accel_ratio, "accelerometer");
  } else if (std::max(gyro_ratio, accel_ratio) > kWarnResidualNoiseRatio) {
    result.warnings.push_back(
        "the IMU residuals are " + StringPrintf("%.2g", gyro_ratio) + "x (gyro) and " +
        StringPrintf("%.2g", accel_ratio) +
        "x (accelerometer) the noise of the given densities: the standard deviations use the "
        "noise measured from the residuals (unmodelled vibration, a knot spacing too coarse for "
        "the motion, or densities that are too low)");
  }
  warn_ratio(result.residual_rms.position_m / options.pose_sigma_m, "pose position");
  warn_ratio(result.residual_rms.rotation_rad / options.pose_sigma_rad, "pose rotation");

  // The solver's Jacobian is gone: give its pages back before the covariance allocates (the
  // peak memory of long recordings, docs/performance.md).
  if (trim_memory) ReturnFreedMemoryToSystem();
  if (options.covariance.compute) ComputeCovariance(&result);
  result.warnings.insert(result.warnings.begin(), warnings.begin(), warnings.end());
  return result;
}

void FitProblem::Impl::ComputeCovariance(FitResult* result) {
  const auto start = std::chrono::steady_clock::now();
  // Parameter blocks and the linear map from their tangent coordinates to the reported
  // quantities (bias averages for the spline model).
  const int num_bias_points = spline_problem->bias_spline().num_points();
  std::vector<const double*> blocks;
  std::vector<int> tangent_sizes;
  for (int m = 0; m < num_bias_points; ++m) {
    blocks.push_back(spline_problem->gyro_bias(m));
    tangent_sizes.push_back(3);
  }
  for (int m = 0; m < num_bias_points; ++m) {
    blocks.push_back(spline_problem->accel_bias(m));
    tangent_sizes.push_back(3);
  }
  blocks.push_back(spline_problem->gravity());
  tangent_sizes.push_back(2);
  if (options.estimate_time_offset) {
    blocks.push_back(&time_offset);
    tangent_sizes.push_back(1);
  }
  if (options.estimate_extrinsic) {
    blocks.push_back(extrinsic.data());
    tangent_sizes.push_back(6);
  }
  const int tangent_total = std::accumulate(tangent_sizes.begin(), tangent_sizes.end(), 0);
  const int reported =
      8 + (options.estimate_time_offset ? 1 : 0) + (options.estimate_extrinsic ? 6 : 0);
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(reported, tangent_total);
  // Bias averages: mean over the samples of sum_j w_j c_{m-1+j}.
  A.topLeftCorner(6, 6 * num_bias_points) = spline_problem->MeanBiasMap(imu);
  int column = 6 * num_bias_points;
  int row = 6;
  const int extra = tangent_total - column;
  A.block(row, column, extra, extra).setIdentity();

  result->covariance_labels = {"gyro_bias_x",
                               "gyro_bias_y",
                               "gyro_bias_z",
                               "accel_bias_x",
                               "accel_bias_y",
                               "accel_bias_z",
                               "gravity_direction_1",
                               "gravity_direction_2"};
  if (options.estimate_time_offset) result->covariance_labels.push_back("time_offset");
  if (options.estimate_extrinsic) {
    for (const char* label : {"T_pose_imu_rho_x",
                              "T_pose_imu_rho_y",
                              "T_pose_imu_rho_z",
                              "T_pose_imu_phi_x",
                              "T_pose_imu_phi_y",
                              "T_pose_imu_phi_z"}) {
      result->covariance_labels.push_back(label);
    }
  }

  MarginalCovarianceOptions covariance_options;
  covariance_options.num_threads = options.solver.num_threads;
  covariance_options.max_ceres_covariance_entries = options.covariance.max_ceres_covariance_entries;
  covariance_options.backend = options.covariance.backend;
  // The noise the residuals show and the cluster-robust scatter over time windows
  // (estimation/marginal_covariance.h, ReportedCovarianceOf); both need the Schur backend.
  const bool extras = imu_noise->AddToCovarianceOptions(
      spline_problem.get(), options.covariance.robust_window_s, &covariance_options);
  if (extras) {
    covariance_options.backend = CovarianceBackend::kSchur;
    covariance_options.reported_map = A;
  }
  const MarginalCovariance marginal =
      ComputeMarginalCovariance(problem(), blocks, covariance_options);
  result->covariance_method = marginal.method;
  const bool ok = marginal.ok;
  if (!ok) {
    ReportSingularFitInformation(options, result);
    result->covariance_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return;
  }
  MarginalCovariance mapped;  // without the extras, the noise model's covariance through A
  mapped.ok = true;
  if (!extras) mapped.covariance = A * marginal.covariance * A.transpose();
  const ReportedCovariance honest = ReportedCovarianceOf(extras ? marginal : mapped);
  result->std_inflation = honest.inflation.maxCoeff();
  result->robust_clusters = marginal.num_clusters;
  ReportFitUncertainty(options, honest.covariance, result);
  result->covariance_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---------------------------------------------------------------------------------------------

FitProblem::FitProblem(const std::vector<ImuSample>& imu,
                       const std::vector<StampedPose>& poses,
                       const FitOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
  impl_->Initialise(imu, poses);
}

FitProblem::~FitProblem() = default;

const KnotLayout& FitProblem::layout() const { return impl_->layout; }

void FitProblem::SetControlPoses(const std::vector<SE3d>& control_poses) {
  if (static_cast<int>(control_poses.size()) != impl_->num_control_poses()) {
    throw Error("FitProblem::SetControlPoses: expected " +
                std::to_string(impl_->num_control_poses()) + " control poses, got " +
                std::to_string(control_poses.size()));
  }
  impl_->spline_problem->SetControlPoses(control_poses);
}

void FitProblem::SetBiases(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias) {
  impl_->spline_problem->SetBiases(gyro_bias, accel_bias);
}

void FitProblem::SetGravity(const Eigen::Vector3d& g_w) {
  if (!(g_w.norm() > 0.0) || !g_w.allFinite()) throw Error("SetGravity: needs a nonzero vector");
  impl_->spline_problem->SetGravity(impl_->options.model.gravity_m_s2 * g_w.normalized());
}

void FitProblem::SetTimeOffset(double time_offset_s) {
  impl_->time_offset = time_offset_s;
  impl_->BuildProblem();  // re-attaches the pose residuals to the segments of the new offset
}

FitResult FitProblem::Solve() { return impl_->Solve(); }

FitResult Fit(const std::vector<ImuSample>& imu,
              const std::vector<StampedPose>& poses,
              const FitOptions& options) {
  FitProblem problem(imu, poses, options);
  return problem.Solve();
}

}  // namespace splinecal
