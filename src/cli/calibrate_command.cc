// `splinecal calibrate`: camera-IMU calibration in continuous time, rolling shutter included
// (calib/calibrate.h). Reads the IMU (EuRoC imu0/data.csv), the detected points
// (observations.csv), the camera rig (Kalibr camchain.yaml) and optionally the target; writes
// camchain-imucam.yaml (Kalibr's keys), result.yaml, report.html, spline.csv and
// reprojection_errors.csv (report/calibrate_report.h). See docs/calibrate.md.
#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/calibrate_run.h"
#include "splinecal/calib/camera_selection.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observation_gates.h"
#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/bag_imu.h"
#include "splinecal/string_printf.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/camchain_yaml_covariance.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/calibrate_report.h"
#include "splinecal/report/command_outputs.h"

DEFINE_string(cameras,
              "",
              "Calibrate only these cameras of the camchain, comma-separated indices in "
              "increasing order (e.g. 0,2); the output camchain numbers them cam0, cam1, ... in "
              "this order. Default: all");
DEFINE_bool(rolling_shutter,
            false,
            "Estimate each camera's line_delay [s/row] (rolling shutter); without it the "
            "camchain's line_delay is kept (0: global shutter)");
DEFINE_bool(no_time_offset,
            false,
            "Keep the camchain's timeshift_cam_imu instead of estimating it");
DEFINE_double(pixel_sigma,
              0.0,
              "Pixel noise std [px] weighting the reprojection residuals; 0 estimates it from the "
              "residuals (robustly) and solves again");
DEFINE_string(intrinsics,
              "",
              "held | prior | consider | free: the cameras' intrinsics held at the camchain's, "
              "estimated with the camchain's covariance as a prior, held with that covariance "
              "carried into the other stds (consider), or estimated freely (all but held "
              "need --target and no natural landmarks). Default: prior for a camera whose "
              "camchain entry has a splinecal_covariance (`splinecal intrinsics` writes it), "
              "else held");
DEFINE_string(camera_chain,
              "",
              "held | prior | free: the cameras' relative poses T_cn_cnm1 held at the "
              "camchain's (one T_cam_imu for the rig), estimated with the covariance's "
              "T_cn_cnm1 rows as a prior, or free (each T_cam_imu on its own). Default: prior "
              "when every camera after cam0 has those rows, else free");
DEFINE_string(imu_model,
              "calibrated",
              "calibrated | scale-misalignment | scale-misalignment-size-effect: Kalibr's IMU "
              "model (--imu-models); the last two also estimate M_a, M_g, A, C_gyro_i (and the "
              "accelerometer axes' lever arms ry_i, rz_i), written to imu_models.yaml and "
              "result.yaml's imu_model (docs/imu_models.md). Several IMUs: one for all or one "
              "per IMU, comma-separated (each further IMU's model at its own pose)");
DEFINE_string(target_scale,
              "check",
              "check | free | held: the target's scale against the IMU (the accelerometer "
              "fixes metric scale). check: estimated, the calibration refused when it is off "
              "from 1 by more than 5% and 3 std, then held at 1; free: estimated and kept; "
              "held: 1, unchecked");
DEFINE_bool(estimate_intrinsics,
            false,
            "Deprecated: the same as --intrinsics free");
DEFINE_bool(hold_camera_chain,
            false,
            "Deprecated: the same as --camera-chain held");
DEFINE_string(initial_poses,
              "",
              "Initial IMU trajectory T_w_s in the IMU clock, EuRoC ground-truth or TUM format "
              "(e.g. aligned_poses.csv of `splinecal align` on SLAM poses) [path]; needed without "
              "--target, optional with it");

