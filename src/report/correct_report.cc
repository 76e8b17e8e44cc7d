#include "splinecal/report/correct_report.h"

#include <sstream>

#include "splinecal/io/euroc.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {

CorrectRun RunCorrection(const ImuCalibration& imu,
                         const std::vector<ImuSample>& raw,
                         const ImuCorrectionOptions& options,
                         const CorrectSources& sources) {
  CorrectRun run;
  run.corrected = CorrectImuReadings(imu, raw, options);
  std::ostringstream csv;
  WriteEurocImu(run.corrected, &csv);
  YamlWriter yaml;
  yaml.Comment("splinecal correct: raw readings with the IMU model inverted (docs/imu_models.md)");
  yaml.Scalar("imu", sources.imu_path);
  yaml.Scalar("imu_intrinsics", sources.intrinsics_path);
  yaml.Scalar("imu_index", sources.imu_index);
  yaml.Scalar("model", ImuModelName(imu.model));
  yaml.Scalar("num_samples", static_cast<int64_t>(run.corrected.size()));
  yaml.Vector("gyro_bias_subtracted", options.gyro_bias);
  yaml.Vector("accel_bias_subtracted", options.accel_bias);
  yaml.Scalar("output_frame", "the IMU's accelerometer frame i, at its origin");
  if (imu.model == ImuModelKind::kScaleMisalignmentSizeEffect) {
    yaml.Scalar("angular_acceleration",
                "least-squares slope of the corrected gyro over 2h+1 samples");
    yaml.Scalar("derivative_half_window", options.derivative_half_window);
  }
  run.files = {{"mav0/imu0/data.csv", csv.str()}, {"result.yaml", yaml.str()}};
  return run;
}

}  // namespace splinecal
