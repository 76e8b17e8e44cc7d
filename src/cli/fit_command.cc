// `splinecal fit`: the continuous-time fit of IMU data and a pose source (calib/fit.h):
// biases, gravity, optionally the time offset and the extrinsic, with standard deviations and
// plain-words warnings. Writes result.yaml, spline.csv, residuals.csv, pose_residuals.csv and
// report.html (report/fit_report.h, docs/fit.md).
#include <gflags/gflags.h>

#include <cstdio>
#include <string>

#include "splinecal/calib/fit.h"
#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/cli/console_text.h"
#include "splinecal/error.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/poses.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/report/fit_report.h"
#include "splinecal/report/option_names.h"
#include "splinecal/units.h"

DEFINE_double(pose_sigma_m, 1e-3, "Pose source position noise, std per axis [m]");
DEFINE_double(pose_sigma_rad, 1e-3, "Pose source rotation noise, std per axis [rad]");
DEFINE_bool(estimate_time_offset,
            false,
            "Estimate the time offset t_imu = t_pose + offset (else it is 0)");
DEFINE_double(max_time_offset, 0.1, "Search range of the time offset, +- [s]");
DEFINE_bool(estimate_extrinsic,
            false,
            "Estimate T_pose_imu between the pose source's body frame and the IMU (else identity)");
DEFINE_string(bias_model, "constant", "IMU biases: constant, or spline (random-walk prior)");
DEFINE_double(bias_knot_spacing, 1.0, "Knot spacing of the bias spline [s] (--bias-model spline)");

