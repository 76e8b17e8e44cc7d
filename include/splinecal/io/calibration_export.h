// A camera-IMU calibration written in the files of the estimators it feeds (`splinecal export`,
// docs/export.md): OpenVINS, VINS-Mono / VINS-Fusion, basalt, and Kalibr's own files.
//
// Each format stores the same facts with its own conventions; docs/conventions.md, "Exported
// formats", has the table. In short (T_a_b maps points of frame b into frame a; splinecal keeps
// Kalibr's T_cam_imu and t_imu = t_cam + timeshift_cam_imu):
//
//   format    camera pose          time offset               IMU noise
//   kalibr    T_cam_imu            timeshift_cam_imu         Kalibr densities (imu.yaml)
//   openvins  T_imu_cam (inverse)  timeshift_cam_imu         Kalibr densities
//   vins      body_T_cam (inverse) td = timeshift_cam_imu    Kalibr densities under acc_n, ...
//   basalt    T_imu_cam as px py   cam_time_offset_ns        per-sample std (density sqrt(rate))
//             pz qx qy qz qw       = -timeshift [ns]         and bias random walk densities
//
// A camera model a format cannot hold is refused with a message naming the ones it can.
#ifndef SPLINECAL_IO_CALIBRATION_EXPORT_H_
#define SPLINECAL_IO_CALIBRATION_EXPORT_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/output_dir.h"

namespace splinecal {

enum class ExportFormat { kOpenVins, kVins, kBasalt, kKalibr };

// "openvins", "vins", "basalt", "kalibr"; false (format untouched) for any other name.
bool ParseExportFormat(const std::string& name, ExportFormat* format);
std::string ExportFormatName(ExportFormat format);
// The four names, comma-separated, for messages.
std::string ExportFormatNames();

// Everything an export needs, read from a calibration folder (ReadCalibrationForExport) or
// filled by a program.
struct CalibrationExport {
  // The cameras; T_cam_imu and the time offsets are meaningful when has_imu.
  Camchain camchain;
  // False for a camera-only calibration (`splinecal intrinsics`' camchain.yaml): the formats
  // that need the IMU (openvins, vins) refuse it.
  bool has_imu = true;
  // Kalibr's continuous-time densities and the IMU's sampling rate.
  ImuNoise imu_noise;
  // Where imu_noise came from (a file, or the estimate in result.yaml), for the summary.
  std::string imu_noise_source;
  // The biases' time averages from calibrate's result.yaml (zero when unknown); the
  // bias convention is docs/conventions.md's: reading = true + bias.
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // [m/s^2]
  std::string imu_topic = "/imu0";
  // The reference IMU's model (calibrate --imu-model's imu_models.yaml, its imu0; the
  // `calibrated` model at nominal when the folder has none): openvins carries it (docs/export.md).
  ImuCalibration imu_model;
  // cam_overlaps[i]: the cameras that saw the target at the same time as camera i (Kalibr's
  // cam_overlaps). Empty when unknown.
  std::vector<std::vector<int>> cam_overlaps;
};

// Reads a calibration folder:
//   camchain-imucam.yaml (calibrate's output) or, failing that, camchain.yaml (intrinsics'
//   output: has_imu = false);
//   the IMU noise: imu_yaml_path when not empty, else DIR/imu.yaml when present (allan's
//   output), else result.yaml's imu_noise (the densities calibrate used), else the EuRoC
//   ADIS16448 defaults (imu_noise_source says "assumed");
//   gyro_bias and accel_bias from result.yaml when present;
//   imu_model from imu_models.yaml's imu0 when present;
//   cam_overlaps from reprojection_errors.csv (calibrate) or observations.csv (cameras with an
//   observation at the same frame time), when present.
// Camera topics: the camchain's rostopic, else /camN/image_raw. Throws splinecal::Error naming
// the file and line of the first problem, or the folder when it holds no camchain.
CalibrationExport ReadCalibrationForExport(const std::string& dir,
                                           const std::string& imu_yaml_path = "");

// The files of `format`, named as the format's users expect them:
//   kalibr    camchain-imucam.yaml (camchain.yaml without an IMU), imu.yaml
//   openvins  kalibr_imucam_chain.yaml, kalibr_imu_chain.yaml
//   vins      vins_config.yaml, cam0.yaml, cam1.yaml, ...
//   basalt    calibration.json
// Throws splinecal::Error for a camera model the format cannot hold, or an IMU-less calibration
// for a format that needs the IMU.
std::vector<OutputFile> ExportCalibration(const CalibrationExport& calibration,
                                          ExportFormat format);

}  // namespace splinecal

#endif  // SPLINECAL_IO_CALIBRATION_EXPORT_H_
