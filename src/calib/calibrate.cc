#include "splinecal/calib/calibrate.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
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
#include "splinecal/calib/fit.h"
#include "splinecal/camera/pnp.h"
#include "splinecal/error.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/estimation/imu_costs.h"
#include "splinecal/estimation/imu_noise_estimate.h"
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

using calibrate_internal::AddStandardDeviationWarnings;
using calibrate_internal::CheckInputs;
using calibrate_internal::CheckRotationExcitation;
using calibrate_internal::CheckTargetSeen;
using calibrate_internal::FramePeriods;
using calibrate_internal::ImuBetween;
using calibrate_internal::Landmark;
using calibrate_internal::MakeLandmarks;
using calibrate_internal::MakeTargetFrames;
using calibrate_internal::ObservationsInsideImu;
using calibrate_internal::SpanOfFrames;
using calibrate_internal::TargetFrame;

namespace {

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
// Stops a solve (SOLVER_TERMINATE_SUCCESSFULLY) at the first iteration for which stop(summary)
// holds, and remembers that it did; the caller rebuilds the problem and solves again. Needs
// Solver::Options::update_state_every_iteration (stop reads the parameters). Two uses in Run:
// - the time windows: the time offset or line delay is about to leave the windows the residuals
//   were built with (Ceres then only sees failed evaluations beyond them);
// - a free line delay that an accepted step has put on a bound: Ceres projects a step that
//   crosses a bound onto it, its quadratic model then over-predicts the decrease, the trust
//   region shrinks and the solve creeps along the bound in tiny steps (EuRoC's global-shutter
//   cameras: 163 iterations instead of 27). That line delay is then held at the bound (the active
//   set, calibrate.h).
class StopWhen : public ceres::IterationCallback {
 public:
  explicit StopWhen(std::function<bool(const ceres::IterationSummary&)> stop)
      : stop_(std::move(stop)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    if (!stop_(summary)) return ceres::SOLVER_CONTINUE;
    triggered_ = true;
    return ceres::SOLVER_TERMINATE_SUCCESSFULLY;
  }
  bool triggered() const { return triggered_; }

 private:
  std::function<bool(const ceres::IterationSummary&)> stop_;
  bool triggered_ = false;
};

// A line delay freed from its bound at most this often per camera (calibrate.h: the active set);
// then it stays where the data put it, so that the rounds cannot alternate for ever.
constexpr int kMaxLineDelayReleases = 2;

class CalibrationProblem {
 public:
  CalibrationProblem(const std::vector<ImuSample>& imu,
                     const Camchain& camchain,
                     const CalibrateOptions& options,
                     const CalibrationInitialGuess& guess,
                     bool has_target)
      : imu_(imu),
        camchain_(camchain),
        options_(options),
        layout_(guess.layout),
        has_target_(has_target) {
    dt_s_ = layout_.dt_s();
    const int n = layout_.num_control_poses;
    spline_ = std::make_unique<SplineProblem>(
        layout_,
        guess.control_poses,
        BiasSpline(options.model.bias_model, layout_, options.model.bias_knot_spacing_s));
    imu_rate_hz_ = ImuRateHz(imu_);
    imu_noise_ = std::make_unique<ImuNoiseEstimator>(
        options.model.noise, imu_rate_hz_, options.model.imu_noise);
    spline_->SetGravity(options.model.gravity_m_s2 * guess.gravity_w.normalized());
    spline_->SetBiases(guess.gyro_bias, guess.accel_bias);
    // Cameras.
    cameras_.resize(camchain.size());
    for (size_t c = 0; c < camchain.size(); ++c) {
      const CameraCalibration& init = guess.camchain[c];
      CameraState& cam = cameras_[c];
      PoseToBlock(init.T_cam_imu, cam.extrinsic.data());
      cam.time_offset_s = init.time_offset_s;
      cam.line_delay =
          options.rolling_shutter ? std::max(0.0, init.line_delay_s) : init.line_delay_s;
    }
    PoseToBlock(SE3d(), T_w_t_.data());
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
  };
  struct LandmarkResidual {
    int landmark = 0;
    int observation = 0;
    ControlPoseWindow reference_window;
    ControlPoseWindow window;
  };
  struct CameraState {
    std::array<double, 7> extrinsic{};
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

