#include "splinecal/io/imu_models_yaml.h"

#include <cmath>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/io/yaml_transforms.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/lie/se3.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// Plausibility limits (a corrupt file or another unit beyond them): a scale factor off by 2x, a
// g-sensitivity of 1 (rad/s)/(m/s^2) (MEMS gyros: ~1e-3), an accelerometer axis 1 m from the
// IMU's origin (MEMS dies: millimetres), a clock offset of a day.
constexpr double kMinScale = 0.5;
constexpr double kMaxScale = 2.0;
constexpr double kMaxGSensitivity = 1.0;
constexpr double kMaxAxisLeverArmM = 1.0;
constexpr double kMaxTimeOffsetS = 86400.0;

// The keys of an imuN map: ours and the noise keys Kalibr writes beside them (ignored).
const std::vector<std::string> kImuKeys = {"model",
                                           "T_i_b",
                                           "time_offset",
                                           "accelerometers",
                                           "gyroscopes",
                                           "accelerometer_noise_density",
                                           "accelerometer_random_walk",
                                           "gyroscope_noise_density",
                                           "gyroscope_random_walk",
                                           "rostopic",
                                           "update_rate"};

Eigen::Matrix3d ReadLowerTriangular(const YamlDocument& yaml, const std::string& key) {
  const Eigen::Matrix3d M = ReadMatrix3(yaml, key);
  if (M(0, 1) != 0.0 || M(0, 2) != 0.0 || M(1, 2) != 0.0) {
    throw Error(yaml.path(),
                yaml.Line(key),
                key + ": must be lower triangular (Kalibr's M has zeros above the diagonal)");
  }
  for (int k = 0; k < 3; ++k) {
    if (!(M(k, k) >= kMinScale && M(k, k) <= kMaxScale)) {
      throw Error(yaml.path(),
                  yaml.Line(key),
                  key + ": diagonal entry " + FormatDouble(M(k, k)) +
                      " is not a plausible scale factor (0.5 to 2)");
    }
  }
  return M;
}

Eigen::Vector3d ReadLeverArm(const YamlDocument& yaml, const std::string& key) {
  const std::vector<double> v = yaml.BoundedNumbers(key, kMaxAxisLeverArmM, "m");
  if (v.size() != 3) {
    throw Error(yaml.path(), yaml.Line(key), key + ": expected 3 numbers [m]");
  }
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

ImuCalibration ReadImu(const YamlDocument& yaml, const std::string& imu, bool reference) {
  yaml.CheckTypos(imu, kImuKeys);
  ImuCalibration out;
  const std::string model_key = imu + "/model";
  const std::string model_name = yaml.String(model_key);
  if (!ParseImuModelKind(model_name, &out.model)) {
    throw Error(yaml.path(),
                yaml.Line(model_key),
                model_key + ": unknown IMU model '" + model_name + "' (expected one of " +
                    ImuModelNames() + ")");
  }
  ImuIntrinsicsd& p = out.intrinsics;
  if (yaml.Has(imu + "/T_i_b")) {
    const SE3d T_i_b = ReadRigidTransform(yaml, imu + "/T_i_b");
    p.C_i_b = T_i_b.rotationMatrix();
    p.r_b = -(p.C_i_b.transpose() * T_i_b.translation());  // T_i_b = [C_i_b, -C_i_b r_b]
    if (reference && (T_i_b.translation().norm() > 0.0 ||
                      !(p.C_i_b - Eigen::Matrix3d::Identity()).isZero(kMaxOrthonormalityError))) {
      throw Error(yaml.path(),
                  yaml.Line(imu + "/T_i_b"),
                  imu +
                      "/T_i_b: the first IMU is the reference (the body frame): its T_i_b "
                      "must be the identity");
    }
    if (reference) p = ImuIntrinsicsd();
  }
  if (yaml.Has(imu + "/time_offset")) {
    out.time_offset_s = yaml.BoundedNumber(imu + "/time_offset", kMaxTimeOffsetS, "s");
    if (reference && out.time_offset_s != 0.0) {
      throw Error(yaml.path(),
                  yaml.Line(imu + "/time_offset"),
                  imu + "/time_offset: the first IMU is the reference clock: must be 0");
    }
  }
  if (out.model == ImuModelKind::kCalibrated) return out;
  p.M_a = ReadLowerTriangular(yaml, imu + "/accelerometers/M");
  p.M_g = ReadLowerTriangular(yaml, imu + "/gyroscopes/M");
  p.A = ReadMatrix3(yaml, imu + "/gyroscopes/A");
  if (!(p.A.cwiseAbs().maxCoeff() <= kMaxGSensitivity)) {
    throw Error(yaml.path(),
                yaml.Line(imu + "/gyroscopes/A"),
                imu + "/gyroscopes/A: an entry beyond the plausible 1 (rad/s)/(m/s^2)");
  }
  p.C_gyro_i = ReadRotation(yaml, imu + "/gyroscopes/C_gyro_i").matrix();
  if (out.model == ImuModelKind::kScaleMisalignment) return out;
  if (yaml.Has(imu + "/accelerometers/rx_i") &&
      !ReadLeverArm(yaml, imu + "/accelerometers/rx_i").isZero(0.0)) {
    throw Error(yaml.path(),
                yaml.Line(imu + "/accelerometers/rx_i"),
                imu + "/accelerometers/rx_i: must be 0 (the x accelerometer is the IMU's origin)");
  }
  p.ry_i = ReadLeverArm(yaml, imu + "/accelerometers/ry_i");
  p.rz_i = ReadLeverArm(yaml, imu + "/accelerometers/rz_i");
  return out;
}

}  // namespace

