// Kalibr's IMU result file (imu-*.yaml of kalibr_calibrate_imu_camera, one section per IMU):
//
//   imu0:
//     model: scale-misalignment          # calibrated | scale-misalignment |
//                                        # scale-misalignment-size-effect
//     T_i_b: [[1, 0, 0, 0], ...]         # 4x4: body (reference IMU) -> this IMU
//     time_offset: 0.0                   # [s], t_reference = t_stamp + time_offset
//     accelerometers:
//       M: [[m00, 0, 0], [m10, m11, 0], [m20, m21, m22]]
//       rx_i: [0, 0, 0]                  # size effect only (rx_i is 0 by definition)
//       ry_i: [x, y, z]                  # [m]
//       rz_i: [x, y, z]
//     gyroscopes:
//       M: [[...]]                       # lower triangular
//       A: [[...]]                       # [(rad/s)/(m/s^2)]
//       C_gyro_i: [[...]]                # rotation
//
// docs/imu_models.md; the parameters' meaning: imu/imu_intrinsics.h. The noise keys Kalibr writes
// in the same sections (accelerometer_noise_density, ..., rostopic, update_rate) are ignored here.
#ifndef SPLINECAL_IO_IMU_MODELS_YAML_H_
#define SPLINECAL_IO_IMU_MODELS_YAML_H_

#include <string>
#include <vector>

#include "splinecal/imu/imu_intrinsics.h"

namespace splinecal {

// The IMUs imu0, imu1, ... (consecutive, at least imu0) of `path`. A key a model needs is
// required (calibrated needs none: T_i_b and time_offset default to the identity and 0). imu0 is
// the reference: its T_i_b must be the identity and its time_offset 0. Throws Error naming the
// file and line for a missing or malformed key, an M with a non-zero upper triangle or a diagonal
// outside [0.5, 2], an A entry beyond 1 (rad/s)/(m/s^2), a rotation that is not one, a non-zero
// rx_i, or a lever arm beyond 1 m.
std::vector<ImuCalibration> ReadImuModelsYaml(const std::string& path);

// The file ReadImuModelsYaml reads (17 significant digits; rotations read back to rounding).
std::string ImuModelsYamlText(const std::vector<ImuCalibration>& imus);

}  // namespace splinecal

#endif  // SPLINECAL_IO_IMU_MODELS_YAML_H_
