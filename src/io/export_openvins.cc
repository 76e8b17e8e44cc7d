// OpenVINS' two calibration files, as its EuRoC configuration (config/euroc_mav in
// rpng/open_vins) lays them out and its OpenCV FileStorage reader expects them:
//
//   kalibr_imucam_chain.yaml  per camera T_imu_cam (the inverse of Kalibr's T_cam_imu: camera
//                             into IMU), cam_overlaps, camera_model pinhole, distortion_model
//                             radtan | equidistant, intrinsics [fu fv pu pv], resolution,
//                             rostopic, timeshift_cam_imu (t_imu = t_cam + timeshift, Kalibr's)
//   kalibr_imu_chain.yaml     imu0: T_i_b, Kalibr's four densities, rostopic, time_offset,
//                             update_rate, and the IMU intrinsics of OpenVINS' "kalibr" model
//                             (Tw, R_IMUtoGYRO, Ta, R_IMUtoACC identity, Tg zero: a calibrated IMU)
//
// OpenVINS projects with pinhole-radtan (four coefficients) or pinhole-equi; pinhole-none is
// radtan with zero coefficients.
#include <Eigen/Core>

#include "export_formats.h"
#include "splinecal/error.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {
namespace internal {

namespace {

// OpenCV's FileStorage wants its own directive on the first line.
constexpr char kOpenCvYamlHeader[] = "%YAML:1.0\n";

std::string ImuCamChainText(const CalibrationExport& calibration) {
  YamlWriter yaml;
  for (size_t i = 0; i < calibration.camchain.size(); ++i) {
    const CameraCalibration& c = calibration.camchain[i];
    yaml.BeginMap("cam" + std::to_string(i));
    yaml.Comment("camera into IMU (R_CtoI, p_CinI): the inverse of Kalibr's T_cam_imu");
    yaml.Matrix("T_imu_cam", c.T_cam_imu.inverse().matrix());
    yaml.Vector("cam_overlaps",
                Eigen::Map<const Eigen::VectorXi>(c.cam_overlaps.data(), c.cam_overlaps.size())
                    .cast<double>());
    yaml.Scalar("camera_model", "pinhole");
    yaml.Vector("distortion_coeffs", FourDistortionCoeffs(calibration, i));
    yaml.Scalar("distortion_model",
                c.camera.distortion == DistortionModel::kEquidistant ? "equidistant" : "radtan");
    yaml.Vector("intrinsics", Eigen::Vector4d(c.camera.fu, c.camera.fv, c.camera.pu, c.camera.pv));
    yaml.Vector("resolution", Eigen::Vector2d(c.camera.width, c.camera.height));
    yaml.Scalar("rostopic", CameraTopic(calibration, i));
    yaml.Scalar("timeshift_cam_imu", c.time_offset_s);
    yaml.EndMap();
  }
  return kOpenCvYamlHeader + yaml.str();
}

std::string ImuChainText(const CalibrationExport& calibration) {
  const ImuNoise& noise = calibration.imu_noise;
  YamlWriter yaml;
  yaml.BeginMap("imu0");
  yaml.Matrix("T_i_b", Eigen::Matrix4d::Identity());
  yaml.Scalar("accelerometer_noise_density", noise.accelerometer_noise_density);
  yaml.Scalar("accelerometer_random_walk", noise.accelerometer_random_walk);
  yaml.Scalar("gyroscope_noise_density", noise.gyroscope_noise_density);
  yaml.Scalar("gyroscope_random_walk", noise.gyroscope_random_walk);
  yaml.Scalar("rostopic", calibration.imu_topic);
  // The camera's time offsets live in kalibr_imucam_chain.yaml; the IMU is the reference clock.
  yaml.Scalar("time_offset", 0.0);
  yaml.Scalar("update_rate", noise.update_rate_hz);
  yaml.Comment("a calibrated IMU: no scale, misalignment or g-sensitivity");
  yaml.Scalar("model", "kalibr");
  yaml.Matrix("Tw", Eigen::Matrix3d::Identity());
  yaml.Matrix("R_IMUtoGYRO", Eigen::Matrix3d::Identity());
  yaml.Matrix("Ta", Eigen::Matrix3d::Identity());
  yaml.Matrix("R_IMUtoACC", Eigen::Matrix3d::Identity());
  yaml.Matrix("Tg", Eigen::Matrix3d::Zero());
  yaml.EndMap();
  return kOpenCvYamlHeader + yaml.str();
}

}  // namespace

std::vector<OutputFile> ExportOpenVins(const CalibrationExport& calibration) {
  RequireImu(calibration, "openvins");
  for (size_t i = 0; i < calibration.camchain.size(); ++i) {
    RequireCameraModel(calibration, i, "openvins", {"pinhole-none", "pinhole-radtan", "pinhole-equi"});
    if (!RadtanHasNoK3(calibration, i)) {
      throw Error("openvins holds four radtan coefficients; cam" + std::to_string(i) +
                  " has k3 (calibrate with pinhole-radtan and four coefficients)");
    }
  }
  return {{"kalibr_imucam_chain.yaml", ImuCamChainText(calibration)},
          {"kalibr_imu_chain.yaml", ImuChainText(calibration)}};
}

}  // namespace internal
}  // namespace splinecal