  ReprojectionSettings Settings(int cam, double sigma, double huber) const {
    ReprojectionSettings s;
    s.camera = &camchain_[cam].camera;
    s.layout = layout_;
    s.sigma_px = sigma;
    s.huber_px = huber;
    s.shared = spline_->evaluation_callback();
    if (HeldToReference(cam)) s.T_cam_cref = options_.camera_chain_T_cn_c0[cam];
    return s;
  }
  // With a held camera chain every camera after the first rides on camera 0's T_cam_imu block.
  bool HeldToReference(size_t c) const { return c > 0 && !options_.camera_chain_T_cn_c0.empty(); }
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
  void Collect(CalibrationResult* result);

  std::vector<ImuSample> imu_;
  const Camchain& camchain_;
  const CalibrateOptions& options_;
  KnotLayout layout_;
  bool has_target_;
  double dt_s_ = 0.0;
  double imu_rate_hz_ = 0.0;
  std::unique_ptr<ImuNoiseEstimator> imu_noise_;  // the densities weighting the IMU residuals
  double sigma_px_ = 1.0;

  std::unique_ptr<SplineProblem> spline_;  // control poses, biases, gravity
  std::vector<CameraState> cameras_;
  std::array<double, 7> T_w_t_{};
  std::vector<double> frame_periods_;

