// `splinecal align`: visual-inertial alignment (vio/align.h). Camera poses known up to scale
// plus IMU readings give the metric scale, gravity in the first camera frame, velocities and the
// gyro bias; writes result.yaml and the IMU poses in a gravity-aligned world (aligned_poses.csv,
// EuRoC ground-truth format) for `fit --poses` or as the initial guess of `calibrate`.
#include <gflags/gflags.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/cli/console_text.h"
#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/poses.h"
#include "splinecal/report/align_report.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/string_printf.h"
#include "splinecal/vio/align.h"

DEFINE_string(camera_poses,
              "",
              "Camera poses T_c0_c up to scale: TUM trajectory (t tx ty tz qx qy qz qw) or EuRoC "
              "ground-truth format [path]");
DEFINE_bool(estimate_rotation_extrinsic,
            false,
            "Estimate the camera-IMU rotation by hand-eye (needs rotation about 2 axes or more); "
            "the translation of T_cam_imu is kept");

DEFINE_double(camera_position_std,
              0.005,
              "Camera position noise per frame and axis, metric [m]; weights the system");
DEFINE_double(camera_rotation_std,
              0.002,
              "Camera rotation noise per frame and axis [rad]; weights the system");

namespace splinecal {
namespace cli {
namespace {

// What align reads and checks before aligning anything (Command::read_inputs).
struct AlignInputs {
  AlignOptions options;
  std::vector<ImuSample> imu;
  std::vector<StampedPose> poses;
};

AlignInputs ReadAlignInputs() {
  const std::string& imu_path = RequiredFlag("imu", FLAGS_imu);
  const std::string& poses_path = RequiredFlag("camera-poses", FLAGS_camera_poses);
  RequiredFlag("out", FLAGS_out);
  AlignInputs in;
  AlignOptions& options = in.options;
  options.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  options.estimate_rotation_extrinsic = FLAGS_estimate_rotation_extrinsic;
  if (!FLAGS_imu_yaml.empty()) options.noise = ReadImuYaml(FLAGS_imu_yaml);
  options.accel_bias = Vector3Flag("accel-bias", FLAGS_accel_bias);
  options.camera_noise.position_std_m =
      PositiveFlag("camera-position-std", FLAGS_camera_position_std);
  options.camera_noise.rotation_std_rad =
      PositiveFlag("camera-rotation-std", FLAGS_camera_rotation_std);
  if (!FLAGS_camchain.empty()) {
    const CameraCalibration cam0 = ReadCam0Extrinsics(FLAGS_camchain);
    options.T_cam_imu = cam0.T_cam_imu;
    options.time_offset_s = cam0.time_offset_s;
  }
  in.imu = ReadEurocImu(imu_path, ImuReadOptionsFromFlags(/*takes_imu_yaml=*/true));
  in.poses = ReadPoses(poses_path);
  return in;
}

int RunAlign() {
  const AlignInputs in = ReadAlignInputs();
  const std::string& out_dir = FLAGS_out;
  const AlignOptions& options = in.options;
  const std::vector<ImuSample>& imu = in.imu;
  const std::vector<StampedPose>& poses = in.poses;
  OutputDir output(out_dir);

  Progress("align: " + std::to_string(poses.size()) + " camera poses, " +
           std::to_string(imu.size()) + " IMU samples");
  const AlignResult result = Align(imu, poses, options);
  if (!result.success) throw Error("alignment refused: " + result.message);

  Progress(StringPrintf(
      "align: gyro bias [%.6g %.6g %.6g] rad/s (%d iterations), free gravity %.6g m/s^2, "
      "refined in %d iterations, condition number %.3g",
      result.gyro_bias.x(),
      result.gyro_bias.y(),
      result.gyro_bias.z(),
      result.gyro_bias_iterations,
      result.free_gravity_c0.norm(),
      result.iterations,
      result.condition_number));

  output.WriteFiles(AlignOutputFiles(result, options));
  output.Commit();

  const Eigen::Vector3d g_w = result.R_w_c0 * result.gravity_c0;
  for (const std::string& warning : result.warnings) std::printf("warning: %s\n", warning.c_str());
  std::printf(
      "scale %.9g (std %.3g)\ngravity_c0 %s m/s^2 (world: [%.3g %.3g %.6f])\n"
      "gyro_bias %s rad/s\nwrote %s/result.yaml and aligned_poses.csv (%d frames)\n",
      result.scale,
      result.scale_std,
      BracketedVector(result.gravity_c0, "%.9f").c_str(),
      g_w.x(),
      g_w.y(),
      g_w.z(),
      BracketedVector(result.gyro_bias, "%.9f").c_str(),
      out_dir.c_str(),
      static_cast<int>(result.states_w.size()));
  return 0;
}

}  // namespace

Command AlignCommand() {
  return {"align",
          "visual-inertial alignment: scale, gravity, gyro bias from up-to-scale camera poses",
          "splinecal align --imu FILE --camera-poses FILE [--camchain FILE] [--imu-yaml FILE]\n"
          "    [--estimate-rotation-extrinsic] [--gravity M_S2] [--accel-bias X,Y,Z]\n"
          "    [--camera-position-std M] [--camera-rotation-std RAD] [--accel-unit m/s^2|g]\n"
          "    [--gyro-unit rad/s|deg/s] --out DIR",
          "Aligns camera poses T_c0_c known only up to scale (monocular SLAM, SfM) with IMU\n"
          "readings: preintegrates the IMU between camera frames, estimates the gyro bias from\n"
          "the relative rotations (and the camera-IMU rotation by hand-eye when asked), solves\n"
          "for velocities, gravity and scale, and refines gravity on the sphere of its known\n"
          "norm. Refuses (exit 2, no output) when the motion does not determine them. Writes\n"
          "result.yaml and aligned_poses.csv: the IMU poses T_w_s in a gravity-aligned world\n"
          "(z up, yaw-free R_w_c0), metric, with velocities and the gyro bias (EuRoC\n"
          "ground-truth format). Without --imu-yaml the EuRoC ADIS16448 densities weight the\n"
          "system. See docs/align.md.",
          {{"imu", ""},
           {"camera_poses", ""},
           {"camchain",
            "Kalibr camchain.yaml; cam0's T_cam_imu (and timeshift_cam_imu if present) are "
            "used [path]; without it T_cam_imu is the identity"},
           {"imu_yaml", "IMU noise densities, Kalibr imu.yaml [path]; weights the system"},
           {"estimate_rotation_extrinsic", ""},
           {"gravity", ""},
           {"accel_bias",
            "Known accelerometer bias b_a, x,y,z [m/s^2] (not estimated; an unknown bias along "
            "gravity goes into the scale, see docs/align.md)"},
           {"camera_position_std", ""},
           {"camera_rotation_std", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"out", ""}},
          &RunAlign,
          [] { ReadAlignInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