std::vector<ImuCalibration> ReadImuModelsYaml(const std::string& path) {
  const YamlDocument yaml(path);
  if (!yaml.Has("imu0")) throw Error(path, 0, "no imu0 section (Kalibr's IMU result file)");
  std::vector<ImuCalibration> imus;
  for (int k = 0; yaml.Has("imu" + std::to_string(k)); ++k) {
    imus.push_back(ReadImu(yaml, "imu" + std::to_string(k), k == 0));
  }
  for (const std::string& key : yaml.TopLevelKeys()) {
    bool known = false;
    for (size_t k = 0; k < imus.size(); ++k) known |= key == "imu" + std::to_string(k);
    if (!known) {
      throw Error(path,
                  yaml.Line(key),
                  "unexpected top-level key '" + key + "' (expected imu0, imu1, ... in order)");
    }
  }
  return imus;
}

std::string ImuModelsYamlText(const std::vector<ImuCalibration>& imus) {
  YamlWriter yaml;
  for (size_t k = 0; k < imus.size(); ++k) {
    const ImuCalibration& imu = imus[k];
    const ImuIntrinsicsd& p = imu.intrinsics;
    yaml.BeginMap("imu" + std::to_string(k));
    yaml.Scalar("model", ImuModelName(imu.model));
    Eigen::Matrix4d T_i_b = Eigen::Matrix4d::Identity();
    T_i_b.topLeftCorner<3, 3>() = p.C_i_b;
    // + 0.0 turns the -0 of a zero r_b into 0.
    T_i_b.topRightCorner<3, 1>() = (-(p.C_i_b * p.r_b)).array() + 0.0;
    yaml.Matrix("T_i_b", T_i_b);
    yaml.Scalar("time_offset", imu.time_offset_s);
    if (imu.model != ImuModelKind::kCalibrated) {
      yaml.BeginMap("accelerometers");
      yaml.Matrix("M", p.M_a);
      if (imu.model == ImuModelKind::kScaleMisalignmentSizeEffect) {
        yaml.Vector("rx_i", Eigen::Vector3d::Zero());
        yaml.Vector("ry_i", p.ry_i);
        yaml.Vector("rz_i", p.rz_i);
      }
      yaml.EndMap();
      yaml.BeginMap("gyroscopes");
      yaml.Matrix("M", p.M_g);
      yaml.Matrix("A", p.A);
      yaml.Matrix("C_gyro_i", p.C_gyro_i);
      yaml.EndMap();
    }
    yaml.EndMap();
  }
  return yaml.str();
}

}  // namespace splinecal