  std::vector<TargetFrame> target_frames_;
  std::vector<Landmark> landmarks_;
  std::vector<FrameResidual> frame_residuals_;
  std::vector<LandmarkResidual> landmark_residuals_;
};

void CalibrationProblem::BuildProblem() {
  spline_->evaluation_callback()->Update();
  // Without a target the first control pose holds the gauge.
  spline_->Reset(/*hold_first_pose=*/!has_target_);
  problem().AddParameterBlock(T_w_t_.data(), 7, spline_->se3_manifold());
  problem().SetParameterBlockConstant(T_w_t_.data());
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraState& cam = cameras_[c];
    const int height = camchain_[c].camera.height;
    cam.built_time_offset_s = cam.time_offset_s;
    if (!HeldToReference(c)) {
      problem().AddParameterBlock(cam.extrinsic.data(), 7, spline_->se3_manifold());
    }
    problem().AddParameterBlock(&cam.time_offset_s, 1);
    problem().AddParameterBlock(&cam.line_delay, 1);
    if (options_.estimate_time_offset) {
      cam.time_offset_s =
          std::clamp(cam.time_offset_s, -options_.max_time_offset_s, options_.max_time_offset_s);
      problem().SetParameterLowerBound(&cam.time_offset_s, 0, -options_.max_time_offset_s);
      problem().SetParameterUpperBound(&cam.time_offset_s, 0, options_.max_time_offset_s);
    } else {
      problem().SetParameterBlockConstant(&cam.time_offset_s);
    }
    if (options_.rolling_shutter) {
      // The readout cannot exceed the frame period.
      cam.max_line_delay = frame_periods_[c] / std::max(1, height - 1);
      cam.line_delay = std::clamp(cam.line_delay, 0.0, cam.max_line_delay);
      problem().SetParameterLowerBound(&cam.line_delay, 0, 0.0);
      problem().SetParameterUpperBound(&cam.line_delay, 0, cam.max_line_delay);
      if (cam.line_delay_held) problem().SetParameterBlockConstant(&cam.line_delay);
    } else {
      problem().SetParameterBlockConstant(&cam.line_delay);
    }
  }
  spline_->AddImuResiduals(imu_, imu_noise_->gyro_sigma(), imu_noise_->accel_sigma());
  spline_->AddBiasRandomWalkResiduals(imu_noise_->densities());
  frame_residuals_.clear();
  for (size_t f = 0; f < target_frames_.size(); ++f) {
    const TargetFrame& frame = target_frames_[f];
    FrameResidual residual;
    residual.frame = static_cast<int>(f);
    if (!FrameWindow(frame.cam, frame.t_ns, kWindowMargin_s, &residual.window)) continue;
    problem().AddResidualBlock(
        FrameCost(residual, sigma_px_, options_.huber_px).release(), nullptr, Blocks(residual));
    frame_residuals_.push_back(residual);
  }
  landmark_residuals_.clear();
  for (size_t l = 0; l < landmarks_.size(); ++l) {
    Landmark& landmark = landmarks_[l];
    bool added_rho = false;
    for (size_t o = 0; o < landmark.others.size(); ++o) {
      const Observation& obs = landmark.others[o];
      LandmarkResidual residual;
      residual.landmark = static_cast<int>(l);
      residual.observation = static_cast<int>(o);
      if (!FrameWindow(
              landmark.cam, landmark.reference.t_ns, kWindowMargin_s, &residual.reference_window) ||
          !FrameWindow(obs.cam_id, obs.t_ns, kWindowMargin_s, &residual.window)) {
        continue;
      }
      if (obs.cam_id != landmark.cam) continue;  // one camera per landmark (the reference's)
      problem().AddResidualBlock(LandmarkCost(residual, sigma_px_, options_.huber_px).release(),
                                 nullptr,
                                 Blocks(residual));
      landmark_residuals_.push_back(residual);
      added_rho = true;
    }
    if (added_rho) problem().SetParameterLowerBound(&landmark.rho, 0, 0.0);
  }
}

std::unique_ptr<TargetFrameCostFunction> CalibrationProblem::FrameCost(const FrameResidual& r,
                                                                       double sigma,
                                                                       double huber) const {
  const TargetFrame& frame = target_frames_[r.frame];
  return std::make_unique<TargetFrameCostFunction>(
      Settings(frame.cam, sigma, huber), r.window, TimeSinceT0(frame.t_ns), frame.corners);
}

std::unique_ptr<LandmarkCostFunction> CalibrationProblem::LandmarkCost(const LandmarkResidual& r,
                                                                       double sigma,
                                                                       double huber) const {
  const Landmark& landmark = landmarks_[r.landmark];
  const Observation& obs = landmark.others[r.observation];
  LandmarkObservation data;
  data.t_reference_frame_s = TimeSinceT0(landmark.reference.t_ns);
  data.ray = landmark.ray;
  data.reference_row = landmark.reference.uv.y();
  data.t_frame_s = TimeSinceT0(obs.t_ns);
  data.uv = obs.uv;
  return std::make_unique<LandmarkCostFunction>(
      Settings(landmark.cam, sigma, huber),
      LandmarkCostFunction::UnionOfWindows(r.reference_window, r.window),
      data);
}

std::vector<double*> CalibrationProblem::Blocks(const FrameResidual& r) {
  const int c = target_frames_[r.frame].cam;
  CameraState& cam = cameras_[c];
  std::vector<double*> blocks(control_blocks().begin() + r.window.first_index,
                              control_blocks().begin() + r.window.last_index() + 1);
  blocks.insert(blocks.end(),
                {ExtrinsicBlock(c), &cam.time_offset_s, &cam.line_delay, T_w_t_.data()});
  return blocks;
}

std::vector<double*> CalibrationProblem::Blocks(const LandmarkResidual& r) {
  Landmark& landmark = landmarks_[r.landmark];
  CameraState& cam = cameras_[landmark.cam];
  std::vector<double*> blocks;
  for (int i : LandmarkCostFunction::UnionOfWindows(r.reference_window, r.window)) {
    blocks.push_back(control_blocks()[i]);
  }
  blocks.insert(blocks.end(),
                {ExtrinsicBlock(landmark.cam), &cam.time_offset_s, &cam.line_delay, &landmark.rho});
  return blocks;
}

template <typename Residual>
bool CalibrationProblem::PixelErrors(const Residual& r, std::vector<double>* errors) {
  std::unique_ptr<ceres::CostFunction> cost;
  if constexpr (std::is_same_v<Residual, FrameResidual>) {
    cost = FrameCost(r, 1.0, 0.0);
  } else {
    cost = LandmarkCost(r, 1.0, 0.0);
  }
  errors->resize(cost->num_residuals());
  return cost->Evaluate(Blocks(r).data(), errors->data(), nullptr);
}

// 1.4826 x the median absolute pixel error per coordinate over every residual.
double CalibrationProblem::EstimatePixelSigma() {
  std::vector<double> errors;
  std::vector<double> e;
  for (const FrameResidual& r : frame_residuals_) {
    if (PixelErrors(r, &e)) {
      for (double v : e) errors.push_back(std::abs(v));
    }
  }
  for (const LandmarkResidual& r : landmark_residuals_) {
    if (PixelErrors(r, &e)) {
      for (double v : e) errors.push_back(std::abs(v));
    }
  }
  if (errors.empty()) return sigma_px_;
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return std::max(1e-3, kMadToStd * errors[errors.size() / 2]);
}

// True when every residual's window still covers its exposure range with a margin.
bool CalibrationProblem::WindowsStillValid() {
  bool valid = true;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const double readout = cameras_[c].line_delay * (camchain_[c].camera.height - 1);
    if (readout > cameras_[c].window_readout_s) valid = false;
  }
  for (const FrameResidual& r : frame_residuals_) {
    const TargetFrame& frame = target_frames_[r.frame];
    ControlPoseWindow needed;
    if (!FrameWindow(frame.cam, frame.t_ns, kWindowRebuildMargin_s, &needed) ||
        !Contains(r.window, needed)) {
      valid = false;
    }
  }
  for (const LandmarkResidual& r : landmark_residuals_) {
    const Landmark& landmark = landmarks_[r.landmark];
    ControlPoseWindow a;
    ControlPoseWindow b;
    const Observation& obs = landmark.others[r.observation];
    if (!FrameWindow(landmark.cam, landmark.reference.t_ns, kWindowRebuildMargin_s, &a) ||
        !FrameWindow(obs.cam_id, obs.t_ns, kWindowRebuildMargin_s, &b) ||
        !Contains(r.reference_window, a) || !Contains(r.window, b)) {
      valid = false;
    }
  }
  return valid;
}

