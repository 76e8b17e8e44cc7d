// The camera-IMU calibration problem of `splinecal calibrate` (calib/calibrate.h is the
// contract): its parameter blocks, residual bookkeeping, solve rounds and results. Private to
// src/calib/: calibrate.cc builds and solves it, calibration_results.cc turns a solution into a
// CalibrationResult (covariance, residuals).
#ifndef SPLINECAL_SRC_CALIB_CALIBRATION_PROBLEM_H_
#define SPLINECAL_SRC_CALIB_CALIBRATION_PROBLEM_H_

#include "splinecal/calib/calibrate.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "calibration_data.h"
#include "calibration_warnings.h"
#include "further_imus.h"
#include "splinecal/calib/camchain_prior.h"
#include "splinecal/calib/fit.h"
#include "splinecal/calib/detail/target_scale_cost.h"
#include "splinecal/camera/pnp.h"
#include "splinecal/error.h"
#include "splinecal/estimation/detail/compact_frame_cost.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/imu_model_observability.h"
#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/estimation/interval_manifold.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/estimation/spline_problem.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"
#include "splinecal/vio/align.h"

namespace splinecal {

using internal::AddStandardDeviationWarnings;
using internal::CheckFurtherImus;
using internal::CheckInputs;
using internal::CheckRotationExcitation;
using internal::CheckTargetSeen;
using internal::FramePeriods;
using internal::ImuBetween;
using internal::Landmark;
using internal::MakeLandmarks;
using internal::MakeTargetFrames;
using internal::ObservationsInsideImu;
using internal::SpanOfFrames;
using internal::TargetFrame;

namespace internal {


// Time windows of the reprojection residuals reach this far beyond the current exposure range
// [s]: the time offset may move this much during one solve before the windows are rebuilt.
constexpr double kWindowMargin_s = 0.005;
// A solve that ends with an exposure range within this of its window's edge [s] is re-solved
// with new windows.
constexpr double kWindowRebuildMargin_s = 0.002;
// The pixel sigma is re-estimated after each solve; a change above this fraction triggers
// another round.
constexpr double kSigmaChangeForNewRound = 0.1;
// 1.4826 x median absolute deviation = std of a Gaussian.
constexpr double kMadToStd = 1.4826;

class CalibrationProblem {
 public:
  CalibrationProblem(const std::vector<ImuSample>& imu,
                     const Camchain& camchain,
                     const CalibrateOptions& options,
                     const CalibrationInitialGuess& guess,
                     bool has_target,
                     std::vector<ParameterMode> intrinsics_modes,
                     ParameterMode chain_mode)
      : imu_(imu),
        camchain_(camchain),
        options_(options),
        layout_(guess.layout),
        has_target_(has_target),
        intrinsics_modes_(std::move(intrinsics_modes)),
        chain_mode_(chain_mode) {
    dt_s_ = layout_.dt_s();
    const int n = layout_.num_control_poses;
    spline_ = std::make_unique<SplineProblem>(
        layout_,
        guess.control_poses,
        BiasSpline(options.model.bias_model, layout_, options.model.bias_knot_spacing_s),
        ResidualOptions(),
        options.model.trajectory);
    imu_rate_hz_ = ImuRateHz(imu_);
    imu_noise_ = std::make_unique<ImuNoiseEstimator>(
        options.model.noise, imu_rate_hz_, options.model.imu_noise);
    spline_->SetImuModel(options.imu_model);
    spline_->SetGravity(options.model.gravity_m_s2 * guess.gravity_w.normalized());
    spline_->SetBiases(guess.gyro_bias, guess.accel_bias);
    // Cameras.
    cameras_.resize(camchain.size());
    for (size_t c = 0; c < camchain.size(); ++c) {
      const CameraCalibration& init = guess.camchain[c];
      CameraState& cam = cameras_[c];
      PoseToBlock(init.T_cam_imu, cam.extrinsic.data());
      cam.intrinsics = init.camera.intrinsics();
      cam.time_offset_s = init.time_offset_s;
      cam.line_delay =
          options.rolling_shutter ? std::max(0.0, init.line_delay_s) : init.line_delay_s;
    }
    PoseToBlock(SE3d(), T_w_t_.data());
    if (!options.further_imus.empty()) {
      further_ = std::make_unique<FurtherImus>(options.further_imus, layout_, spline_->bias_spline(),
                                               options.model.trajectory, options.max_time_offset_s);
    }
    imu_ = ImuBetween(imu,
                      layout_.t0_ns + layout_.dt_ns,
                      layout_.t0_ns + static_cast<int64_t>(n - 2) * layout_.dt_ns);
    if (imu_.size() < 2) throw Error("calibrate: fewer than 2 IMU samples inside the spline");
  }

