// `splinecal simulate`: realistic IMU data from a spline (sim/simulate_imu.h). The trajectory is an
// analytic one (sim/trajectories.h) or a recorded one (--trajectory-file), turned into spline
// control poses by a least-squares fit (estimation/pose_fit.h); the IMU readings are the spline's
// IMU model plus Kalibr noise. Writes a EuRoC folder (mav0/imu0, mav0/state_groundtruth_estimate0),
// spline.csv, imu.yaml and result.yaml (report/command_outputs.h) to --out. See docs/simulate.md.
#include <gflags/gflags.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/simulation_result.h"
#include "splinecal/sim/simulation_trajectory.h"
#include "splinecal/sim/trajectories.h"

DEFINE_string(trajectory_file,
              "",
              "Recorded trajectory to simulate instead, TUM or EuRoC ground truth [path]; its "
              "timestamps are kept");
DEFINE_double(imu_rate, 200.0, "IMU sample rate [Hz]");
DEFINE_double(camera_rate, 20.0, "Camera frame rate with --camchain [Hz]");
DEFINE_double(pixel_noise, 0.5, "Pixel noise with --camchain, std per coordinate [px]");
DEFINE_int32(landmarks, 0, "Natural landmarks to simulate with --camchain [count]");
DEFINE_bool(noise_free, false, "No white noise and no bias random walk (initial biases kept)");
DEFINE_double(gyroscope_noise_density, 1.6968e-4, "Gyro white noise density [rad/s/sqrt(Hz)]");
DEFINE_double(gyroscope_random_walk, 1.9393e-5, "Gyro bias random walk [rad/s^2/sqrt(Hz)]");
DEFINE_double(accelerometer_noise_density,
              2.0e-3,
              "Accelerometer white noise density [m/s^2/sqrt(Hz)]");
DEFINE_double(accelerometer_random_walk, 3.0e-3, "Accelerometer bias random walk [m/s^3/sqrt(Hz)]");