CalibrationResult CalibrationProblem::Run() {
  CalibrationResult result;
  sigma_px_ = options_.pixel_sigma_px > 0.0 ? options_.pixel_sigma_px : 1.0;
  result.pixel_sigma_estimated = options_.pixel_sigma_px <= 0.0;
  // Windows: the physically largest readout (the frame period) in the first round when the line
  // delay is estimated, then the estimate with room to grow.
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const int rows = camchain_[c].camera.height - 1;
    cameras_[c].window_readout_s =
        options_.rolling_shutter ? frame_periods_[c] : cameras_[c].line_delay * rows;
    // An initial time offset from PnP poses of a rolling-shutter camera is late by about half
    // the readout (the pose fits the middle rows): room to move back by up to half a frame.
    cameras_[c].window_before_s =
        kWindowMargin_s + (options_.rolling_shutter ? 0.5 * frame_periods_[c] : 0.0);
  }
  const SolverOptions& solver = options_.solver;
  ceres::Solver::Options solver_options = ToCeresOptions(solver, 0.0, nullptr);
  solver_options.update_state_every_iteration = true;  // for the StopWhen callbacks
  SolveRounds rounds(solver_options, options_.solver.progress);
  for (int round = 1; round <= solver.max_rounds; ++round) {
    BuildProblem();
    if (frame_residuals_.empty() && landmark_residuals_.empty()) {
      throw Error("calibrate: no frame lies inside the spline's time range");
    }
    StopWhen guard([this](const ceres::IterationSummary&) { return !TimesInsideWindows(); });
    StopWhen bound_guard([this](const ceres::IterationSummary& summary) {
      if (summary.iteration == 0 || !summary.step_is_successful) return false;
      for (const CameraState& cam : cameras_) {
        if (options_.rolling_shutter && !cam.line_delay_held && LineDelayAtBound(cam)) return true;
      }
      return false;
    });
    rounds.Solve(&problem(), StringPrintf("calibrate: round %d ", round), {&guard, &bound_guard});
    if (rounds.failed()) {
      throw Error("calibrate: the solver failed (" + rounds.last().message +
                  "); likely causes: a wrong camchain (intrinsics, T_cam_imu far off), "
                  "observations of another camera, or IMU units");
    }
    spline_->evaluation_callback()->Update();
    bool again = false;
    if (result.pixel_sigma_estimated) {
      const double sigma = EstimatePixelSigma();
      if (std::abs(sigma / sigma_px_ - 1.0) > kSigmaChangeForNewRound) again = true;
      sigma_px_ = sigma;
    }
    // The IMU noise from the residuals (variance components): weights that match the data's
    // own noise, so that the covariance below reflects it.
    const double noise_change = imu_noise_->Update(spline_.get());
    if (noise_change > kSigmaChangeForNewRound) again = true;
    const bool windows_valid = !guard.triggered() && WindowsStillValid();
    if (!windows_valid) again = true;
    // Later rounds: windows sized to the estimate with room to grow.
    for (size_t c = 0; c < cameras_.size(); ++c) {
      const int rows = camchain_[c].camera.height - 1;
      if (options_.rolling_shutter) {
        const double readout = cameras_[c].line_delay * rows;
        const double wanted = std::min(frame_periods_[c], 1.2 * readout + 0.002);
        if (!windows_valid || wanted < cameras_[c].window_readout_s) {
          cameras_[c].window_readout_s = wanted;
        }
      }
      cameras_[c].window_before_s = kWindowMargin_s;
    }
    // The active set: a line delay that landed on a bound is held there; at a solution, one whose
    // gradient points inside is freed (its windows then sized for any readout).
    const bool held = bound_guard.triggered() && HoldLineDelaysAtBounds();
    const bool released = !bound_guard.triggered() && !guard.triggered() && ReleaseLineDelays();
    if (held || released) again = true;
    if (!again) break;
    if (round < options_.solver.max_rounds && options_.solver.progress) {
      const ImuNoise& noise = imu_noise_->densities();
      options_.solver.progress(
          "calibrate: pixel sigma " + StringPrintf("%.4g", sigma_px_) + " px, gyro noise " +
          StringPrintf("%.3g", noise.gyroscope_noise_density) + " rad/s/sqrt(Hz), accel noise " +
          StringPrintf("%.3g", noise.accelerometer_noise_density) +
          " m/s^2/sqrt(Hz); time windows " + (windows_valid ? "valid" : "moved") +
          (held ? "; line delay held at its bound" : "") +
          (released ? "; line delay freed from its bound" : "") + ": solving again");
    }
  }
  // A line delay still held: free for the covariance (its std is that of the unconstrained
  // model at the bound; a line delay at 0 within it is consistent with a global shutter).
  for (CameraState& cam : cameras_) {
    if (cam.line_delay_held) problem().SetParameterBlockVariable(&cam.line_delay);
  }
  result.solve = rounds.Summary();
  if (!rounds.NoConvergenceWarning().empty()) {
    result.warnings.push_back(rounds.NoConvergenceWarning());
  }
  result.pixel_sigma_px = sigma_px_;
  result.imu_noise = imu_noise_->estimate();
  Collect(&result);
  if (options_.covariance.compute) {
    const auto start = std::chrono::steady_clock::now();
    ComputeCovariance(&result);
    result.covariance_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return result;
}

