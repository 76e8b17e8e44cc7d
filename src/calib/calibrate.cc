#include "calibration_problem.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "splinecal/camera/observation_gates.h"
#include "splinecal/enum_names.h"

namespace splinecal {
namespace internal {
namespace {

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

// The refusal of a target whose scale the IMU contradicts (CalibrateOptions::target_scale).
std::string TargetScaleRefusal(double s, double std_s, const CalibrateOptions& options) {
  std::string fit;
  if (options.target_tag_size_m > 0.0) {
    fit = StringPrintf(" (tagSize %.4g m; %.3g m would fit)", options.target_tag_size_m,
                       s * options.target_tag_size_m);
  }
  return StringPrintf(
      "calibrate: the IMU says the target is %.3gx the size in %s%s: its scale is %.4f "
      "(std %.4f), off from 1 by more than %.0f%% and %.0f std; check the target's size "
      "(or the accelerometer's unit, --accel-unit)",
      s, options.target_name.c_str(), fit.c_str(), s, std_s,
      100.0 * options.max_target_scale_error, options.target_scale_sigmas);
}

}  // namespace


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
    if (HasIntrinsicsBlock(c)) {
      // Only the entries the camera model uses vary (camera/camera_model.h).
      const std::vector<int> active = camchain_[c].camera.ActiveIntrinsics();
      std::vector<int> held;
      for (int j = 0; j < kNumIntrinsics; ++j) {
        if (std::find(active.begin(), active.end(), j) == active.end()) held.push_back(j);
      }
      if (!held.empty() && cam.intrinsics_manifold == nullptr) {
        cam.intrinsics_manifold = std::make_shared<ceres::SubsetManifold>(kNumIntrinsics, held);
      }
      problem().AddParameterBlock(cam.intrinsics.data(), kNumIntrinsics,
                                  cam.intrinsics_manifold.get());
      // Considered intrinsics are held in the solve; their block is there for the covariance's
      // d theta / d c (ComputeCovariance).
      if (!EstimatesIntrinsics(c)) problem().SetParameterBlockConstant(cam.intrinsics.data());
    }
    // Both intervals are kept by the blocks' Plus, not by Ceres' bounds
    // (estimation/interval_manifold.h: bounds would double the Jacobian evaluations).
    if (options_.estimate_time_offset) {
      cam.time_offset_s =
          std::clamp(cam.time_offset_s, -options_.max_time_offset_s, options_.max_time_offset_s);
      cam.time_offset_manifold = std::make_shared<IntervalManifold>(-options_.max_time_offset_s,
                                                                    options_.max_time_offset_s);
      problem().AddParameterBlock(&cam.time_offset_s, 1, cam.time_offset_manifold.get());
    } else {
      problem().AddParameterBlock(&cam.time_offset_s, 1);
      problem().SetParameterBlockConstant(&cam.time_offset_s);
    }
    if (options_.rolling_shutter) {
      // The readout cannot exceed the frame period.
      cam.max_line_delay = frame_periods_[c] / std::max(1, height - 1);
      cam.line_delay = std::clamp(cam.line_delay, 0.0, cam.max_line_delay);
      cam.line_delay_manifold = std::make_shared<IntervalManifold>(0.0, cam.max_line_delay);
      problem().AddParameterBlock(&cam.line_delay, 1, cam.line_delay_manifold.get());
      if (cam.line_delay_held) problem().SetParameterBlockConstant(&cam.line_delay);
    } else {
      problem().AddParameterBlock(&cam.line_delay, 1);
      problem().SetParameterBlockConstant(&cam.line_delay);
    }
  }
  // The camchain's priors (calib/camchain_prior.h).
  prior_blocks_.clear();
  for (size_t c = 0; c < cameras_.size(); ++c) {
    std::vector<double*> blocks;
    std::unique_ptr<CamchainPriorCostFunction> prior = PriorCost(c, &blocks);
    if (prior) prior_blocks_.insert(problem().AddResidualBlock(prior.release(), nullptr, blocks));
  }
  if (target_scale_free_) problem().AddParameterBlock(&target_scale_, 1);
  spline_->AddImuResiduals(imu_, imu_noise_->gyro_sigma(), imu_noise_->accel_sigma());
  spline_->AddBiasRandomWalkResiduals(imu_noise_->densities());
  if (further_) further_->AddToProblem(spline_.get());
  // A residual that cannot be evaluated at the current values (a corner or landmark behind the
  // camera or outside its model's valid region: the trajectory is far off at that time) would
  // stop the solver at its first evaluation; it sits out this round and is counted. (The
  // spline's cache is current: Update() at the top of this function.)
  unprojectable_residuals_ = 0;
  std::vector<double> values;
  auto evaluates = [&values](const ceres::CostFunction& cost, const std::vector<double*>& blocks) {
    values.resize(cost.num_residuals());
    return cost.Evaluate(blocks.data(), values.data(), nullptr);
  };
  frame_residuals_.clear();
  for (size_t f = 0; f < target_frames_.size(); ++f) {
    const TargetFrame& frame = target_frames_[f];
    FrameResidual residual;
    residual.frame = static_cast<int>(f);
    if (!FrameWindow(frame.cam, frame.t_ns, kWindowMargin_s, &residual.window)) continue;
    std::unique_ptr<TargetFrameCostFunction> rows =
        FrameCost(residual, sigma_px_, options_.huber_px);
    // A global-shutter frame goes to Ceres compacted: same steps, ~35x fewer rows
    // (estimation/detail/compact_frame_cost.h).
    const bool global_shutter = !options_.rolling_shutter && cameras_[frame.cam].line_delay == 0.0;
    std::unique_ptr<ceres::CostFunction> cost;
    if (global_shutter && CompactFrameCostFunction::SavesRows(*rows)) {
      cost = std::make_unique<CompactFrameCostFunction>(std::move(rows));
    } else {
      cost = std::move(rows);
    }
    cost = ScaledFrameCost(std::move(cost), residual);
    const std::vector<double*> blocks = Blocks(residual);
    if (!evaluates(*cost, blocks)) {
      ++unprojectable_residuals_;
      continue;
    }
    residual.id = problem().AddResidualBlock(cost.release(), nullptr, blocks);
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
      std::unique_ptr<LandmarkCostFunction> cost =
          LandmarkCost(residual, sigma_px_, options_.huber_px);
      const std::vector<double*> blocks = Blocks(residual);
      if (!evaluates(*cost, blocks)) {
        ++unprojectable_residuals_;
        continue;
      }
      problem().AddResidualBlock(cost.release(), nullptr, blocks);
      landmark_residuals_.push_back(residual);
      added_rho = true;
    }
    // rho >= 0 by its Plus, not by a bound (estimation/interval_manifold.h).
    if (added_rho) problem().SetManifold(&landmark.rho, rho_manifold_.get());
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

std::unique_ptr<CamchainPriorCostFunction> CalibrationProblem::PriorCost(
    size_t c, std::vector<double*>* blocks) {
  if (c >= options_.camchain_covariances.size() || !options_.camchain_covariances[c]) return {};
  const CameraCovariance& covariance = *options_.camchain_covariances[c];
  const bool intrinsics = intrinsics_modes_[c] == ParameterMode::kPrior;
  const bool chain = c > 0 && chain_mode_ == ParameterMode::kPrior && covariance.has_T_cn_cnm1;
  if (!intrinsics && !chain) return {};
  // The rows of the covariance in the prior: a Gaussian's marginal is its sub-block.
  const int num_intrinsics = static_cast<int>(covariance.intrinsics.size());
  std::vector<int> rows;
  if (intrinsics) {
    for (int j = 0; j < num_intrinsics; ++j) rows.push_back(j);
  }
  if (chain) {
    for (int j = 0; j < kChainTangentSize; ++j) rows.push_back(num_intrinsics + j);
  }
  Eigen::MatrixXd sub(rows.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    for (size_t j = 0; j < rows.size(); ++j) sub(i, j) = covariance.matrix(rows[i], rows[j]);
  }
  std::optional<SE3d> T_cn_cnm1;
  if (chain) {
    T_cn_cnm1 = options_.camera_chain_T_cn_c0[c] * options_.camera_chain_T_cn_c0[c - 1].inverse();
  }
  blocks->clear();
  if (intrinsics) blocks->push_back(cameras_[c].intrinsics.data());
  if (chain) blocks->insert(blocks->end(), {ExtrinsicBlock(c), ExtrinsicBlock(c - 1)});
  return std::make_unique<CamchainPriorCostFunction>(
      intrinsics ? covariance.intrinsics : std::vector<int>(),
      camchain_[c].camera.intrinsics(),
      T_cn_cnm1,
      sub);
}

std::unique_ptr<ceres::CostFunction> CalibrationProblem::ScaledFrameCost(
    std::unique_ptr<ceres::CostFunction> cost, const FrameResidual& r) const {
  if (!target_scale_free_) return cost;
  return std::make_unique<TargetScaleCostFunction>(std::move(cost), r.window.num_poses);
}

std::vector<double*> CalibrationProblem::Blocks(const FrameResidual& r) {
  const int c = target_frames_[r.frame].cam;
  CameraState& cam = cameras_[c];
  std::vector<double*> blocks(control_blocks().begin() + r.window.first_index,
                              control_blocks().begin() + r.window.last_index() + 1);
  blocks.insert(blocks.end(),
                {ExtrinsicBlock(c), &cam.time_offset_s, &cam.line_delay, T_w_t_.data()});
  if (HasIntrinsicsBlock(c)) blocks.push_back(cam.intrinsics.data());
  if (target_scale_free_) blocks.push_back(&target_scale_);
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
    cost = ScaledFrameCost(FrameCost(r, 1.0, 0.0), r);
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
  const SolverOptions solver = spline_->ResolvedSolverOptions(options_.solver);
  ceres::Solver::Options solver_options = ToCeresOptions(solver, 0.0, nullptr);
  solver_options.update_state_every_iteration = true;  // for the StopWhen callbacks
  SolveRounds rounds(
      solver_options, options_.solver.progress, options_.solver.stop, solver.warm_start_rounds);
  target_scale_free_ = has_target_ && options_.target_scale != TargetScaleMode::kHeld;
  result.target_scale_mode = has_target_ ? options_.target_scale : TargetScaleMode::kHeld;
  if (options_.imu_model != ImuModelKind::kCalibrated) HoldUndeterminedImuModelParameters(&result);
  if (further_) {
    further_->Initialise(Spline(), spline_->gravity_w(), &result.warnings);
    further_->HoldUndeterminedLeverArms(Spline(), options_.max_lever_arm_std_m, &result.warnings);
    further_->HoldUndeterminedModelParameters(spline_.get(), &result.warnings);
  }
  SolveUntilStable(&rounds, solver, &result);
  if (target_scale_free_) {
    // The check (calibrate.h): the scale with everything else free, then held at 1.
    double std_s = std::numeric_limits<double>::quiet_NaN();
    const bool have_std = TargetScaleStd(&std_s);
    result.target_scale = target_scale_;
    result.target_scale_std = std_s;
    if (options_.target_scale == TargetScaleMode::kCheck) {
      const double error = std::abs(target_scale_ - 1.0);
      if (error > options_.max_target_scale_error &&
          (!have_std || error > options_.target_scale_sigmas * std_s)) {
        throw Error(TargetScaleRefusal(target_scale_, std_s, options_));
      }
      HoldTargetScale();
      if (options_.solver.progress) {
        options_.solver.progress(StringPrintf(
            "calibrate: target scale %.4f (std %.4f) against the IMU: held at 1, solving again",
            result.target_scale, std_s));
      }
      SolveUntilStable(&rounds, solver, &result);
    } else {
      result.target_scale_used = target_scale_;
    }
  }
  // A line delay still held: free for the covariance (its std is that of the unconstrained
  // model at the bound; a line delay at 0 within it is consistent with a global shutter).
  for (CameraState& cam : cameras_) {
    if (cam.line_delay_held) problem().SetParameterBlockVariable(&cam.line_delay);
  }
  if (most_unprojectable_ > 0) {
    result.warnings.push_back(
        unprojectable_in_last_round_ > 0
            ? StringPrintf("%d target frame(s) or landmark observation(s) do not project from the "
                           "trajectory (a point behind the camera or outside its model's valid "
                           "region) and were left out of the final solve: the trajectory is far "
                           "off at their times",
                           unprojectable_in_last_round_)
            : StringPrintf("%d target frame(s) or landmark observation(s) did not project from "
                           "the initial trajectory (a point behind the camera or outside its "
                           "model's valid region) and sat out the first round(s); all of them "
                           "entered the final solve",
                           most_unprojectable_));
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

void CalibrationProblem::HoldUndeterminedImuModelParameters(CalibrationResult* result) {
  // At the initial guess: the information of the model's parameters comes from the motion, which
  // the initial trajectory already has (estimation/imu_model_observability.h).
  BuildProblem();
  HoldRequestedImuModelParameters();
  const std::vector<ImuModelParameter> undetermined = UndeterminedImuModelParameters(spline_.get());
  if (undetermined.empty()) return;
  for (const ImuModelParameter& p : undetermined) spline_->HoldImuModelEntry(p.block, p.index);
  result->warnings.push_back(UndeterminedImuModelWarning(undetermined));
}

void CalibrationProblem::HoldRequestedImuModelParameters() {
  if (options_.imu_model_held.empty()) return;
  const std::vector<ImuModelParameter> parameters = ImuModelParameterStds(spline_.get());
  for (const std::string& name : options_.imu_model_held) {
    bool found = false;
    for (const ImuModelParameter& p : parameters) {
      if (p.name == name || p.name.rfind(name + "(", 0) == 0) {
        spline_->HoldImuModelEntry(p.block, p.index);
        found = true;
      }
    }
    if (!found) {
      throw Error("imu_model_held: " + name + " is not a parameter of the " +
                  ImuModelName(options_.imu_model) + " model");
    }
  }
}

void CalibrationProblem::SolveUntilStable(SolveRounds* solve_rounds,
                                          const SolverOptions& solver,
                                          CalibrationResult* result) {
  SolveRounds& rounds = *solve_rounds;
  for (int round = 1; round <= solver.max_rounds; ++round) {
    BuildProblem();
    if (frame_residuals_.empty() && landmark_residuals_.empty()) {
      throw Error(unprojectable_residuals_ > 0
                      ? "calibrate: no frame projects from the initial trajectory (every one "
                        "puts points behind the camera or outside its model's valid region); "
                        "check the camchain's intrinsics and T_cam_imu"
                      : "calibrate: no frame lies inside the spline's time range");
    }
    unprojectable_in_last_round_ = unprojectable_residuals_;
    most_unprojectable_ = std::max(most_unprojectable_, unprojectable_residuals_);
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
    if (result->pixel_sigma_estimated) {
      const double sigma = EstimatePixelSigma();
      if (std::abs(sigma / sigma_px_ - 1.0) > kSigmaChangeForNewRound) again = true;
      sigma_px_ = sigma;
    }
    // The IMU noise from the residuals (variance components): weights that match the data's
    // own noise, so that the covariance below reflects it.
    const double noise_change = imu_noise_->Update(spline_.get(), solver.num_threads);
    if (noise_change > kSigmaChangeForNewRound) again = true;
    const bool windows_valid = !guard.triggered() && WindowsStillValid();
    if (!windows_valid) again = true;
    // A further IMU's time offset that left its residuals' segments (further_imus.h).
    if (further_ && further_->NeedRebuild()) again = true;
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

}  // namespace internal

using internal::CalibrationProblem;

const char* ParameterModeName(ParameterMode mode) {
  static constexpr std::array<EnumName<ParameterMode>, 4> kNames = {{
      {ParameterMode::kHeld, "held"},
      {ParameterMode::kPrior, "prior"},
      {ParameterMode::kFree, "free"},
      {ParameterMode::kConsider, "consider"},
  }};
  return NameOf(kNames, mode);
}

const char* TargetScaleModeName(TargetScaleMode mode) {
  static constexpr std::array<EnumName<TargetScaleMode>, 3> kNames = {{
      {TargetScaleMode::kCheck, "check"},
      {TargetScaleMode::kFree, "free"},
      {TargetScaleMode::kHeld, "held"},
  }};
  return NameOf(kNames, mode);
}

namespace {

const CameraCovariance* CovarianceOf(const CalibrateOptions& options, size_t c) {
  if (c >= options.camchain_covariances.size() || !options.camchain_covariances[c]) return nullptr;
  return &*options.camchain_covariances[c];
}

// CalibrateOptions::intrinsics per camera (calibrate.h): the default kPrior where a covariance
// is given, else kHeld.
std::vector<ParameterMode> ResolveIntrinsicsModes(const CalibrateOptions& options,
                                                  size_t num_cameras) {
  std::vector<ParameterMode> modes(num_cameras, ParameterMode::kHeld);
  for (size_t c = 0; c < num_cameras; ++c) {
    if (options.intrinsics) {
      modes[c] = *options.intrinsics;
    } else if (options.estimate_intrinsics) {
      modes[c] = ParameterMode::kFree;
    } else {
      modes[c] = CovarianceOf(options, c) != nullptr ? ParameterMode::kPrior : ParameterMode::kHeld;
    }
    const bool needs_covariance =
        modes[c] == ParameterMode::kPrior || modes[c] == ParameterMode::kConsider;
    if (needs_covariance && CovarianceOf(options, c) == nullptr) {
      throw Error(std::string("calibrate: intrinsics ") + ParameterModeName(modes[c]) +
                  " needs the camchain's covariance, and cam" + std::to_string(c) +
                  " has none (splinecal_covariance, written by `splinecal intrinsics`)");
    }
  }
  return modes;
}

// CalibrateOptions::camera_chain (calibrate.h).
ParameterMode ResolveCameraChainMode(const CalibrateOptions& options, size_t num_cameras) {
  const bool chain_given = !options.camera_chain_T_cn_c0.empty();
  bool chain_covariances = chain_given && num_cameras > 1;
  for (size_t c = 1; c < num_cameras; ++c) {
    const CameraCovariance* covariance = CovarianceOf(options, c);
    if (covariance == nullptr || !covariance->has_T_cn_cnm1) chain_covariances = false;
  }
  ParameterMode mode = ParameterMode::kFree;
  if (options.camera_chain) {
    mode = *options.camera_chain;
    if (mode == ParameterMode::kConsider) {
      throw Error("calibrate: the camera chain can be held, prior or free; consider is for the "
                  "intrinsics");
    }
  } else if (chain_given) {
    mode = chain_covariances ? ParameterMode::kPrior : ParameterMode::kHeld;
  }
  if (mode != ParameterMode::kFree && num_cameras > 1 &&
      options.camera_chain_T_cn_c0.size() != num_cameras) {
    throw Error("calibrate: a held or prior camera chain needs T_cn_c0 for each of the " +
                std::to_string(num_cameras) + " cameras, got " +
                std::to_string(options.camera_chain_T_cn_c0.size()));
  }
  if (mode == ParameterMode::kPrior && !chain_covariances && num_cameras > 1) {
    throw Error("calibrate: a camera-chain prior needs every camera after cam0 to have a "
                "covariance with T_cn_cnm1 rows (splinecal_covariance, written by `splinecal "
                "intrinsics`)");
  }
  return mode;
}

}  // namespace

CalibrationResult Calibrate(const std::vector<ImuSample>& imu,
                            const std::vector<Observation>& all_observations,
                            const Camchain& camchain,
                            const CalibrationTarget* target,
                            const CalibrateOptions& given_options,
                            const CalibrationInitialGuess* guess) {
  CheckInputs(imu, all_observations, camchain, given_options);
  CheckFurtherImus(given_options.further_imus, ImuRateHz(imu));
  CheckObservationInputs(all_observations, target, camchain);  // target layout, image sizes
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
  if (target != nullptr) {
    CheckTargetSeen(observations, *target);
    if (options.target_tag_size_m <= 0.0) options.target_tag_size_m = target->tag_size_m;
  }
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
  if (!options.camchain_covariances.empty() &&
      options.camchain_covariances.size() != camchain.size()) {
    throw Error("calibrate: " + std::to_string(options.camchain_covariances.size()) +
                " camchain covariances for " + std::to_string(camchain.size()) + " cameras");
  }
  std::vector<ParameterMode> intrinsics_modes = ResolveIntrinsicsModes(options, camchain.size());
  const ParameterMode chain_mode = ResolveCameraChainMode(options, camchain.size());
  const bool any_intrinsics = std::any_of(intrinsics_modes.begin(), intrinsics_modes.end(),
                                          [](ParameterMode m) { return m != ParameterMode::kHeld; });
  CalibrationProblem problem(
      imu, camchain, options, initial, target != nullptr, intrinsics_modes, chain_mode);
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
  if (any_intrinsics && (target == nullptr || !problem.landmarks()->empty())) {
    throw Error("calibrate: estimated or considered intrinsics (--intrinsics prior, consider or "
                "free) need target corners "
                "only (landmark residuals take the intrinsics as given; --intrinsics held); the "
                "observations have " +
                std::to_string(problem.landmarks()->size()) + " landmark(s)");
  }
  CalibrationResult result = problem.Run();
  result.knot_spacing_s = initial.layout.dt_s();
  result.knot_spacing_rule = knot_rule;
  result.initialisation_time_s = init_time;
  result.warnings.insert(result.warnings.begin(), warnings.begin(), warnings.end());
  return result;
}

}  // namespace splinecal