namespace splinecal {
namespace cli {
namespace {

// `splinecal calibrate` and every flag given, as typed (for result.yaml and report.html).
std::string CommandLineText() {
  std::string text = "splinecal calibrate";
  for (const FlagDoc& flag : CalibrateCommand().flags) {
    gflags::CommandLineFlagInfo info;
    if (!gflags::GetCommandLineFlagInfo(flag.name.c_str(), &info) || info.is_default) continue;
    std::string name = flag.name;
    std::replace(name.begin(), name.end(), '_', '-');
    if (info.type == "bool") {
      text += " --" + name + (info.current_value == "true" ? "" : "=false");
    } else {
      text += " --" + name + " " + info.current_value;
    }
  }
  return text;
}

// The rig's IMUs (docs/calibrate.md, "Several IMUs"): --imu a.csv,b.csv or --bag with
// --imu-topic t0,t1; --imu-yaml and --imu-model give one entry for every IMU or one per IMU. The
// first is the reference (`imu`, options->model.noise, options->imu_model); each further one
// becomes a FurtherImu.
void ReadRigImus(std::vector<ImuSample>* imu, CalibrateOptions* options) {
  const std::optional<BagImuSource> bag = BagImuFlags();
  const std::vector<std::string> sources =
      bag ? ListFlag("imu-topic", FLAGS_imu_topic) : ListFlag("imu", FLAGS_imu);
  const size_t n = sources.size();
  const std::vector<std::string> yamls = ListFlag("imu-yaml", FLAGS_imu_yaml);
  const std::vector<std::string> models = ListFlag("imu-model", FLAGS_imu_model);
  const std::string listed = bag ? "--imu-topic lists " : "--imu lists ";
  if (yamls.size() > 1 && yamls.size() != n) {
    throw Error("--imu-yaml: " + std::to_string(yamls.size()) + " files for " + std::to_string(n) +
                " IMU(s) (" + listed + std::to_string(n) + "): give one for all or one per IMU");
  }
  if (models.size() != 1 && models.size() != n) {
    throw Error("--imu-model: " + std::to_string(models.size()) + " models for " +
                std::to_string(n) + " IMU(s) (" + listed + std::to_string(n) +
                "): give one for all or one per IMU");
  }
  std::vector<ImuModelKind> kinds;
  for (size_t i = 0; i < n; ++i) {
    const std::string& model_name = models[models.size() == 1 ? 0 : i];
    ImuModelKind kind = ImuModelKind::kCalibrated;
    if (!ParseImuModelKind(model_name, &kind)) {
      throw Error("--imu-model: '" + model_name + "' is not one of " + ImuModelNames());
    }
    if (i == 0) options->imu_model = kind;
    kinds.push_back(kind);
  }
  const ImuReadOptions read = ImuReadOptionsFromFlags(/*takes_imu_yaml=*/true);
  double reference_rate_hz = 0.0;
  for (size_t i = 0; i < n; ++i) {
    std::vector<ImuSample> samples;
    std::string name = sources[i];
    if (bag) {
      BagImuSource source = *bag;
      source.topic = sources[i];
      name = source.Name();
      samples = ReadBagImu(source, read);
    } else {
      samples = ReadEurocImu(sources[i], read);
    }
    const ImuNoise noise =
        yamls.empty() ? ImuNoise::Adis16448() : ReadImuYaml(yamls[yamls.size() == 1 ? 0 : i]);
    // The library refuses another rate too (calib/calibrate.h); here the message names the file.
    const double rate_hz = ImuRateHz(samples);
    if (i == 0) {
      *imu = std::move(samples);
      options->model.noise = noise;
      reference_rate_hz = rate_hz;
      continue;
    }
    if (std::abs(rate_hz / reference_rate_hz - 1.0) > 0.01) {
      throw Error(name + ": IMU samples at " + StringPrintf("%.6g", rate_hz) + " Hz, the reference " +
                  sources[0] + " at " + StringPrintf("%.6g", reference_rate_hz) +
                  " Hz: every IMU must have the reference's rate (resample it first)");
    }
    options->further_imus.push_back({name, std::move(samples), noise, kinds[i]});
  }
}

// What calibrate reads and checks before the initial guess and the solve
// (Command::read_inputs); Calibrate() checks the rest (time ranges, motion) before it allocates.
struct CalibrateInputs {
  CalibrateOptions options;
  Camchain camchain;
  std::unique_ptr<CalibrationTarget> target;  // nullptr: landmarks only
  std::vector<Observation> observations;
  std::vector<ImuSample> imu;
  std::vector<StampedPose> initial_poses;  // empty without --initial-poses
};

CalibrateInputs ReadCalibrateInputs() {
  ImuInputName();  // exactly one of --imu and --bag, checked first
  const std::string& observations_path = RequiredFlag("observations", FLAGS_observations);
  const std::string& camchain_path = RequiredFlag("camchain", FLAGS_camchain);
  RequiredFlag("out", FLAGS_out);
  if (FLAGS_target.empty() && FLAGS_initial_poses.empty()) {
    throw Error(
        "without --target, --initial-poses is needed (the IMU trajectory, e.g. "
        "`splinecal align` on SLAM poses)");
  }
  CalibrateInputs in;
  CalibrateOptions& options = in.options;
  options.model.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  // 0: chosen from the IMU data (CalibrateOptions, estimation/knot_spacing.h).
  options.model.knot_spacing_s = KnotSpacingFlag(/*can_choose=*/true);
  options.model.trajectory = TrajectoryModelFlag();
  options.rolling_shutter = FLAGS_rolling_shutter;
  options.estimate_time_offset = !FLAGS_no_time_offset;
  options.pixel_sigma_px = NonNegativeFlag("pixel-sigma", FLAGS_pixel_sigma);
  options.huber_px = NonNegativeFlag("huber", FLAGS_huber);
  options.intrinsics = ParseParameterMode("--intrinsics", FLAGS_intrinsics,
                                          FLAGS_estimate_intrinsics, ParameterMode::kFree,
                                          "--estimate-intrinsics");
  options.camera_chain = ParseParameterMode("--camera-chain", FLAGS_camera_chain,
                                            FLAGS_hold_camera_chain, ParameterMode::kHeld,
                                            "--hold-camera-chain");
  options.target_scale = ParseTargetScaleMode("--target-scale", FLAGS_target_scale);
  options.command_line = CommandLineText();
  if (!FLAGS_target.empty()) options.target_name = FLAGS_target;
  if (FLAGS_min_corners < 4) throw Error("--min-corners: must be at least 4");
  options.min_corners_per_frame = FLAGS_min_corners;
  options.solver.num_threads = ThreadsFlag();
  options.solver.progress = [](const std::string& line) { Progress(line); };
  options.model.imu_noise = ImuNoiseModeFlag();

  in.camchain = ReadCamchainYaml(camchain_path);
  const std::vector<std::optional<CameraCovariance>> covariances =
      ReadCamchainCovariances(camchain_path, in.camchain);
  if (!FLAGS_target.empty()) {
    in.target = std::make_unique<CalibrationTarget>(ReadTargetYaml(FLAGS_target));
  }
  in.observations = ReadObservationsCsv(observations_path);
  // The library checks again (Calibrate); here the message names the files.
  CheckObservationInputs(in.observations,
                         in.target.get(),
                         in.camchain,
                         {observations_path, FLAGS_target, camchain_path});
  SelectCalibrationCameras(FLAGS_cameras,
                           camchain_path,
                           observations_path,
                           covariances,
                           &in.camchain,
                           &in.observations,
                           &options);
  ReadRigImus(&in.imu, &options);
  if (!FLAGS_initial_poses.empty()) in.initial_poses = ReadPoses(FLAGS_initial_poses);
  return in;
}

int RunCalibrate() {
  const CalibrateInputs in = ReadCalibrateInputs();
  const std::string& out_dir = FLAGS_out;
  const CalibrateOptions& options = in.options;
  const Camchain& camchain = in.camchain;
  const std::vector<Observation>& observations = in.observations;
  const std::vector<ImuSample>& imu = in.imu;
  OutputDir output(out_dir);
  if (FLAGS_imu_yaml.empty()) {
    Progress("calibrate: no --imu-yaml: weighting the IMU with the ADIS16448 (EuRoC) densities");
  }
  Progress("calibrate: " + std::to_string(observations.size()) + " observations, " +
           std::to_string(imu.size()) + " IMU samples, " + std::to_string(camchain.size()) +
           " camera(s)");
  CalibrationResult result;
  try {
    if (!in.initial_poses.empty()) {
      Progress("calibrate: initial guess from " + std::to_string(in.initial_poses.size()) +
               " initial poses");
    }
    result = CalibrateWithInitialPoses(
        imu, observations, camchain, in.target.get(), in.initial_poses, options);
  } catch (const Error& e) {
    // The library's messages start with "calibrate: "; the front end names the command already.
    const std::string prefix = "calibrate: ";
    if (e.path().empty() && e.message().rfind(prefix, 0) == 0) {
      throw Error(e.message().substr(prefix.size()));
    }
    throw;
  }

  // In CalibrateReportInputs' order: IMU, observations, camchain, target, initial poses, imu.yaml.
  const CalibrateReportInputs report_inputs = {ImuInputName(),
                                               FLAGS_observations,
                                               FLAGS_camchain,
                                               FLAGS_target,
                                               FLAGS_initial_poses,
                                               FLAGS_imu_yaml};
  output.WriteFiles(CalibrateOutputFiles(result, options, report_inputs));
  output.Commit();

  std::fputs(CalibrateSummaryText(result).c_str(), stdout);
  std::printf("wrote %s/camchain-imucam.yaml, result.yaml, report.html\n", out_dir.c_str());
  return 0;
}

// --imu, --bag, --imu-topic, --bag-time with calibrate's lists of IMUs.
std::vector<FlagDoc> RigImuFlags() {
  std::vector<FlagDoc> flags = ImuInputFlags();
  for (FlagDoc& flag : flags) {
    if (flag.name == "imu") {
      flag.help = "IMU samples, EuRoC imu0/data.csv [path]; several IMUs of one rig: "
                  "comma-separated, the first the reference (docs/calibrate.md); or --bag";
    } else if (flag.name == "imu_topic") {
      flag.help = "The IMU's ROS topic (sensor_msgs/Imu) in --bag; several IMUs: "
                  "comma-separated, the first the reference";
    }
  }
  return flags;
}

}  // namespace

Command CalibrateCommand() {
  return {"calibrate",
          "camera-IMU calibration in continuous time: T_cam_imu, time offset, rolling-shutter "
          "line delay",
          "splinecal calibrate (--imu FILE[,FILE...]\n"
          "    | --bag FILE [--imu-topic T[,T...]] [--bag-time header|receive])\n"
          "    --observations FILE --camchain FILE [--target FILE]\n"
          "    [--cameras I,J] [--initial-poses FILE] [--imu-yaml FILE[,FILE...]] [--imu-noise MODE] [--rolling-shutter] [--no-time-offset]\n"
          "    [--intrinsics held|prior|consider|free] [--camera-chain held|prior|free] [--target-scale check|free|held]\n"
          "    [--imu-model calibrated|scale-misalignment|scale-misalignment-size-effect]\n"
          "    [--hold-camera-chain] [--estimate-intrinsics]\n"
          "    [--knot-spacing S] [--trajectory se3|split] [--pixel-sigma PX] [--huber PX]\n"
          "    [--min-corners N] [--gravity M_S2] [--accel-unit m/s^2|g] [--gyro-unit rad/s|deg/s]\n"
          "    [--threads N]\n"
          "    --out DIR",
          "Fits camera observations (a calibration target's corners and/or natural landmarks,\n"
          "one row per detected point in observations.csv) and IMU readings jointly on one\n"
          "spline T_w_s(t): estimates T_cam_imu, timeshift_cam_imu (t_imu = t_cam + shift) and,\n"
          "with --rolling-shutter, the line delay (row r exposed at t_frame + r * line_delay),\n"
          "plus the trajectory, IMU biases and gravity. The camchain's intrinsics are held, or\n"
          "estimated with its covariance as a prior (--intrinsics); its T_cam_imu, time offset\n"
          "and line delay are the starting point. The target's scale is checked against the IMU. The target gives the\n"
          "initial guess (PnP per frame, then the fit of `splinecal fit`); without a target,\n"
          "--initial-poses does (e.g. `splinecal align` on SLAM poses). Writes\n"
          "camchain-imucam.yaml (Kalibr's keys), result.yaml with standard deviations and\n"
          "warnings, report.html, spline.csv and reprojection_errors.csv. See docs/calibrate.md.",
          WithFlags(RigImuFlags(), {
           {"observations", ""},
           {"camchain",
            "Camera rig, Kalibr camchain.yaml: intrinsics, distortion, resolution; "
            "T_cam_imu, timeshift_cam_imu, line_delay as the starting point [path]"},
           {"target",
            "Calibration target: Kalibr aprilgrid/checkerboard YAML or target_type: "
            "points [path]; point ids not in it are natural landmarks"},
           {"cameras", ""},
           {"initial_poses", ""},
           {"imu_yaml",
            "IMU noise densities, Kalibr imu.yaml [path], weighting the IMU residuals; several "
            "IMUs: one for all, or one per IMU, comma-separated (default: ADIS16448)"},
           {"imu_noise", ""},
           {"rolling_shutter", ""},
           {"intrinsics", ""},
           {"camera_chain", ""},
           {"target_scale", ""},
           {"imu_model", ""},
           {"hold_camera_chain", ""},
           {"estimate_intrinsics", ""},
           {"no_time_offset", ""},
           {"knot_spacing", "Spline knot spacing dt [s]; 0 chooses it from the IMU data", "0.05"},
           {"trajectory", kTrajectoryModelHelp, "se3"},
           {"pixel_sigma", ""},
           {"huber", ""},
           {"min_corners", ""},
           {"gravity", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"threads", ""},
           {"out", ""}}),
          &RunCalibrate,
          [] { ReadCalibrateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