bool CalibrationProblem::HoldLineDelaysAtBounds() {
  bool any = false;
  for (CameraState& cam : cameras_) {
    if (!cam.line_delay_held && LineDelayAtBound(cam)) cam.line_delay_held = any = true;
  }
  return any;
}

bool CalibrationProblem::ReleaseLineDelays() {
  bool any = false;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraState& cam = cameras_[c];
    if (!cam.line_delay_held) continue;
    // d cost / d line_delay at the solution of the rest: by the envelope theorem the slope of the
    // cost minimised over everything else, so its sign says which way the line delay would go.
    problem().SetParameterBlockVariable(&cam.line_delay);
    ceres::Problem::EvaluateOptions evaluate;
    evaluate.parameter_blocks = {&cam.line_delay};
    evaluate.num_threads = options_.solver.num_threads;
    double cost = 0.0;
    std::vector<double> gradient;
    if (!problem().Evaluate(evaluate, &cost, nullptr, &gradient, nullptr)) continue;
    const bool inward = cam.line_delay <= 0.0 ? gradient[0] < 0.0 : gradient[0] > 0.0;
    if (inward && cam.line_delay_releases < kMaxLineDelayReleases) {
      cam.line_delay_held = false;
      ++cam.line_delay_releases;
      cameras_[c].window_readout_s = frame_periods_[c];
      any = true;
    }
  }
  return any;
}