  void SetFramePeriods(const std::vector<double>& periods) { frame_periods_ = periods; }
  std::vector<TargetFrame>* target_frames() { return &target_frames_; }
  std::vector<Landmark>* landmarks() { return &landmarks_; }
  SE3Splined Spline() const { return spline_->Spline(); }
  const KnotLayout& layout() const { return layout_; }
  double TimeSinceT0(int64_t t_ns) const {
    return 1e-9 * static_cast<double>(t_ns - layout_.t0_ns);
  }

  CalibrationResult Run();

 private:
  // Per residual: which frame / landmark observation it is, and its window(s).
  struct FrameResidual {
    int frame = 0;
    ControlPoseWindow window;
    ceres::ResidualBlockId id = nullptr;  // its block in problem() (the covariance's clusters)
  };
  struct LandmarkResidual {
    int landmark = 0;
    int observation = 0;
    ControlPoseWindow reference_window;
    ControlPoseWindow window;
  };
  struct CameraState {
    std::array<double, 7> extrinsic{};
    IntrinsicsVector intrinsics = IntrinsicsVector::Zero();  // a block with estimate_intrinsics
    // Holds the entries the model does not use; the problem does not own its manifolds (the
    // spline's are shared), so the camera does.
    std::shared_ptr<ceres::Manifold> intrinsics_manifold;
    std::shared_ptr<ceres::Manifold> time_offset_manifold;  // [-max, max] when estimated
    std::shared_ptr<ceres::Manifold> line_delay_manifold;   // [0, max_line_delay]
    double time_offset_s = 0.0;
    double line_delay = 0.0;
    double window_readout_s = 0.0;     // the readout the windows were built for
    double window_before_s = 0.0;      // how far before the stamp + time offset they reach
    double built_time_offset_s = 0.0;  // the time offset they were built around
    double max_line_delay = 0.0;       // the line delay's upper bound (lower: 0)
    bool line_delay_held = false;      // held constant at a bound (the active set)
    int line_delay_releases = 0;       // times freed from a bound
  };

  const std::vector<double*>& control_blocks() const { return spline_->control_blocks(); }
  ceres::Problem& problem() { return spline_->problem(); }

