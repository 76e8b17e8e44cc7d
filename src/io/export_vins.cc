// VINS-Mono / VINS-Fusion's configuration, laid out as VINS-Fusion's EuRoC example
// (config/euroc in HKUST-Aerial-Robotics/VINS-Fusion): one OpenCV FileStorage file with the
// topics, body_T_camN (camera into IMU, "body" being the IMU: the inverse of Kalibr's
// T_cam_imu), the IMU noise and td, and one camodocal camera file per camera.
//
//   td: VINS reads "image clock + td = IMU clock", Kalibr's timeshift_cam_imu. VINS holds one td
//       for the rig: cam0's is written, and cameras whose offsets differ by more than 0.1 ms are
//       refused (VINS would misplace their frames by that much).
//   acc_n, gyr_n, acc_w, gyr_w: VINS scales them with the integration step as continuous-time
//       densities, so Kalibr's densities go in unchanged. VINS-Fusion's own EuRoC files carry
//       hand-inflated values (acc_n 0.1 against the ADIS16448's 0.002): docs/export.md says why
//       a user may still inflate them.
//   cameras: camodocal's PINHOLE (pinhole-none, pinhole-radtan with four coefficients),
//       KANNALA_BRANDT (pinhole-equi: k2..k5 are Kalibr's k1..k4, mu mv u0 v0 its fu fv pu pv)
//       and MEI (omni-none, omni-radtan: xi, k1 k2 p1 p2, gamma1 gamma2 u0 v0). One or two
//       cameras of one image size.
//   The estimator's own settings (feature tracker, solver, loop closure) are VINS-Fusion's
//   EuRoC defaults, with estimate_extrinsic and estimate_td off: the calibration is trusted.
#include <cmath>

#include "export_formats.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

namespace {

// Cameras whose time offsets differ by more than this cannot share VINS' one td [s].
constexpr double kMaxTdSpreadS = 1e-4;

std::string Number(double value) { return FormatDouble(value); }

std::string OpenCvMatrix(const std::string& key, const Eigen::Matrix4d& m) {
  std::string text = key + ": !!opencv-matrix\n   rows: 4\n   cols: 4\n   dt: d\n   data: [";
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      text += Number(m(r, c));
      if (r < 3 || c < 3) text += c == 3 ? ",\n          " : ", ";
    }
  }
  return text + "]\n";
}

std::string CameraFileText(const CameraCalibration& c) {
  const Camera& camera = c.camera;
  std::string text = "%YAML:1.0\n---\n";
  const Eigen::Vector4d d = camera.distortion_coeffs.head<4>();
  const auto size = [&] {
    return "camera_name: camera\nimage_width: " + std::to_string(camera.width) +
           "\nimage_height: " + std::to_string(camera.height) + "\n";
  };
  if (camera.projection == ProjectionModel::kPinhole &&
      camera.distortion == DistortionModel::kEquidistant) {
    text += "model_type: KANNALA_BRANDT\n" + size() + "projection_parameters:\n";
    text += "   k2: " + Number(d[0]) + "\n   k3: " + Number(d[1]) + "\n   k4: " + Number(d[2]) +
            "\n   k5: " + Number(d[3]) + "\n";
    text += "   mu: " + Number(camera.fu) + "\n   mv: " + Number(camera.fv) +
            "\n   u0: " + Number(camera.pu) + "\n   v0: " + Number(camera.pv) + "\n";
    return text;
  }
  const Eigen::Vector4d radtan =
      camera.distortion == DistortionModel::kRadTan ? d : Eigen::Vector4d::Zero();
  const std::string distortion = "distortion_parameters:\n   k1: " + Number(radtan[0]) +
                                 "\n   k2: " + Number(radtan[1]) + "\n   p1: " +
                                 Number(radtan[2]) + "\n   p2: " + Number(radtan[3]) + "\n";
  if (camera.projection == ProjectionModel::kOmni) {
    text += "model_type: MEI\n" + size() + "mirror_parameters:\n   xi: " +
            Number(camera.projection_params[0]) + "\n" + distortion;
    text += "projection_parameters:\n   gamma1: " + Number(camera.fu) +
            "\n   gamma2: " + Number(camera.fv) + "\n   u0: " + Number(camera.pu) +
            "\n   v0: " + Number(camera.pv) + "\n";
    return text;
  }
  text += "model_type: PINHOLE\n" + size() + distortion;
  text += "projection_parameters:\n   fx: " + Number(camera.fu) + "\n   fy: " + Number(camera.fv) +
          "\n   cx: " + Number(camera.pu) + "\n   cy: " + Number(camera.pv) + "\n";
  return text;
}

}  // namespace

