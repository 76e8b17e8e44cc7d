#include "splinecal/io/calibration_export.h"

#include <filesystem>

#include "export_formats.h"
#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/yaml_document.h"

namespace splinecal {

namespace {

struct FormatName {
  ExportFormat format;
  const char* name;
};
constexpr FormatName kFormatNames[] = {{ExportFormat::kOpenVins, "openvins"},
                                       {ExportFormat::kVins, "vins"},
                                       {ExportFormat::kBasalt, "basalt"},
                                       {ExportFormat::kKalibr, "kalibr"}};

bool IsFile(const std::string& path) { return std::filesystem::is_regular_file(path); }

// The densities calibrate weighted its IMU residuals with (result.yaml's imu_noise/*/used).
ImuNoise ImuNoiseFromResult(const YamlDocument& result) {
  ImuNoise noise;
  noise.gyroscope_noise_density = result.PositiveNumber("imu_noise/gyroscope_noise_density/used");
  noise.gyroscope_random_walk = result.PositiveNumber("imu_noise/gyroscope_random_walk/used");
  noise.accelerometer_noise_density =
      result.PositiveNumber("imu_noise/accelerometer_noise_density/used");
  noise.accelerometer_random_walk =
      result.PositiveNumber("imu_noise/accelerometer_random_walk/used");
  return noise;
}

Eigen::Vector3d ReadVector3(const YamlDocument& yaml, const std::string& key) {
  const std::vector<double> v = yaml.Numbers(key);
  if (v.size() != 3) throw Error(yaml.path(), yaml.Line(key), key + ": expected 3 numbers");
  return Eigen::Vector3d(v[0], v[1], v[2]);
}

std::vector<OutputFile> ExportKalibr(const CalibrationExport& calibration) {
  Camchain camchain = calibration.camchain;
  for (size_t i = 0; i < camchain.size(); ++i) {
    camchain[i].rostopic = internal::CameraTopic(calibration, i);
  }
  if (!calibration.has_imu) {
    return {{"camchain.yaml", CamchainYamlText(camchain, CamchainKeys::kCamerasOnly)}};
  }
  return {{"camchain-imucam.yaml", CamchainYamlText(camchain)},
          {"imu.yaml", ImuYamlText(calibration.imu_noise, calibration.imu_topic)}};
}

}  // namespace

bool ParseExportFormat(const std::string& name, ExportFormat* format) {
  for (const FormatName& f : kFormatNames) {
    if (name == f.name) {
      *format = f.format;
      return true;
    }
  }
  return false;
}

std::string ExportFormatName(ExportFormat format) {
  for (const FormatName& f : kFormatNames) {
    if (f.format == format) return f.name;
  }
  return "unknown";
}

std::string ExportFormatNames() {
  std::string names;
  for (const FormatName& f : kFormatNames) names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names;
}

CalibrationExport ReadCalibrationForExport(const std::string& dir,
                                           const std::string& imu_yaml_path) {
  CalibrationExport calibration;
  const std::string imucam = dir + "/camchain-imucam.yaml";
  const std::string cameras_only = dir + "/camchain.yaml";
  if (IsFile(imucam)) {
    calibration.camchain = ReadCamchainYaml(imucam);
  } else if (IsFile(cameras_only)) {
    calibration.camchain = ReadCamchainYaml(cameras_only);
    calibration.has_imu = false;
  } else {
    throw Error(dir + ": no camchain-imucam.yaml (calibrate's output) or camchain.yaml "
                "(intrinsics' output) in this folder");
  }

  const std::string result_path = dir + "/result.yaml";
  const bool has_result = calibration.has_imu && IsFile(result_path);
  const std::string folder_imu_yaml = dir + "/imu.yaml";
  if (!imu_yaml_path.empty()) {
    calibration.imu_noise = ReadImuYaml(imu_yaml_path);
    calibration.imu_noise_source = imu_yaml_path;
  } else if (IsFile(folder_imu_yaml)) {
    calibration.imu_noise = ReadImuYaml(folder_imu_yaml);
    calibration.imu_noise_source = folder_imu_yaml;
  } else if (has_result && YamlDocument(result_path).Has("imu_noise")) {
    calibration.imu_noise = ImuNoiseFromResult(YamlDocument(result_path));
    calibration.imu_noise_source = result_path + " (the densities calibrate used)";
  } else {
    calibration.imu_noise_source = "assumed: EuRoC's ADIS16448 (no imu.yaml, no result.yaml)";
  }
  if (has_result) {
    const YamlDocument result(result_path);
    if (result.Has("gyro_bias")) calibration.gyro_bias = ReadVector3(result, "gyro_bias");
    if (result.Has("accel_bias")) calibration.accel_bias = ReadVector3(result, "accel_bias");
    // The rate calibrate measured replaces an imu.yaml's nominal one only when no file was
    // given: a file the user names is taken as it is.
    if (imu_yaml_path.empty() && !IsFile(folder_imu_yaml) && result.Has("imu_rate_hz")) {
      calibration.imu_noise.update_rate_hz = result.PositiveNumber("imu_rate_hz");
    }
  }
  // calibrate --imu-model writes the model beside result.yaml; imu0 is the reference IMU, the
  // one the exported files describe.
  const std::string imu_models_path = dir + "/imu_models.yaml";
  if (calibration.has_imu && IsFile(imu_models_path)) {
    calibration.imu_model = ReadImuModelsYaml(imu_models_path).front();
  }
  return calibration;
}

std::vector<OutputFile> ExportCalibration(const CalibrationExport& calibration,
                                          ExportFormat format) {
  switch (format) {
    case ExportFormat::kOpenVins: return internal::ExportOpenVins(calibration);
    case ExportFormat::kVins: return internal::ExportVins(calibration);
    case ExportFormat::kBasalt: return internal::ExportBasalt(calibration);
    case ExportFormat::kKalibr: return ExportKalibr(calibration);
  }
  return {};
}

namespace internal {

void RequireCameraModel(const CalibrationExport& calibration,
                        size_t index,
                        const std::string& format,
                        const std::vector<std::string>& supported) {
  const std::string model = calibration.camchain[index].camera.model_name();
  for (const std::string& name : supported) {
    if (name == model) return;
  }
  std::string names;
  for (const std::string& name : supported) names += (names.empty() ? "" : ", ") + name;
  throw Error(format + " cannot hold cam" + std::to_string(index) + "'s camera model " + model +
              "; it holds: " + names + " (calibrate with one of those models to export)");
}

void RequireImu(const CalibrationExport& calibration, const std::string& format) {
  if (!calibration.has_imu) {
    throw Error(format + " needs the camera-IMU calibration (camchain-imucam.yaml from "
                "`splinecal calibrate`); this is a camera-only camchain.yaml");
  }
}

std::string CameraTopic(const CalibrationExport& calibration, size_t index) {
  const std::string& topic = calibration.camchain[index].rostopic;
  return topic.empty() ? "/cam" + std::to_string(index) + "/image_raw" : topic;
}

bool RadtanHasNoK3(const CalibrationExport& calibration, size_t index) {
  const Camera& camera = calibration.camchain[index].camera;
  return camera.distortion != DistortionModel::kRadTan ||
         (!camera.radtan_k3 && camera.distortion_coeffs[4] == 0.0);
}

Eigen::Vector4d FourDistortionCoeffs(const CalibrationExport& calibration, size_t index) {
  const Camera& camera = calibration.camchain[index].camera;
  if (camera.distortion == DistortionModel::kNone) return Eigen::Vector4d::Zero();
  // radtan (k1 k2 p1 p2) and equidistant (k1 k2 k3 k4) keep their first four coefficients in
  // Kalibr's order at d0..d3 (camera/camera_model.h).
  return camera.distortion_coeffs.head<4>();
}

}  // namespace internal
}  // namespace splinecal