void CalibrationProblem::ComputeCovariance(CalibrationResult* result) {
  // The marginal covariance of the calibration parameters (estimation/marginal_covariance.h),
  // with every other free block -- control poses, bias spline, gravity, inverse depths -- as
  // nuisance. Always the Schur backend: it needs only the nuisance block H_aa to be positive
  // definite and tests the calibration parameters' own complement for singularity, so a weakly
  // determined landmark depth does not withhold the calibration's standard deviations.
  // Wanted: the cameras' blocks, then every bias control point; reported: the cameras' tangent
  // coordinates as they are and the biases' time averages (MeanBiasMap), q = A x.
  std::vector<const double*> wanted;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    if (!HeldToReference(c)) wanted.push_back(cameras_[c].extrinsic.data());
    if (options_.estimate_time_offset) wanted.push_back(&cameras_[c].time_offset_s);
    if (options_.rolling_shutter) wanted.push_back(&cameras_[c].line_delay);
  }
  std::map<const double*, int> offset;  // first row of each camera block in the covariance
  int num_camera = 0;
  for (const double* block : wanted) {
    offset[block] = num_camera;
    num_camera += problem().ParameterBlockTangentSize(block);
  }
  const int num_bias_points = spline_->bias_spline().num_points();
  for (int m = 0; m < num_bias_points; ++m) wanted.push_back(spline_->gyro_bias(m));
  for (int m = 0; m < num_bias_points; ++m) wanted.push_back(spline_->accel_bias(m));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(num_camera + 6, num_camera + 6 * num_bias_points);
  A.topLeftCorner(num_camera, num_camera).setIdentity();
  A.bottomRightCorner(6, 6 * num_bias_points) = spline_->MeanBiasMap(imu_);
  MarginalCovarianceOptions covariance_options;
  covariance_options.backend = CovarianceBackend::kSchur;
  covariance_options.num_threads = options_.solver.num_threads;
  covariance_options.reported_map = A;
  imu_noise_->AddToCovarianceOptions(
      spline_.get(), options_.covariance.robust_window_s, &covariance_options);
  const MarginalCovariance marginal =
      ComputeMarginalCovariance(&problem(), wanted, covariance_options);
  if (!marginal.ok) {
    result->warnings.push_back(
        "the covariance could not be computed (the problem is rank deficient: some parameter is "
        "not determined by the data); standard deviations are not reported");
    return;
  }
  const ReportedCovariance reported = ReportedCovarianceOf(marginal);
  const Eigen::MatrixXd& cov = reported.covariance;
  result->std_inflation = reported.inflation.maxCoeff();
  result->robust_clusters = marginal.num_clusters;
  auto block = [&](const double* a, int rows) {
    return Eigen::MatrixXd(cov.block(offset[a], offset[a], rows, rows));
  };
  result->covariance_ok = true;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraState& cam = cameras_[c];
    CameraEstimate& estimate = result->cameras[c];
    // A held camera shares camera 0's right tangent (reprojection_cost.h, T_cam_cref).
    const Eigen::MatrixXd cov6 = block(ExtrinsicBlock(c), 6);
    const Eigen::Matrix3d R = CameraFromImu(c).rotationMatrix();
    const Eigen::Matrix3d cov_t = R * cov6.topLeftCorner<3, 3>() * R.transpose();
    estimate.translation_std_m = cov_t.diagonal().cwiseMax(0.0).cwiseSqrt();
    estimate.rotation_std_deg =
        cov6.bottomRightCorner<3, 3>().diagonal().cwiseMax(0.0).cwiseSqrt() * kRadToDeg;
    if (options_.estimate_time_offset) {
      estimate.time_offset_std_s = std::sqrt(std::max(0.0, block(&cam.time_offset_s, 1)(0, 0)));
    }
    if (options_.rolling_shutter) {
      estimate.line_delay_std_s = std::sqrt(std::max(0.0, block(&cam.line_delay, 1)(0, 0)));
    }
  }
  const Eigen::VectorXd bias_std = cov.diagonal().tail(6).cwiseMax(0.0).cwiseSqrt();
  result->gyro_bias_std = bias_std.head<3>();
  result->accel_bias_std = bias_std.tail<3>();
  AddStandardDeviationWarnings(options_, imu_noise_->estimate(), result);
}

