// The initial guesses of `splinecal calibrate` (calib/calibrate.h): from the target by PnP and
// `fit`, or from given IMU poses.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "calibration_data.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/fit.h"
#include "splinecal/camera/pnp.h"
#include "splinecal/error.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

using internal::LayoutFor;
using internal::MakeTargetFrames;
using internal::TargetFrame;

namespace {

// PnP poses whose reprojection RMS exceeds this [px] are not used for the initial guess (a
// wrong detection or a strong rolling-shutter smear; the full problem still uses the frame).
constexpr double kMaxPnpRmsPx = 10.0;
// Fewer usable PnP poses than this make no initial trajectory.
constexpr int kMinPnpPoses = 10;
// A PnP pose farther than this from the trajectory fitted to the IMU and the other poses is left
// out of the initial fit: a flipped pose (the planar ambiguity of a small or distant target) or
// one of a frame stamped wrongly is tens of degrees off, where blur and detector noise leave
// tenths. Each pass fits the poses that agreed with the previous fit, so that the neighbours an
// outlier pulled away come back once it is out.
constexpr double kMaxPoseDisagreementRad = 5.0 * kDegToRad;
constexpr double kMaxPoseDisagreementM = 0.05;
constexpr int kMaxInitialFitPasses = 4;
// The noise a pose source is assumed to have in the initial fit, per axis.
struct PoseSigma {
  double m;    // position [m]
  double rad;  // rotation [rad]
};
// PnP poses of the target.
constexpr PoseSigma kPnpSigma = {0.003, 0.003};
// User-supplied initial IMU poses (SLAM after alignment): loose, as they only start the solve.
constexpr PoseSigma kInitialPoseSigma = {0.01, 0.01};

// The fitted spline re-sampled onto `layout` (dt / 10 steps over its valid range), in the
// fitted spline's trajectory model.
std::vector<SE3d> ResampleOnto(const SE3Splined& fitted, const KnotLayout& layout,
                               int num_threads) {
  std::vector<StampedPose> samples;
  const int64_t step = std::max<int64_t>(1, layout.dt_ns / 10);
  for (int64_t t = fitted.start_time_ns(); t <= fitted.end_time_ns(); t += step) {
    const SE3d T = fitted.PoseNs(t);
    samples.push_back({t, T.translation(), T.so3().quaternion()});
  }
  PoseFitOptions options;
  options.num_threads = num_threads;
  options.trajectory = fitted.model();
  return FitControlPoses(samples, layout, options).control_poses;
}

// An initial guess from the continuous-time fit of the IMU to `poses` (`source` names them in
// messages): the fitted trajectory on the calibration's layout, gravity and biases. The caller
// gives the pose weights and what else to estimate, and takes those estimates from `fit`.
CalibrationInitialGuess GuessFromFit(const std::vector<ImuSample>& imu,
                                     const std::vector<StampedPose>& poses,
                                     const std::vector<Observation>& observations,
                                     const Camchain& camchain,
                                     const CalibrateOptions& options,
                                     FitOptions fit_options,
                                     const std::string& source,
                                     std::vector<std::string>* warnings,
                                     FitResult* fit) {
  fit_options.model.knot_spacing_s = options.model.knot_spacing_s;
  fit_options.model.trajectory = options.model.trajectory;
  fit_options.model.gravity_m_s2 = options.model.gravity_m_s2;
  fit_options.model.noise = options.model.noise;
  // A starting point: the given noise weights it, and the calibration measures the noise.
  fit_options.model.imu_noise = ImuNoiseMode::kGiven;
  fit_options.warn_imu_residual_noise = false;
  fit_options.covariance.compute = false;
  fit_options.keep_samples = false;
  fit_options.max_residual_noise_ratio = 1e9;
  fit_options.solver.max_iterations = 30;
  fit_options.solver.num_threads = options.solver.num_threads;
  try {
    *fit = Fit(imu, poses, fit_options);
  } catch (const Error& e) {
    std::string message = e.what();
    if (message.rfind("fit: ", 0) == 0) message = message.substr(5);
    throw Error("calibrate: initial guess from the " + source + " failed: " + message);
  }
  if (warnings != nullptr) {
    for (const std::string& w : fit->warnings) warnings->push_back("initial guess: " + w);
  }
  CalibrationInitialGuess guess;
  guess.layout = LayoutFor(imu, observations, camchain, options.model.knot_spacing_s);
  guess.control_poses =
      ResampleOnto(fit->MakeSpline(), guess.layout, options.solver.num_threads);
  guess.gravity_w = fit->gravity_w;
  guess.gyro_bias = fit->gyro_bias;
  guess.accel_bias = fit->accel_bias;
  guess.camchain = camchain;
  return guess;
}

// Whether each pose (T_w_m of the pose source m at t_ns) lies within the disagreement bounds of
// the fit's T_w_s(t_ns + time offset) T_m_s^-1 (calib/fit.h); poses outside the fitted time range
// agree (nothing says otherwise).
std::vector<bool> PosesAgreeingWithFit(const std::vector<StampedPose>& poses, const FitResult& fit) {
  const SE3Splined spline = fit.MakeSpline();
  const SE3d T_s_m = fit.T_m_s.inverse();
  const int64_t offset_ns = std::llround(fit.time_offset_s * 1e9);
  std::vector<bool> agree(poses.size(), true);
  for (size_t i = 0; i < poses.size(); ++i) {
    const int64_t t_ns = poses[i].t_ns + offset_ns;
    if (t_ns < spline.start_time_ns() || t_ns > spline.end_time_ns()) continue;
    const SE3d measured(SO3d(poses[i].q), poses[i].p);
    const SE3d difference = (spline.PoseNs(t_ns) * T_s_m).inverse() * measured;
    agree[i] = difference.so3().Log().norm() <= kMaxPoseDisagreementRad &&
               difference.translation().norm() <= kMaxPoseDisagreementM;
  }
  return agree;
}

}  // namespace

