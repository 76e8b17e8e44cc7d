#include "splinecal/report/align_report.h"

#include <cstdint>

#include "splinecal/io/yaml_writer.h"

namespace splinecal {

namespace {

// One representative of q and -q: w >= 0.
Eigen::VectorXd QuaternionWxyz(const SO3d& R) {
  const Eigen::Quaterniond& q = R.quaternion();
  Eigen::VectorXd v(4);
  v << q.w(), q.x(), q.y(), q.z();
  if (v(0) < 0.0) v = -v;
  return v;
}

}  // namespace

std::string AlignResultYaml(const AlignResult& result, const AlignOptions& options) {
  YamlWriter yaml;
  yaml.Comment(
      "splinecal align: metric = scale * input camera positions; gravity_c0 in the first "
      "camera frame [m/s^2]; quaternions w x y z");
  yaml.Scalar("success", true);
  yaml.Scalar("message", result.message);
  yaml.Scalar("scale", result.scale);
  yaml.Scalar("scale_std", result.scale_std);
  yaml.Vector("gravity_c0", result.gravity_c0);
  yaml.Vector("gyro_bias", result.gyro_bias);
  yaml.Vector("R_w_c0", QuaternionWxyz(result.R_w_c0));
  if (result.rotation_extrinsic_estimated) {
    yaml.Vector("R_cam_imu", QuaternionWxyz(result.R_cam_imu));
  }
  yaml.Scalar("iterations", result.iterations);
  yaml.Scalar("condition_number", result.condition_number);
  yaml.Scalar("gyro_bias_iterations", result.gyro_bias_iterations);
  yaml.Scalar("rms_rotation_residual_rad", result.rms_rotation_residual_rad);
  yaml.Vector("free_gravity_c0", result.free_gravity_c0);
  yaml.Scalar("free_scale", result.free_scale);
  yaml.Scalar("free_scale_std", result.free_scale_std);
  yaml.Scalar("residual_noise_ratio", result.residual_noise_ratio);
  yaml.Scalar("scale_with_accel_bias", result.scale_with_accel_bias);
  yaml.Scalar("scale_with_accel_bias_std", result.scale_with_accel_bias_std);
  yaml.Vector("accel_bias_estimate", result.accel_bias_estimate);
  yaml.Vector("accel_bias_estimate_std", result.accel_bias_estimate_std);
  yaml.Scalar("refined_condition_number", result.refined_condition_number);
  yaml.Scalar("gravity_m_s2", options.gravity_m_s2);
  yaml.Vector("accel_bias_assumed", options.accel_bias);
  yaml.Scalar("camera_position_std_m", options.camera_noise.position_std_m);
  yaml.Scalar("camera_rotation_std_rad", options.camera_noise.rotation_std_rad);
  yaml.Scalar("num_frames", static_cast<int64_t>(result.states_w.size()));
  yaml.Scalar("num_ignored_frames", result.num_ignored_frames);
  yaml.StringList("warnings", result.warnings);
  return yaml.str();
}

}  // namespace splinecal
