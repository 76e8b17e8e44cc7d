#include "splinecal/report/simulate_report.h"

#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {

bool HasImuModels(const SimulationRun& run) {
  return run.options.imu.model != ImuModelKind::kCalibrated || !run.more_imus.empty();
}

std::string SimulationImuModelsYaml(const SimulationRun& run) {
  std::vector<ImuCalibration> imus = {run.options.imu};
  imus.insert(imus.end(), run.more_imus.begin(), run.more_imus.end());
  return ImuModelsYamlText(imus);
}

std::string SimulationResultYaml(const SimulationRun& run) {
  const SimulationOptions& options = run.options;
  const PoseFitResult& fit = run.spline.fit;
  YamlWriter yaml;
  yaml.Comment(
      "splinecal simulate: IMU readings of the spline in spline.csv plus Kalibr noise "
      "(docs/simulate.md)");
  yaml.Scalar("trajectory", run.spline.source);
  yaml.Scalar("start_t_ns", run.start_ns);
  yaml.Scalar("end_t_ns", run.end_ns);
  yaml.Scalar("duration_s", (run.end_ns - run.start_ns) * 1e-9);
  yaml.Scalar("imu_rate_hz", options.imu_rate_hz);
  yaml.Scalar("num_imu_samples", static_cast<int64_t>(run.imu.size()));
  yaml.Scalar("seed", static_cast<int64_t>(options.seed));
  yaml.Scalar("gravity_m_s2", options.gravity_m_s2);
  yaml.Vector("gravity_w", Eigen::Vector3d(0.0, 0.0, -options.gravity_m_s2));
  yaml.Scalar("noise_free", options.noise_free);
  yaml.BeginMap("noise");
  yaml.Scalar("gyroscope_noise_density", options.noise.gyroscope_noise_density);
  yaml.Scalar("gyroscope_random_walk", options.noise.gyroscope_random_walk);
  yaml.Scalar("accelerometer_noise_density", options.noise.accelerometer_noise_density);
  yaml.Scalar("accelerometer_random_walk", options.noise.accelerometer_random_walk);
  yaml.EndMap();
  yaml.Vector("initial_gyro_bias", options.gyro_bias);
  yaml.Vector("initial_accel_bias", options.accel_bias);
  yaml.Vector("final_gyro_bias", run.truth.back().gyro_bias);
  yaml.Vector("final_accel_bias", run.truth.back().accel_bias);
  yaml.BeginMap("spline");
  yaml.Scalar("knot_spacing_s", run.knot_spacing_s);
  yaml.Scalar("t0_ns", fit.layout.t0_ns);
  yaml.Scalar("num_control_poses", static_cast<int64_t>(fit.control_poses.size()));
  yaml.Scalar("fit_num_poses", fit.num_poses);
  yaml.Scalar("fit_position_rms_m", fit.position_rms_m);
  yaml.Scalar("fit_rotation_rms_deg", fit.rotation_rms_deg);
  yaml.Scalar("fit_max_position_error_m", fit.max_position_error_m);
  yaml.Scalar("fit_max_rotation_error_deg", fit.max_rotation_error_deg);
  yaml.Scalar("fit_converged", fit.converged);
  yaml.EndMap();
  if (HasImuModels(run)) {
    yaml.Scalar("imu_model", ImuModelName(options.imu.model));
    yaml.Scalar("num_imus", static_cast<int64_t>(1 + run.more_imus.size()));
    yaml.Scalar("imu_models_file", "imu_models.yaml");
  }
  if (!run.camchain.empty()) {
    WriteCameraSimulationTruth(run.camchain, run.camera_options, run.cameras, &yaml);
  }
  return yaml.str();
}

}  // namespace splinecal