namespace splinecal {
namespace cli {

namespace {

// What fit reads and checks before the solve (Command::read_inputs); Fit() checks the rest
// (time ranges, knot spacing) before it allocates.
struct FitInputs {
  FitOptions options;
  std::vector<ImuSample> imu;
  std::vector<StampedPose> poses;
};

FitInputs ReadFitInputs() {
  ImuInputName();  // exactly one of --imu and --bag, checked first
  const std::string& poses_path = RequiredFlag("poses", FLAGS_poses);
  RequiredFlag("out", FLAGS_out);
  FitInputs in;
  FitOptions& options = in.options;
  // Time spans through SpanFlagNs: bounded, so that the fit's int64 knot times cannot overflow.
  options.model.knot_spacing_s = KnotSpacingFlag(/*can_choose=*/true);
  options.model.trajectory = TrajectoryModelFlag();
  options.model.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  options.pose_sigma_m = PositiveFlag("pose-sigma-m", FLAGS_pose_sigma_m);
  options.pose_sigma_rad = PositiveFlag("pose-sigma-rad", FLAGS_pose_sigma_rad);
  options.estimate_time_offset = FLAGS_estimate_time_offset;
  SpanFlagNs("max-time-offset", FLAGS_max_time_offset);
  options.max_time_offset_s = FLAGS_max_time_offset;
  options.estimate_extrinsic = FLAGS_estimate_extrinsic;
  if (!ValueNamed(kBiasModelNames, FLAGS_bias_model, &options.model.bias_model)) {
    throw Error("--bias-model: expected " + JoinNames(kBiasModelNames, " or ") + ", got '" +
                FLAGS_bias_model + "'");
  }
  SpanFlagNs("bias-knot-spacing", FLAGS_bias_knot_spacing);
  options.model.bias_knot_spacing_s = FLAGS_bias_knot_spacing;
  options.solver.num_threads = ThreadsFlag();
  if (!Quiet()) options.solver.progress = [](const std::string& line) { Progress(line); };

  in.imu = ReadImuFlags(/*takes_imu_yaml=*/true);
  in.poses = ReadPoses(poses_path);
  if (!FLAGS_imu_yaml.empty()) options.model.noise = ReadImuYaml(FLAGS_imu_yaml);
  options.model.imu_noise = ImuNoiseModeFlag();
  return in;
}

int RunFit() {
  const FitInputs in = ReadFitInputs();
  const std::string& out_dir = FLAGS_out;
  OutputDir output(out_dir);

  const FitResult result = Fit(in.imu, in.poses, in.options);

  FitReportInputs inputs;
  inputs.imu_path = ImuInputName();
  inputs.poses_path = FLAGS_poses;
  inputs.imu_yaml_path = FLAGS_imu_yaml;
  output.WriteFiles(FitOutputFiles(result, inputs));
  output.Commit();

  std::printf("gyro_bias   %s rad/s   std %s\n",
              BracketedVector(result.gyro_bias, "%.6f").c_str(),
              BracketedVector(result.gyro_bias_std, "%.2g").c_str());
  std::printf("accel_bias  %s m/s^2   std %s\n",
              BracketedVector(result.accel_bias, "%.6f").c_str(),
              BracketedVector(result.accel_bias_std, "%.2g").c_str());
  std::printf("gravity_w   %s m/s^2   direction std %.2g deg\n",
              BracketedVector(result.gravity_w, "%.6f").c_str(),
              result.gravity_direction_std_deg);
  if (result.time_offset_estimated) {
    std::printf("time_offset %.6f ms   std %.2g ms\n",
                1e3 * result.time_offset_s,
                1e3 * result.time_offset_std_s);
  }
  if (result.extrinsic_estimated) {
    std::printf("T_pose_imu  t %s m, rotation vector %s deg\n",
                BracketedVector(result.T_m_s.translation(), "%.5f").c_str(),
                BracketedVector(result.T_m_s.so3().Log() * kRadToDeg, "%.4f").c_str());
  }
  std::printf(
      "residual RMS gyro %.3g rad/s (noise %.3g), accel %.3g m/s^2 (noise %.3g); "
      "%d iterations, %.3f s; knot spacing %.6g s\n",
      result.residual_rms.gyro_rad_s,
      result.noise_std.gyro_rad_s,
      result.residual_rms.accel_m_s2,
      result.noise_std.accel_m_s2,
      result.solve.iterations,
      result.solve.solve_time_s,
      result.knot_spacing_s);
  for (const std::string& warning : result.warnings) std::printf("warning: %s\n", warning.c_str());
  std::printf("wrote %s/{result.yaml,spline.csv,residuals.csv,pose_residuals.csv,report.html}\n",
              out_dir.c_str());
  return 0;
}

}  // namespace

Command FitCommand() {
  return {"fit",
          "fit IMU biases, gravity, time offset and extrinsic to IMU data and poses",
          "splinecal fit (--imu FILE | --bag FILE [--imu-topic T] [--bag-time header|receive])\n"
          "    --poses FILE --out DIR [--imu-yaml FILE] [--imu-noise MODE] [--knot-spacing S]\n"
          "    [--trajectory se3|split] [--pose-sigma-m M] [--pose-sigma-rad R]\n"
          "    [--estimate-time-offset] [--max-time-offset S] [--estimate-extrinsic]\n"
          "    [--bias-model constant|spline] [--bias-knot-spacing S] [--gravity M_S2]\n"
          "    [--accel-unit m/s^2|g] [--gyro-unit rad/s|deg/s] [--threads N]",
          "Fits a continuous-time spline T_w_s(t) of the IMU to its readings and to a pose source\n"
          "(motion capture, EuRoC ground truth or a TUM trajectory), with the gyro and\n"
          "accelerometer biases, the gravity direction and optionally the time offset\n"
          "(t_imu = t_pose + offset) and the extrinsic T_pose_imu. Standard deviations come from\n"
          "the solver's covariance; a parameter the data does not excite is named in plain words\n"
          "instead. Writes result.yaml, spline.csv, residuals.csv, pose_residuals.csv and\n"
          "report.html. See docs/fit.md.",
          WithFlags(ImuInputFlags(), {
           {"poses", ""},
           {"out", ""},
           {"imu_yaml", "IMU noise densities, Kalibr imu.yaml [path]; default ADIS16448"},
           {"imu_noise", ""},
           {"knot_spacing", "Spline knot spacing dt [s]; 0 chooses it from the IMU data", "0"},
           {"trajectory", kTrajectoryModelHelp, "se3"},
           {"pose_sigma_m", ""},
           {"pose_sigma_rad", ""},
           {"estimate_time_offset", ""},
           {"max_time_offset", ""},
           {"estimate_extrinsic", ""},
           {"bias_model", ""},
           {"bias_knot_spacing", ""},
           {"gravity", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"threads", ""},
           {"quiet", ""}}),
          &RunFit,
          [] { ReadFitInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