CalibrationInitialGuess InitialGuessFromTarget(const std::vector<ImuSample>& imu,
                                               const std::vector<Observation>& observations,
                                               const Camchain& camchain,
                                               const CalibrationTarget& target,
                                               const CalibrateOptions& options,
                                               std::vector<std::string>* warnings) {
  // PnP per frame of cam0.
  std::vector<StampedPose> poses;
  int frames_tried = 0;
  for (const TargetFrame& frame :
       MakeTargetFrames(observations, target, options.min_corners_per_frame)) {
    if (frame.cam != 0) continue;
    ++frames_tried;
    std::vector<Eigen::Vector3d> p_t;
    std::vector<Eigen::Vector2d> uv;
    for (const TargetCornerObservation& c : frame.corners) {
      p_t.push_back(c.p_t);
      uv.push_back(c.uv);
    }
    PnpOptions pnp_options;
    pnp_options.min_points = options.min_corners_per_frame;
    const PnpResult pnp = SolvePnp(camchain[0].camera, p_t, uv, pnp_options);
    if (!pnp.ok || pnp.rms_px > kMaxPnpRmsPx) continue;
    const SE3d T_t_c = pnp.T_c_t.inverse();
    StampedPose pose;
    pose.t_ns = frame.t_ns;
    pose.p = T_t_c.translation();
    pose.q = T_t_c.so3().quaternion();
    poses.push_back(pose);
  }
  if (static_cast<int>(poses.size()) < kMinPnpPoses) {
    throw Error("calibrate: the target gives a pose in only " + std::to_string(poses.size()) +
                " of " + std::to_string(frames_tried) + " frames of cam0 with at least " +
                std::to_string(options.min_corners_per_frame) + " corners (need " +
                std::to_string(kMinPnpPoses) +
                "): check the target file (size, spacing, corner ids) and the intrinsics");
  }
  if (warnings != nullptr && static_cast<int>(poses.size()) < frames_tried) {
    warnings->push_back(std::to_string(frames_tried - static_cast<int>(poses.size())) + " of " +
                        std::to_string(frames_tried) +
                        " target frames gave no usable PnP pose (they still enter the "
                        "calibration)");
  }
  // The continuous-time fit to those camera poses: T_m_s = T_c_s (the camera is the pose source).
  FitOptions fit_options;
  fit_options.pose_sigma_m = kPnpSigma.m;
  fit_options.pose_sigma_rad = kPnpSigma.rad;
  fit_options.estimate_time_offset = options.estimate_time_offset;
  fit_options.time_offset_s = camchain[0].time_offset_s;
  fit_options.max_time_offset_s = options.max_time_offset_s;
  fit_options.estimate_extrinsic = true;
  fit_options.T_m_s = camchain[0].T_cam_imu;
  fit_options.solver.progress = nullptr;
  FitResult fit;
  CalibrationInitialGuess guess;
  std::vector<bool> used(poses.size(), true);
  std::vector<std::string> fit_warnings;
  for (int pass = 1;; ++pass) {
    std::vector<StampedPose> fitted;
    for (size_t i = 0; i < poses.size(); ++i) {
      if (used[i]) fitted.push_back(poses[i]);
    }
    fit_warnings.clear();
    guess = GuessFromFit(imu, fitted, observations, camchain, options, fit_options,
                         "target poses", &fit_warnings, &fit);
    const std::vector<bool> agree = PosesAgreeingWithFit(poses, fit);
    if (agree == used || pass == kMaxInitialFitPasses ||
        std::count(agree.begin(), agree.end(), true) < kMinPnpPoses) {
      break;
    }
    used = agree;
  }
  if (warnings != nullptr) {
    warnings->insert(warnings->end(), fit_warnings.begin(), fit_warnings.end());
    const int left_out = static_cast<int>(std::count(used.begin(), used.end(), false));
    if (left_out > 0) {
      warnings->push_back(StringPrintf(
          "initial guess: %d of %zu PnP poses lie more than %.0f deg or %.0f cm from the "
          "trajectory the IMU and the other poses give (a flipped pose of a small or distant "
          "target, or a frame stamped wrongly) and were left out of it (they still enter the "
          "calibration)",
          left_out, poses.size(), kMaxPoseDisagreementRad * kRadToDeg,
          100.0 * kMaxPoseDisagreementM));
    }
  }
  guess.camchain[0].T_cam_imu = fit.T_m_s;
  guess.camchain[0].time_offset_s = fit.time_offset_s;
  // Camera n > 0 starts where the camchain's T_cn_cnm1 puts it from the fitted cam0: a camchain
  // from `splinecal intrinsics` has the chain but no T_cam_imu (read as the identity, 90 deg
  // off on EuRoC), and a given T_cn_imu was relative to the given cam0, which the fit replaced.
  // From the identity, with the chain's prior, calibrate spent six rounds on a pixel sigma near
  // 3 px before the first converged solve (EuRoC imu_april, docs/calibrate.md).
  for (size_t c = 1; c < guess.camchain.size() && guess.camchain[c].T_cn_cnm1; ++c) {
    guess.camchain[c].T_cam_imu = *guess.camchain[c].T_cn_cnm1 * guess.camchain[c - 1].T_cam_imu;
  }
  return guess;
}

CalibrationInitialGuess InitialGuessFromImuPoses(const std::vector<ImuSample>& imu,
                                                 const std::vector<StampedPose>& poses,
                                                 const std::vector<Observation>& observations,
                                                 const Camchain& camchain,
                                                 const CalibrateOptions& options,
                                                 std::vector<std::string>* warnings) {
  FitOptions fit_options;
  fit_options.pose_sigma_m = kInitialPoseSigma.m;
  fit_options.pose_sigma_rad = kInitialPoseSigma.rad;
  FitResult fit;
  return GuessFromFit(
      imu, poses, observations, camchain, options, fit_options, "initial poses", warnings, &fit);
}

}  // namespace splinecal