  ReprojectionOptions Settings(int cam, double sigma, double huber) const {
    ReprojectionOptions s;
    s.camera = &camchain_[cam].camera;
    s.layout = layout_;
    s.model = spline_->trajectory_model();
    s.sigma_px = sigma;
    s.huber_px = huber;
    s.shared = spline_->evaluation_callback();
    if (HeldToReference(cam)) s.T_cam_cref = options_.camera_chain_T_cn_c0[cam];
    s.estimate_intrinsics = HasIntrinsicsBlock(cam);
    return s;
  }
  // With a held camera chain every camera after the first rides on camera 0's T_cam_imu block.
  bool HeldToReference(size_t c) const { return c > 0 && chain_mode_ == ParameterMode::kHeld; }
  bool EstimatesIntrinsics(size_t c) const {
    return intrinsics_modes_[c] == ParameterMode::kPrior ||
           intrinsics_modes_[c] == ParameterMode::kFree;
  }
  // The frames' costs take the intrinsics as a block (estimated, or considered: held constant in
  // the solve, freed for the covariance's sensitivity).
  bool HasIntrinsicsBlock(size_t c) const { return intrinsics_modes_[c] != ParameterMode::kHeld; }
  // The prior residual of camera c (intrinsics and/or T_cn_cnm1; nullptr: none).
  std::unique_ptr<CamchainPriorCostFunction> PriorCost(size_t c, std::vector<double*>* blocks);
  // The frame's cost with the target scale's block when it is free (target_scale_cost.h).
  std::unique_ptr<ceres::CostFunction> ScaledFrameCost(std::unique_ptr<ceres::CostFunction> cost,
                                                       const FrameResidual& r) const;
  // With an IMU model: holds at nominal, with a warning, the model's parameters the recording
  // does not determine (estimation/imu_model_observability.h).
  void HoldUndeterminedImuModelParameters(CalibrationResult* result);
  // CalibrateOptions::imu_model_held.
  void HoldRequestedImuModelParameters();
  // Solves in rounds until nothing changes between them (time windows, noise, line delays).
  void SolveUntilStable(SolveRounds* rounds, const SolverOptions& solver, CalibrationResult* result);
  // The target scale's estimate and std with the rest free (false: covariance singular).
  bool TargetScaleStd(double* std_out);
  // Holds the target scale at 1 after the check: the solution mapped to s = 1 (translations
  // divided by s, target_scale_cost.h) as the start of the next solve.
  void HoldTargetScale();
  double* ExtrinsicBlock(size_t c) { return cameras_[HeldToReference(c) ? 0 : c].extrinsic.data(); }
  SE3d CameraFromImu(size_t c) const {
    const SE3d block = PoseFromBlock(cameras_[HeldToReference(c) ? 0 : c].extrinsic.data());
    return HeldToReference(c) ? options_.camera_chain_T_cn_c0[c] * block : block;
  }
  // The window of a frame's exposures for the camera's current state (false near the ends).
  bool FrameWindow(int cam, int64_t t_ns, double margin, ControlPoseWindow* window) const {
    const CameraState& c = cameras_[cam];
    const double t = TimeSinceT0(t_ns) + c.time_offset_s;
    return layout_.WindowCovering(
        t - std::max(margin, c.window_before_s), t + c.window_readout_s + margin, window);
  }
  bool Contains(const ControlPoseWindow& outer, const ControlPoseWindow& inner) const {
    return inner.first_index >= outer.first_index && inner.last_index() <= outer.last_index();
  }

