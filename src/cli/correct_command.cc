// `splinecal correct`: applies an IMU calibration (Kalibr's imu-*.yaml: scale, misalignment,
// g-sensitivity, gyro frame, size effect) to raw readings by inverting the model
// (imu/correct_imu.h). Writes the corrected EuRoC file and result.yaml to --out. See
// docs/imu_models.md, "Applying a calibration".
#include <gflags/gflags.h>

#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/imu/correct_imu.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/report/correct_report.h"

DEFINE_int32(imu_index, 0, "Which IMU of --imu-intrinsics the readings are from (imuN) [index]");
DEFINE_int32(derivative_window,
             2,
             "Half width h of the size effect's angular-acceleration window: the slope of the "
             "corrected gyro over 2h+1 samples [samples]");

namespace splinecal {
namespace cli {
namespace {

struct CorrectInputs {
  std::string out_dir;
  std::string imu_path;
  std::string intrinsics_path;
  ImuCalibration imu;
  ImuCorrectionOptions options;
  std::vector<ImuSample> raw;
};

CorrectInputs ReadCorrectInputs() {
  CorrectInputs in;
  in.imu_path = RequiredFlag("imu", FLAGS_imu);
  in.intrinsics_path = RequiredFlag("imu-intrinsics", FLAGS_imu_intrinsics);
  in.out_dir = RequiredFlag("out", FLAGS_out);
  in.options.gyro_bias = Vector3Flag("gyro-bias", FLAGS_gyro_bias);
  in.options.accel_bias = Vector3Flag("accel-bias", FLAGS_accel_bias);
  if (FLAGS_derivative_window < 1 || FLAGS_derivative_window > 1000) {
    throw Error("--derivative-window: expected 1 to 1000 samples, got " +
                std::to_string(FLAGS_derivative_window));
  }
  in.options.derivative_half_window = FLAGS_derivative_window;
  const std::vector<ImuCalibration> imus = ReadImuModelsYaml(in.intrinsics_path);
  if (FLAGS_imu_index < 0 || FLAGS_imu_index >= static_cast<int>(imus.size())) {
    throw Error(in.intrinsics_path,
                0,
                "--imu-index " + std::to_string(FLAGS_imu_index) + ": the file has " +
                    std::to_string(imus.size()) + " IMU(s), imu0 to imu" +
                    std::to_string(imus.size() - 1));
  }
  in.imu = imus[FLAGS_imu_index];
  in.raw = ReadEurocImu(in.imu_path, ImuReadOptionsFromFlags());
  return in;
}

int RunCorrect() {
  const CorrectInputs in = ReadCorrectInputs();
  OutputDir output(in.out_dir);
  const CorrectRun run =
      RunCorrection(in.imu, in.raw, in.options, {in.imu_path, in.intrinsics_path, FLAGS_imu_index});
  output.WriteFiles(run.files);
  output.Commit();
  std::printf(
      "corrected %zu readings with the %s model of imu%d; wrote %s/mav0/imu0/data.csv, "
      "result.yaml\n",
      run.corrected.size(),
      ImuModelName(in.imu.model),
      FLAGS_imu_index,
      in.out_dir.c_str());
  return 0;
}

}  // namespace

Command CorrectCommand() {
  return {"correct",
          "apply an IMU calibration (Kalibr's IMU models) to raw IMU readings",
          "splinecal correct --imu FILE --imu-intrinsics FILE [--imu-index N]\n"
          "    [--gyro-bias X,Y,Z] [--accel-bias X,Y,Z] [--derivative-window H]\n"
          "    [--accel-unit U] [--gyro-unit U] --out DIR",
          "Inverts the IMU model of --imu-intrinsics (Kalibr's imu-*.yaml: calibrated,\n"
          "scale-misalignment or scale-misalignment-size-effect) on every raw reading of --imu:\n"
          "f_i = M_a^-1 (accel - b_a) - size effect, w_i = C_gyro_i^T M_g^-1 (gyro - b_g -\n"
          "A C_gyro_i f_i), the angular velocity and specific force of an ideal IMU at the\n"
          "IMU's origin in its accelerometer frame. The biases subtracted are the constants\n"
          "--gyro-bias and --accel-bias. The size effect's angular acceleration is the slope of\n"
          "the corrected gyro over 2h+1 samples (--derivative-window h). Writes\n"
          "DIR/mav0/imu0/data.csv (EuRoC, the raw timestamps) and DIR/result.yaml. See\n"
          "docs/imu_models.md.",
          {{"imu", "Raw IMU data, EuRoC imu0/data.csv [path]"},
           {"imu_intrinsics", "The calibration, Kalibr's imu-*.yaml layout [path]"},
           {"imu_index", ""},
           {"gyro_bias", "Constant gyro bias to subtract, x,y,z [rad/s]"},
           {"accel_bias", "Constant accelerometer bias to subtract, x,y,z [m/s^2]"},
           {"derivative_window", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"out", ""}},
          &RunCorrect,
          [] { ReadCorrectInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