void CalibrationProblem::Collect(CalibrationResult* result) {
  result->layout = layout_;
  // Solved in the target's frame; written in the gravity-aligned world (calibrate.h).
  result->gravity_target = spline_->gravity_w();
  result->T_w_target =
      SE3d(GravityAlignedRotation(result->gravity_target), Eigen::Vector3d::Zero());
  result->gravity_w = result->T_w_target.so3() * result->gravity_target;
  result->control_poses.clear();
  const SE3Splined spline_t = Spline();  // T_t_s
  for (const SE3d& T_t_s : spline_t.control_poses()) {
    result->control_poses.push_back(result->T_w_target * T_t_s);
  }
  result->camchain = camchain_;
  result->cameras.resize(cameras_.size());
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraCalibration& out = result->camchain[c];
    out.T_cam_imu = CameraFromImu(c);
    out.time_offset_s = cameras_[c].time_offset_s;
    out.line_delay_s = cameras_[c].line_delay;
    result->cameras[c].calibration = out;
    result->cameras[c].time_offset_estimated = options_.estimate_time_offset;
    result->cameras[c].line_delay_estimated = options_.rolling_shutter;
  }
  // IMU residuals.
  const ImuResidualStatistics imu_stats =
      spline_->EvaluateImu(imu_, [&](const ImuSample& s, const ImuPrediction& p) {
        if (options_.keep_residuals) {
          result->imu_samples.push_back(
              {s.t_ns, p.gyro - s.gyro, p.accel - s.accel, p.gyro_bias, p.accel_bias});
        }
      });
  result->num_imu_samples = static_cast<int>(imu_.size());
  result->gyro_rms = imu_stats.gyro_rms;
  result->accel_rms = imu_stats.accel_rms;
  result->gyro_bias = imu_stats.mean_gyro_bias;
  result->accel_bias = imu_stats.mean_accel_bias;
  // Reprojection residuals (pixels, no weights, no robust loss).
  std::vector<double> cam_sq(cameras_.size(), 0.0);
  std::vector<std::set<std::pair<int64_t, int>>> cam_frames(cameras_.size());
  double all_sq = 0.0;
  int all_count = 0;
  for (const FrameResidual& r : frame_residuals_) {
    const TargetFrame& frame = target_frames_[r.frame];
    std::vector<double> e;
    if (!PixelErrors(r, &e)) continue;
    CameraEstimate& estimate = result->cameras[frame.cam];
    ++estimate.num_frames;
    for (size_t k = 0; k < frame.corners.size(); ++k) {
      const Eigen::Vector2d error(e[2 * k], e[2 * k + 1]);
      cam_sq[frame.cam] += error.squaredNorm();
      all_sq += error.squaredNorm();
      ++all_count;
      ++estimate.num_observations;
      if (options_.keep_residuals) {
        result->reprojection_samples.push_back(
            {frame.t_ns, frame.cam, frame.ids[k], frame.corners[k].uv, error});
      }
    }
  }
  std::set<int> landmarks_used;
  for (const LandmarkResidual& r : landmark_residuals_) {
    const Landmark& landmark = landmarks_[r.landmark];
    const Observation& obs = landmark.others[r.observation];
    std::vector<double> e;
    if (!PixelErrors(r, &e)) continue;
    landmarks_used.insert(r.landmark);
    const Eigen::Vector2d error(e[0], e[1]);
    cam_sq[landmark.cam] += error.squaredNorm();
    all_sq += error.squaredNorm();
    ++all_count;
    ++result->cameras[landmark.cam].num_observations;
    if (options_.keep_residuals) {
      result->reprojection_samples.push_back({obs.t_ns, obs.cam_id, landmark.id, obs.uv, error});
    }
  }
  result->num_landmarks = static_cast<int>(landmarks_used.size());
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const int count = result->cameras[c].num_observations;
    result->cameras[c].reprojection_rms_px = count > 0 ? std::sqrt(cam_sq[c] / count) : 0.0;
  }
  result->reprojection_rms_px = all_count > 0 ? std::sqrt(all_sq / all_count) : 0.0;
  std::sort(result->reprojection_samples.begin(),
            result->reprojection_samples.end(),
            [](const ReprojectionSample& a, const ReprojectionSample& b) {
              return std::tie(a.t_ns, a.cam_id, a.point_id) <
                     std::tie(b.t_ns, b.cam_id, b.point_id);
            });
}

}  // namespace

