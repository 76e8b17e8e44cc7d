// The IMU models a calibration can estimate, named as Kalibr's `--imu-models` names them
// (kalibr_calibrate_imu_camera; docs/imu_models.md, docs/conventions.md "IMU models"):
//
//   calibrated                      gyro = C_i_b w_b + b_g,  accel = C_i_b f_b(r_b) + b_a
//   scale-misalignment              adds M_a, M_g (lower triangular), A (g-sensitivity), C_gyro_i
//   scale-misalignment-size-effect  adds the accelerometer axes' lever arms ry_i, rz_i (rx_i = 0)
#ifndef SPLINECAL_IMU_IMU_MODEL_KIND_H_
#define SPLINECAL_IMU_IMU_MODEL_KIND_H_

#include <string>

namespace splinecal {

enum class ImuModelKind {
  kCalibrated,
  kScaleMisalignment,
  kScaleMisalignmentSizeEffect,
};

// Kalibr's name of the model: "calibrated", "scale-misalignment", "scale-misalignment-size-effect".
const char* ImuModelName(ImuModelKind kind);

// The model named `name` (Kalibr's spelling); false, leaving *kind alone, for any other text.
bool ParseImuModelKind(const std::string& name, ImuModelKind* kind);

// The three names, comma separated, for messages and --help.
const char* ImuModelNames();

// Number of intrinsic parameters the model estimates on top of biases and the pose of the IMU:
// 0, 24 (M_a 6, M_g 6, A 9, C_gyro_i 3) and 30 (+ ry_i, rz_i).
int NumImuIntrinsicParameters(ImuModelKind kind);

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_MODEL_KIND_H_