namespace splinecal {
namespace cli {
namespace {

// Beyond this many IMU samples the outputs no longer fit comfortably in memory (~200 bytes per
// sample with its ground truth): 2e7 is 27 hours at 200 Hz.
constexpr double kMaxSamples = 2e7;

bool IsDefault(const char* flag) { return gflags::GetCommandLineFlagInfoOrDie(flag).is_default; }

ImuNoise NoiseFromFlags() {
  const bool any_kalibr_flag =
      !IsDefault("gyroscope_noise_density") || !IsDefault("gyroscope_random_walk") ||
      !IsDefault("accelerometer_noise_density") || !IsDefault("accelerometer_random_walk");
  if (!FLAGS_imu_yaml.empty()) {
    if (any_kalibr_flag) {
      throw Error("give the noise either with --imu-yaml or with the Kalibr-key flags, not both");
    }
    return ReadImuYaml(FLAGS_imu_yaml);
  }
  ImuNoise noise;
  noise.gyroscope_noise_density =
      NonNegativeFlag("gyroscope_noise_density", FLAGS_gyroscope_noise_density);
  noise.gyroscope_random_walk =
      NonNegativeFlag("gyroscope_random_walk", FLAGS_gyroscope_random_walk);
  noise.accelerometer_noise_density =
      NonNegativeFlag("accelerometer_noise_density", FLAGS_accelerometer_noise_density);
  noise.accelerometer_random_walk =
      NonNegativeFlag("accelerometer_random_walk", FLAGS_accelerometer_random_walk);
  return noise;
}

// What simulate reads and checks before fitting or simulating anything (Command::read_inputs).
struct SimulateInputs {
  std::string out_dir;
  double rate_hz = 0.0;
  double knot_spacing_s = 0.0;
  int64_t knot_spacing_ns = 0;
  double duration_s = 0.0;
  SimulationOptions options;
  Camchain camchain;  // empty: no cameras
  CameraSimulationOptions camera_options;
  Eigen::Vector3d target_centre_w = Eigen::Vector3d::Zero();
  std::vector<ImuCalibration> more_imus;  // imu1, ... of --imu-intrinsics
  std::vector<StampedPose> poses;  // of --trajectory-file; empty for the other trajectories
  int64_t start_ns = 0;            // the simulated time range
  int64_t end_ns = 0;
};

SimulateInputs ReadSimulateInputs() {
  SimulateInputs in;
  in.out_dir = RequiredFlag("out", FLAGS_out);
  in.rate_hz = PositiveFlag("imu-rate", FLAGS_imu_rate);
  in.knot_spacing_s = KnotSpacingFlag(/*can_choose=*/false);  // no IMU data to choose it from
  in.knot_spacing_ns = SpanFlagNs("knot-spacing", in.knot_spacing_s);
  if (in.knot_spacing_ns < 1'000'000) {
    throw Error("--knot-spacing: must be at least 0.001 s, got " +
                std::to_string(in.knot_spacing_s));
  }
  in.duration_s = FLAGS_duration;
  const int64_t duration_ns = SpanFlagNs("duration", in.duration_s);
  SimulationOptions& options = in.options;
  options.imu_rate_hz = in.rate_hz;
  options.noise = NoiseFromFlags();
  options.noise.update_rate_hz = in.rate_hz;
  options.noise_free = FLAGS_noise_free;
  options.gyro_bias = Vector3Flag("gyro-bias", FLAGS_gyro_bias);
  options.accel_bias = Vector3Flag("accel-bias", FLAGS_accel_bias);
  options.seed = static_cast<uint64_t>(static_cast<int64_t>(FLAGS_seed));
  options.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  if (!FLAGS_imu_intrinsics.empty()) {
    std::vector<ImuCalibration> imus = ReadImuModelsYaml(FLAGS_imu_intrinsics);
    options.imu = imus.front();
    in.more_imus.assign(imus.begin() + 1, imus.end());
  }

  // Cameras (optional).
  CameraSimulationOptions& camera_options = in.camera_options;
  if (!FLAGS_camchain.empty()) {
    in.camchain = ReadCamchainYaml(FLAGS_camchain);
    camera_options.camera_rate_hz = PositiveFlag("camera-rate", FLAGS_camera_rate);
    camera_options.pixel_noise_px = NonNegativeFlag("pixel-noise", FLAGS_pixel_noise);
    camera_options.seed = options.seed + 100;
    if (FLAGS_landmarks < 0 || FLAGS_landmarks > 1000000) {
      throw Error("--landmarks: expected 0 to 1000000, got " + std::to_string(FLAGS_landmarks));
    }
    camera_options.num_landmarks = FLAGS_landmarks;
    if (!FLAGS_target.empty()) {
      camera_options.has_target = true;
      camera_options.target = ReadTargetYaml(FLAGS_target);
      camera_options.T_w_t = SE3d();  // the target lies in the world's z = 0 plane, at the origin
      in.target_centre_w = TargetCentre(camera_options.target, camera_options.T_w_t);
    }
    if (!camera_options.has_target && camera_options.num_landmarks == 0) {
      throw Error("--camchain needs --target FILE and/or --landmarks N: nothing to observe");
    }
  } else if (!FLAGS_target.empty() || FLAGS_landmarks != 0) {
    throw Error("--target and --landmarks need --camchain (the cameras that observe them)");
  }

  // The time range of each kind of trajectory.
  if (!FLAGS_trajectory_file.empty()) {
    if (!IsDefault("trajectory")) {
      throw Error("give either --trajectory or --trajectory-file, not both");
    }
    in.poses = ReadPoses(FLAGS_trajectory_file);
    in.start_ns = in.poses.front().t_ns;
    in.end_ns = in.poses.back().t_ns;
    if (!IsDefault("duration")) {
      const int64_t wanted_end = in.start_ns + duration_ns;
      if (wanted_end > in.end_ns) {
        throw Error(FLAGS_trajectory_file,
                    0,
                    "--duration " + std::to_string(in.duration_s) + " s is longer than the " +
                        "trajectory (" + std::to_string((in.end_ns - in.start_ns) * 1e-9) + " s)");
      }
      in.end_ns = wanted_end;
    }
    if (in.duration_s * in.rate_hz > kMaxSamples ||
        (in.end_ns - in.start_ns) * 1e-9 * in.rate_hz > kMaxSamples) {
      throw Error("simulation would produce more than 2e7 IMU samples: shorten it");
    }
    return in;
  }
  if (FLAGS_trajectory == "calibration") {
    if (in.camchain.empty()) throw Error("--trajectory calibration needs --camchain");
    in.start_ns = 1'000'000'000;
  } else {
    MakeTrajectory(FLAGS_trajectory, options.seed);  // refuses an unknown name
    // The first knot at t = 0 and the IMU from t_1 = one knot spacing (trajectory time 0).
    in.start_ns = in.knot_spacing_ns;
  }
  if (in.duration_s * in.rate_hz > kMaxSamples) {
    throw Error("--duration " + std::to_string(in.duration_s) + " s at " +
                std::to_string(in.rate_hz) + " Hz is more than 2e7 IMU samples: shorten it");
  }
  in.end_ns = in.start_ns + duration_ns;
  return in;
}

int RunSimulate() {
  SimulateInputs in = ReadSimulateInputs();
  const std::string& out_dir = in.out_dir;
  const SimulationOptions& options = in.options;
  const Camchain& camchain = in.camchain;
  const CameraSimulationOptions& camera_options = in.camera_options;
  const int64_t start_ns = in.start_ns;
  const int64_t end_ns = in.end_ns;
  OutputDir output(out_dir);  // an unwritable --out fails here, before any work

  SimulationTrajectory trajectory;
  trajectory.recorded_poses = std::move(in.poses);
  trajectory.recorded_source = FLAGS_trajectory_file;
  trajectory.name = FLAGS_trajectory;
  trajectory.seed = options.seed;
  trajectory.target_centre_w = in.target_centre_w;
  if (!camchain.empty()) trajectory.T_cam_imu = camchain.front().T_cam_imu;
  PoseFitOptions fit_options;
  fit_options.progress = [](const std::string& line) { Progress(line); };
  SimulationRun run;
  run.start_ns = start_ns;
  run.end_ns = end_ns;
  run.knot_spacing_s = in.knot_spacing_s;
  run.options = options;
  run.more_imus = in.more_imus;
  run.camchain = camchain;
  run.camera_options = camera_options;
  RunSimulation(trajectory, fit_options, &run);
  const PoseFitResult& fit = run.spline.fit;
  const std::vector<ImuSample>& imu = run.imu;
  const CameraSimulationResult& cameras = run.cameras;
  if (!camchain.empty()) {
    Progress("simulate: " + std::to_string(cameras.num_frames) + " camera frames, " +
             std::to_string(cameras.num_target_observations) + " target and " +
             std::to_string(cameras.num_landmark_observations) + " landmark observations");
  }

  output.WriteFiles(SimulationOutputFiles(run));
  output.Commit();

  if (HasImuModels(run)) {
    std::printf("simulated %zu IMU(s), imu0 model %s; wrote mav0/imu0..imu%zu/data.csv and "
                "imu_models.yaml\n",
                1 + run.more_imus.size(),
                ImuModelName(options.imu.model),
                run.more_imus.size());
  }
  std::printf(
      "simulated %zu IMU samples (%.6g s at %.6g Hz) on %s; spline fit RMS %.3g m, "
      "%.3g deg\nwrote %s/mav0/imu0/data.csv, "
      "mav0/state_groundtruth_estimate0/data.csv, spline.csv, imu.yaml, result.yaml\n",
      imu.size(),
      (end_ns - start_ns) * 1e-9,
      options.imu_rate_hz,
      run.spline.source.c_str(),
      fit.position_rms_m,
      fit.rotation_rms_deg,
      out_dir.c_str());
  return 0;
}

}  // namespace

Command SimulateCommand() {
  return {
      "simulate",
      "simulate IMU data (EuRoC format) with Kalibr noise from a spline trajectory",
      "splinecal simulate [--trajectory vio_course|figure8|random|calibration |\n"
      "    --trajectory-file FILE] [--duration S] [--imu-rate HZ] [--knot-spacing S] [--seed N]\n"
      "    [--gravity M_S2] [--imu-yaml FILE | --gyroscope_noise_density D\n"
      "    --gyroscope_random_walk D --accelerometer_noise_density D\n"
      "    --accelerometer_random_walk D] [--noise-free] [--camchain FILE [--target FILE]\n"
      "    [--landmarks N] [--camera-rate HZ] [--pixel-noise PX]] [--gyro-bias X,Y,Z]\n"
      "    [--accel-bias X,Y,Z] [--imu-intrinsics FILE] --out DIR",
      "Turns a trajectory into spline control poses (a least-squares fit to dense pose\n"
      "samples, or to the poses of --trajectory-file) and writes the spline's IMU readings\n"
      "at --imu-rate with Kalibr's noise model: white noise sigma*sqrt(f) per sample, a bias\n"
      "random walk with steps sigma_rw/sqrt(f), and constant initial biases. The same --seed\n"
      "gives byte-identical files. Writes DIR/mav0/imu0/data.csv (EuRoC IMU),\n"
      "DIR/mav0/state_groundtruth_estimate0/data.csv (pose, world velocity and true biases\n"
      "at every IMU time), DIR/spline.csv (the control poses), DIR/imu.yaml (the noise, Kalibr\n"
      "keys) and DIR/result.yaml (with the fit's RMS). With --noise-free and zero biases the\n"
      "IMU file is exactly the spline's prediction. --imu-intrinsics simulates Kalibr's IMU\n"
      "models (scale, misalignment, g-sensitivity, size effect) and further IMUs at their\n"
      "poses: DIR/mav0/imuN/data.csv and their truth DIR/imu_models.yaml (docs/imu_models.md).\n"
      "See docs/simulate.md.",
      {{"trajectory",
        "Trajectory: vio_course, figure8, random (seeded by --seed) or calibration (a lively "
        "motion over --target for camera-IMU calibration; needs --camchain)",
        "vio_course"},
       {"trajectory_file", ""},
       {"duration",
        "Duration [s] from the start; without the flag 20 s, or the whole --trajectory-file",
        "20"},
       {"imu_rate", ""},
       {"knot_spacing",
        "Spline knot spacing dt [s]; 0 is refused (no IMU data to choose it from)",
        "0.05"},
       {"seed", ""},
       {"gravity", ""},
       {"imu_yaml", "IMU noise densities, Kalibr imu.yaml [path] (instead of the flags below)"},
       {"gyroscope_noise_density", ""},
       {"gyroscope_random_walk", ""},
       {"accelerometer_noise_density", ""},
       {"accelerometer_random_walk", ""},
       {"noise_free", ""},
       {"camchain",
        "Cameras to simulate, Kalibr camchain.yaml (intrinsics, T_cam_imu, timeshift_cam_imu, "
        "line_delay) [path]; writes observations.csv"},
       {"target",
        "Calibration target seen by the cameras, Kalibr aprilgrid YAML or points YAML "
        "[path]; it lies in the world's z = 0 plane at the origin"},
       {"landmarks", ""},
       {"camera_rate", ""},
       {"pixel_noise", ""},
       {"gyro_bias", "Initial gyro bias b_g, x,y,z [rad/s]"},
       {"accel_bias", "Initial accelerometer bias b_a, x,y,z [m/s^2]"},
       {"imu_intrinsics",
        "IMU models and poses to simulate, Kalibr's imu-*.yaml layout (imu0: model, T_i_b, "
        "time_offset, accelerometers, gyroscopes; imu1: ...) [path]; imu0 is the spline's body"},
       {"out", ""}},
      &RunSimulate,
      [] { ReadSimulateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
