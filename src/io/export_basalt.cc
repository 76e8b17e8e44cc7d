// basalt's calibration JSON (a cereal archive, value0), as basalt's own data/euroc_ds_calib.json
// lays it out:
//
//   T_imu_cam         per camera, camera into IMU (the inverse of Kalibr's T_cam_imu) as
//                     px py pz and the unit quaternion qx qy qz qw (Eigen's order)
//   intrinsics        camera_type and its parameters under basalt's names:
//                       pinhole-none -> pinhole  fx fy cx cy
//                       pinhole-equi -> kb4      fx fy cx cy k1 k2 k3 k4
//                       pinhole-fov  -> fov      fx fy cx cy w
//                       ds-none      -> ds       fx fy cx cy xi alpha
//                       eucm-none    -> eucm     fx fy cx cy alpha beta
//                       omni-none    -> ucm      fx fy cx cy alpha, with fx = fu / (1 + xi),
//                                                alpha = xi / (1 + xi): the same projection,
//                                                since (1 + xi)((1 - alpha) z + alpha |p|) =
//                                                z + xi |p|
//   resolution        [[width, height], ...]
//   calib_accel_bias  the bias, then the 6 entries of a scale/misalignment matrix (zero: a
//   calib_gyro_bias   calibrated IMU); 3 + 9 for the gyro. basalt subtracts the bias from the
//                     reading, splinecal's convention (reading = true + bias)
//   imu_update_rate   [Hz]
//   accel_noise_std, gyro_noise_std, accel_bias_std, gyro_bias_std: basalt's continuous-time
//                     noise and bias random-walk densities, Kalibr's four densities per axis
//   cam_time_offset_ns  basalt adds it to an image's time stamp to reach the IMU clock: Kalibr's
//                     timeshift_cam_imu in nanoseconds. One for the rig.
//   vignette          [] (not estimated); the mocap keys at identity and zero.
//
// basalt has no 4- or 5-coefficient radtan model, so pinhole-radtan is refused.
#include <cmath>

#include "export_formats.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

namespace {

// Cameras whose time offsets differ by more than this cannot share basalt's one offset [s].
constexpr double kMaxOffsetSpreadS = 1e-4;

std::string Number(double value) { return FormatDouble(value); }

std::string Array(const std::vector<double>& values) {
  std::string text = "[";
  for (size_t i = 0; i < values.size(); ++i) text += (i == 0 ? "" : ", ") + Number(values[i]);
  return text + "]";
}

// {"k": v, ...} on one line, values already formatted.
std::string Object(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string text = "{";
  for (size_t i = 0; i < entries.size(); ++i) {
    text += (i == 0 ? "\"" : ", \"") + entries[i].first + "\": " + entries[i].second;
  }
  return text + "}";
}

std::string PoseObject(const SE3d& T) {
  // q and -q are the same rotation; basalt's files have qw >= 0, and so do these.
  Eigen::Quaterniond q = T.so3().quaternion();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d& p = T.translation();
  return Object({{"px", Number(p.x())},
                 {"py", Number(p.y())},
                 {"pz", Number(p.z())},
                 {"qx", Number(q.x())},
                 {"qy", Number(q.y())},
                 {"qz", Number(q.z())},
                 {"qw", Number(q.w())}});
}

std::string IntrinsicsObject(const Camera& camera) {
  std::vector<std::pair<std::string, std::string>> p;
  std::string type;
  double fx = camera.fu;
  double fy = camera.fv;
  const Eigen::Vector2d& m = camera.projection_params;
  const auto add = [&](const char* name, double value) { p.push_back({name, Number(value)}); };
  if (camera.projection == ProjectionModel::kOmni) {
    type = "ucm";
    fx /= 1.0 + m[0];
    fy /= 1.0 + m[0];
  } else if (camera.projection == ProjectionModel::kDoubleSphere) {
    type = "ds";
  } else if (camera.projection == ProjectionModel::kEucm) {
    type = "eucm";
  } else if (camera.distortion == DistortionModel::kEquidistant) {
    type = "kb4";
  } else if (camera.distortion == DistortionModel::kFov) {
    type = "fov";
  } else {
    type = "pinhole";
  }
  add("fx", fx);
  add("fy", fy);
  add("cx", camera.pu);
  add("cy", camera.pv);
  if (type == "ucm") add("alpha", m[0] / (1.0 + m[0]));
  if (type == "ds") {
    add("xi", m[0]);
    add("alpha", m[1]);
  }
  if (type == "eucm") {
    add("alpha", m[0]);
    add("beta", m[1]);
  }
  if (type == "kb4") {
    for (int k = 0; k < 4; ++k) add(("k" + std::to_string(k + 1)).c_str(), camera.distortion_coeffs[k]);
  }
  if (type == "fov") add("w", camera.distortion_coeffs[0]);
  return Object({{"camera_type", "\"" + type + "\""}, {"intrinsics", Object(p)}});
}

}  // namespace