std::vector<OutputFile> ExportVins(const CalibrationExport& calibration) {
  RequireImu(calibration, "vins");
  const Camchain& camchain = calibration.camchain;
  if (camchain.size() > 2) {
    throw Error("vins holds one or two cameras; this calibration has " +
                std::to_string(camchain.size()) + " (calibrate --cameras I,J selects two)");
  }
  for (size_t i = 0; i < camchain.size(); ++i) {
    RequireCameraModel(calibration,
                       i,
                       "vins",
                       {"pinhole-none", "pinhole-radtan", "pinhole-equi", "omni-none",
                        "omni-radtan"});
    if (!RadtanHasNoK3(calibration, i)) {
      throw Error("vins holds four radtan coefficients; cam" + std::to_string(i) +
                  " has k3 (calibrate with four coefficients)");
    }
    if (camchain[i].camera.width != camchain[0].camera.width ||
        camchain[i].camera.height != camchain[0].camera.height) {
      throw Error("vins holds one image size for all cameras; cam0 is " +
                  StringPrintf("%dx%d, cam%zu %dx%d", camchain[0].camera.width,
                               camchain[0].camera.height, i, camchain[i].camera.width,
                               camchain[i].camera.height));
    }
    if (std::abs(camchain[i].time_offset_s - camchain[0].time_offset_s) > kMaxTdSpreadS) {
      throw Error(StringPrintf(
          "vins holds one time offset td for all cameras; cam0's is %.6f s and cam%zu's %.6f s",
          camchain[0].time_offset_s, i, camchain[i].time_offset_s));
    }
  }
  const ImuNoise& noise = calibration.imu_noise;
  std::string text = "%YAML:1.0\n\n# VINS-Mono / VINS-Fusion configuration written by splinecal export\n";
  text += "imu: 1\nnum_of_cam: " + std::to_string(camchain.size()) + "\n\n";
  text += "imu_topic: \"" + calibration.imu_topic + "\"\n";
  for (size_t i = 0; i < camchain.size(); ++i) {
    text += "image" + std::to_string(i) + "_topic: \"" + CameraTopic(calibration, i) + "\"\n";
  }
  text += "output_path: \"/tmp/vins_output/\"\n\n";
  for (size_t i = 0; i < camchain.size(); ++i) {
    text += "cam" + std::to_string(i) + "_calib: \"cam" + std::to_string(i) + ".yaml\"\n";
  }
  text += "image_width: " + std::to_string(camchain[0].camera.width) + "\n";
  text += "image_height: " + std::to_string(camchain[0].camera.height) + "\n\n";
  text += "# camera into IMU (body): the inverse of Kalibr's T_cam_imu; trusted, not estimated\n";
  text += "estimate_extrinsic: 0\n";
  for (size_t i = 0; i < camchain.size(); ++i) {
    text += OpenCvMatrix("body_T_cam" + std::to_string(i), camchain[i].T_cam_imu.inverse().matrix());
  }
  text += "\nmultiple_thread: 1\n\n";
  text += "max_cnt: 150\nmin_dist: 30\nfreq: 10\nF_threshold: 1.0\nshow_track: 1\nflow_back: 1\n\n";
  text += "max_solver_time: 0.04\nmax_num_iterations: 8\nkeyframe_parallax: 10.0\n\n";
  text += "# Kalibr's continuous-time densities (docs/export.md)\n";
  text += "acc_n: " + Number(noise.accelerometer_noise_density) + "\n";
  text += "gyr_n: " + Number(noise.gyroscope_noise_density) + "\n";
  text += "acc_w: " + Number(noise.accelerometer_random_walk) + "\n";
  text += "gyr_w: " + Number(noise.gyroscope_random_walk) + "\n";
  text += "g_norm: " + Number(kDefaultGravity) + "\n\n";
  text += "# image clock + td = IMU clock (Kalibr's timeshift_cam_imu)\n";
  text += "estimate_td: 0\ntd: " + Number(camchain[0].time_offset_s) + "\n\n";
  text += "load_previous_pose_graph: 0\npose_graph_save_path: \"/tmp/vins_output/pose_graph/\"\n";
  text += "save_image: 0\n";

  std::vector<OutputFile> files = {{"vins_config.yaml", text}};
  for (size_t i = 0; i < camchain.size(); ++i) {
    files.push_back({"cam" + std::to_string(i) + ".yaml", CameraFileText(camchain[i])});
  }
  return files;
}

}  // namespace internal
}  // namespace splinecal