  void BuildProblem();
  // The cost (pixel sigma, Huber threshold) and parameter blocks of a frame or landmark residual,
  // and its unweighted pixel errors at the current values (false: cannot be evaluated).
  std::unique_ptr<TargetFrameCostFunction> FrameCost(const FrameResidual& r,
                                                     double sigma,
                                                     double huber) const;
  std::unique_ptr<LandmarkCostFunction> LandmarkCost(const LandmarkResidual& r,
                                                     double sigma,
                                                     double huber) const;
  std::vector<double*> Blocks(const FrameResidual& r);
  std::vector<double*> Blocks(const LandmarkResidual& r);
  template <typename Residual>
  bool PixelErrors(const Residual& r, std::vector<double>* errors);
  double EstimatePixelSigma();
  bool WindowsStillValid();
  // Cheap check for the windows' StopWhen in Run: every camera's time offset and readout are
  // still inside what the windows were built for, less kWindowRebuildMargin_s.
  bool TimesInsideWindows() const {
    for (size_t c = 0; c < cameras_.size(); ++c) {
      const CameraState& cam = cameras_[c];
      const double moved = cam.time_offset_s - cam.built_time_offset_s;
      const double readout = cam.line_delay * (camchain_[c].camera.height - 1);
      if (moved < -(cam.window_before_s - kWindowRebuildMargin_s) ||
          moved + readout > cam.window_readout_s + kWindowMargin_s - kWindowRebuildMargin_s) {
        return false;
      }
    }
    return true;
  }
  // Holds every free line delay that sits on a bound (true: one did).
  bool HoldLineDelaysAtBounds();
  // Frees every held line delay whose cost gradient points into its interval (true: one was),
  // and leaves the others' blocks variable for the covariance.
  bool ReleaseLineDelays();
  bool LineDelayAtBound(const CameraState& cam) const {
    return cam.line_delay <= 0.0 || cam.line_delay >= cam.max_line_delay;
  }
  void ComputeCovariance(CalibrationResult* result);
  // Adds S Sigma_c S^T of the considered intrinsics (ParameterMode::kConsider;
  // calib/consider_covariance.h) to the reported covariance `cov` of the quantities
  // q = reported_map x of the blocks `wanted`, and sets their carried stds in `result`. False
  // (cov unchanged) when the sensitivity cannot be computed; true when nothing is considered.
  bool CarryConsideredIntrinsics(std::vector<const double*> wanted,
                                 const Eigen::MatrixXd& reported_map,
                                 Eigen::MatrixXd* cov,
                                 CalibrationResult* result);
  // result->cameras[c].baseline_std_m (c > 0) from the reported covariance `cov` of the
  // requested blocks (first row of each at offset[block]).
  void BaselineStd(size_t c,
                   const Eigen::MatrixXd& cov,
                   const std::map<const double*, int>& offset,
                   CalibrationResult* result);
  // result->imu_model_covariance and the stds it gives (imu_model_std) from the reported
  // covariance (as BaselineStd).
  void ImuModelCovarianceFrom(const Eigen::MatrixXd& cov,
                              const std::map<const double*, int>& offset,
                              CalibrationResult* result);
  // Options for ComputeMarginalCovariance: the IMU noise's groups and time clusters, each
  // camchain prior as model noise (kModelNoiseCluster).
  MarginalCovarianceOptions CovarianceOptionsForProblem();
  // Adds to `options` (further_cluster_of) the clusters of the second cluster-robust
  // covariance, over kinds of view, built on its time windows (calibration_results.cc); the
  // number of occupied view clusters, 0 (options unchanged) when none or too few.
  int ViewKindClusters(MarginalCovarianceOptions* options);
  void Collect(CalibrationResult* result);

  std::vector<ImuSample> imu_;
  const Camchain& camchain_;
  const CalibrateOptions& options_;
  KnotLayout layout_;
  bool has_target_;
  std::vector<ParameterMode> intrinsics_modes_;  // per camera, resolved (calibrate.h)
  ParameterMode chain_mode_;
  std::set<ceres::ResidualBlockId> prior_blocks_;  // the camchain priors' residuals
  double target_scale_ = 1.0;  // p_t -> s p_t (a block while target_scale_free_)
  bool target_scale_free_ = false;
  double dt_s_ = 0.0;
  double imu_rate_hz_ = 0.0;
  std::unique_ptr<ImuNoiseEstimator> imu_noise_;  // the densities weighting the IMU residuals
  double sigma_px_ = 1.0;

  std::unique_ptr<SplineProblem> spline_;  // control poses, biases, gravity
  std::unique_ptr<FurtherImus> further_;   // the rig's further IMUs (nullptr: one IMU)
  std::vector<CameraState> cameras_;
  // Every landmark's inverse depth stays >= 0 (estimation/interval_manifold.h).
  std::shared_ptr<ceres::Manifold> rho_manifold_ =
      std::make_shared<IntervalManifold>(0.0, std::numeric_limits<double>::infinity());
  std::array<double, 7> T_w_t_{};
  std::vector<double> frame_periods_;

  std::vector<TargetFrame> target_frames_;
  std::vector<Landmark> landmarks_;
  std::vector<FrameResidual> frame_residuals_;
  std::vector<LandmarkResidual> landmark_residuals_;
  // Frame and landmark residuals left out of the problem because they could not be evaluated at
  // the values it was built at (BuildProblem): in the latest build, in the last solved round and
  // at most in any round.
  int unprojectable_residuals_ = 0;
  int unprojectable_in_last_round_ = 0;
  int most_unprojectable_ = 0;
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_CALIBRATION_PROBLEM_H_