std::vector<OutputFile> ExportBasalt(const CalibrationExport& calibration) {
  RequireImu(calibration, "basalt");
  const Camchain& camchain = calibration.camchain;
  for (size_t i = 0; i < camchain.size(); ++i) {
    RequireCameraModel(calibration,
                       i,
                       "basalt",
                       {"pinhole-none", "pinhole-equi", "pinhole-fov", "ds-none", "eucm-none",
                        "omni-none"});
    if (std::abs(camchain[i].time_offset_s - camchain[0].time_offset_s) > kMaxOffsetSpreadS) {
      throw Error(StringPrintf(
          "basalt holds one time offset for all cameras; cam0's is %.6f s and cam%zu's %.6f s",
          camchain[0].time_offset_s, i, camchain[i].time_offset_s));
    }
  }
  const ImuNoise& noise = calibration.imu_noise;
  const auto per_axis = [](double v) { return Array({v, v, v}); };
  std::string poses, intrinsics, resolution;
  for (size_t i = 0; i < camchain.size(); ++i) {
    const std::string separator = i == 0 ? "\n      " : ",\n      ";
    poses += separator + PoseObject(camchain[i].T_cam_imu.inverse());
    intrinsics += separator + IntrinsicsObject(camchain[i].camera);
    resolution += separator + Array({static_cast<double>(camchain[i].camera.width),
                                     static_cast<double>(camchain[i].camera.height)});
  }
  std::vector<double> accel_bias(9, 0.0), gyro_bias(12, 0.0);
  for (int k = 0; k < 3; ++k) {
    accel_bias[k] = calibration.accel_bias[k];
    gyro_bias[k] = calibration.gyro_bias[k];
  }
  const SE3d identity;
  std::string text = "{\n  \"value0\": {\n";
  text += "    \"T_imu_cam\": [" + poses + "\n    ],\n";
  text += "    \"intrinsics\": [" + intrinsics + "\n    ],\n";
  text += "    \"resolution\": [" + resolution + "\n    ],\n";
  text += "    \"vignette\": [],\n";
  text += "    \"calib_accel_bias\": " + Array(accel_bias) + ",\n";
  text += "    \"calib_gyro_bias\": " + Array(gyro_bias) + ",\n";
  text += "    \"imu_update_rate\": " + Number(noise.update_rate_hz) + ",\n";
  text += "    \"accel_noise_std\": " + per_axis(noise.accelerometer_noise_density) + ",\n";
  text += "    \"gyro_noise_std\": " + per_axis(noise.gyroscope_noise_density) + ",\n";
  text += "    \"accel_bias_std\": " + per_axis(noise.accelerometer_random_walk) + ",\n";
  text += "    \"gyro_bias_std\": " + per_axis(noise.gyroscope_random_walk) + ",\n";
  text += "    \"T_mocap_world\": " + PoseObject(identity) + ",\n";
  text += "    \"T_imu_marker\": " + PoseObject(identity) + ",\n";
  text += "    \"mocap_time_offset_ns\": 0,\n";
  text += "    \"mocap_to_imu_offset_ns\": 0,\n";
  text += "    \"cam_time_offset_ns\": " +
          std::to_string(std::llround(camchain[0].time_offset_s * 1e9)) + "\n";
  text += "  }\n}\n";
  return {{"calibration.json", text}};
}

}  // namespace internal
}  // namespace splinecal
