// OpenVINS' two calibration files, as its EuRoC configuration (config/euroc_mav in
// rpng/open_vins) lays them out and its OpenCV FileStorage reader expects them:
//
//   kalibr_imucam_chain.yaml  per camera T_imu_cam (the inverse of Kalibr's T_cam_imu: camera
//                             into IMU), cam_overlaps, camera_model pinhole, distortion_model
//                             radtan | equidistant, intrinsics [fu fv pu pv], resolution,
//                             rostopic, timeshift_cam_imu (t_imu = t_cam + timeshift, Kalibr's)
//   kalibr_imu_chain.yaml     imu0: T_i_b, Kalibr's four densities, rostopic, time_offset,
//                             update_rate, and the IMU intrinsics of OpenVINS' "kalibr" model
//                             (Tw, R_IMUtoGYRO, Ta, R_IMUtoACC, Tg; below)
//
// OpenVINS' IMU intrinsics (its docs, "IMU Intrinsic Models"; ov_msckf's loader reads Tw, Ta,
// R_IMUtoACC, R_IMUtoGYRO, Tg and forms Dw = Tw^-1, Da = Ta^-1) correct a reading as
//   a_I = R_IMUtoACC^T Da (a_m - b_a)                w_I = R_IMUtoGYRO^T Dw (w_m - b_g - Tg a_I)
// with a_I the specific force in the IMU frame I. Inverted, with I = Kalibr's accelerometer frame
// i (the frame splinecal's T_cam_imu refers to):
//   a_m = Ta R_IMUtoACC a_I + b_a                    w_m = Tw R_IMUtoGYRO w_I + Tg a_I + b_g,
// and Kalibr's scale-misalignment model (docs/imu_models.md) is
//   a_m = M_a f_i + b_a                              w_m = M_g C_gyro_i w_i + A C_gyro_i f_i + b_g,
// so Ta = M_a, R_IMUtoACC = I, Tw = M_g, R_IMUtoGYRO = C_gyro_i, Tg = A C_gyro_i (Kalibr's A acts
// on the specific force in the gyro frame, OpenVINS' Tg on it in the IMU frame). M_a and M_g are
// lower triangular, so Da and Dw are too: OpenVINS' "kalibr" model (lower-triangular D'_6 and
// R_IMUtoGYRO) holds them exactly. The size effect's lever arms have no counterpart in OpenVINS:
// they are left out, and a comment in the file says so (docs/export.md).
//
// OpenVINS projects with pinhole-radtan (four coefficients) or pinhole-equi; pinhole-none is
// radtan with zero coefficients.
#include <Eigen/Core>
#include <string>

#include "export_formats.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_model_kind.h"
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
  const ImuCalibration& model = calibration.imu_model;
  const ImuIntrinsicsd& p = model.intrinsics;
  if (model.model == ImuModelKind::kCalibrated) {
    yaml.Comment("a calibrated IMU: no scale, misalignment or g-sensitivity");
  } else {
    yaml.Comment(std::string("Kalibr's ") + ImuModelName(model.model) +
                 " model: Tw = M_g, R_IMUtoGYRO = C_gyro_i, Ta = M_a, Tg = A C_gyro_i");
  }
  if (model.model == ImuModelKind::kScaleMisalignmentSizeEffect) {
    yaml.Comment("the size effect's lever arms ry_i, rz_i have no OpenVINS counterpart: left out");
  }
  yaml.Scalar("model", "kalibr");
  yaml.Matrix("Tw", p.M_g);
  yaml.Matrix("R_IMUtoGYRO", p.C_gyro_i);
  yaml.Matrix("Ta", p.M_a);
  yaml.Matrix("R_IMUtoACC", Eigen::Matrix3d::Identity());
  yaml.Matrix("Tg", p.A * p.C_gyro_i);
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