CalibrationResult Calibrate(const std::vector<ImuSample>& imu,
                            const std::vector<Observation>& all_observations,
                            const Camchain& camchain,
                            const CalibrationTarget* target,
                            const CalibrateOptions& given_options,
                            const CalibrationInitialGuess* guess) {
  CheckInputs(imu, all_observations, camchain, given_options);
  std::vector<std::string> warnings;
  const std::vector<Observation> observations =
      ObservationsInsideImu(imu, all_observations, camchain, &warnings);
  // Knot spacing 0: chosen from the gyro over the frames' time span, as `fit` chooses it.
  CalibrateOptions options = given_options;
  std::string knot_rule = "given (--knot-spacing)";
  if (guess != nullptr) {
    options.model.knot_spacing_s = guess->layout.dt_s();
    knot_rule = "the initial guess's";
  } else if (options.model.knot_spacing_s == 0.0) {
    const auto [start, end] = SpanOfFrames(imu, observations, camchain);
    const std::vector<ImuSample> span_imu = ImuBetween(imu, start, end);
    if (span_imu.size() < 2) throw Error("calibrate: fewer than 2 IMU samples during the frames");
    options.model.knot_spacing_s = ChooseKnotSpacing(span_imu, options.model.noise, &knot_rule);
  }
  if (target != nullptr) CheckTargetSeen(observations, *target);
  CheckRotationExcitation(imu, options.min_rotation_rate_rad_s);
  const auto init_start = std::chrono::steady_clock::now();
  CalibrationInitialGuess initial;
  if (guess != nullptr) {
    initial = *guess;
    if (initial.camchain.size() != camchain.size() ||
        static_cast<int>(initial.control_poses.size()) != initial.layout.num_control_poses)
      throw Error("calibrate: the initial guess does not match the camchain or its layout");
  } else if (target != nullptr) {
    if (options.solver.progress)
      options.solver.progress("calibrate: initial guess (PnP per frame, then fit)");
    initial = InitialGuessFromTarget(imu, observations, camchain, *target, options, &warnings);
  } else {
    throw Error(
        "calibrate: without a target the calibration needs an initial trajectory "
        "(CalibrationInitialGuess; e.g. from `splinecal align` on SLAM poses)");
  }
  CalibrationProblem problem(imu, camchain, options, initial, target != nullptr);
  problem.SetFramePeriods(FramePeriods(GroupIntoFrames(observations), camchain.size()));
  if (target != nullptr) {
    *problem.target_frames() =
        MakeTargetFrames(observations, *target, options.min_corners_per_frame);
  }
  *problem.landmarks() =
      MakeLandmarks(observations, target, initial.camchain, problem.Spline(), &warnings);
  if (problem.target_frames()->empty() && problem.landmarks()->empty()) {
    throw Error("calibrate: no usable frame: no frame has " +
                std::to_string(options.min_corners_per_frame) +
                " target corners and no landmark is seen twice");
  }
  const double init_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - init_start).count();
  CalibrationResult result = problem.Run();
  result.knot_spacing_s = initial.layout.dt_s();
  result.knot_spacing_rule = knot_rule;
  result.initialisation_time_s = init_time;
  result.warnings.insert(result.warnings.begin(), warnings.begin(), warnings.end());
  return result;
}

}  // namespace splinecal
