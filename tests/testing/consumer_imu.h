// Test IMUs for Kalibr's IMU models (imu/imu_intrinsics.h), shared by the simulator, correct and
// file tests. Header-only; include as "testing/consumer_imu.h".
#ifndef SPLINECAL_TESTS_TESTING_CONSUMER_IMU_H_
#define SPLINECAL_TESTS_TESTING_CONSUMER_IMU_H_

#include <Eigen/Core>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace testing {

// A consumer-grade IMU at the body origin (Rehder et al., ICRA 2016's magnitudes): scale errors
// of ~1%, misalignments of ~0.5 deg, g-sensitivity ~1e-3 (rad/s)/(m/s^2), the gyro frame ~1 deg
// off, accelerometer axes 5-8 mm apart.
inline ImuCalibration ConsumerImu(ImuModelKind model) {
  ImuCalibration imu;
  imu.model = model;
  ImuIntrinsicsd& p = imu.intrinsics;
  p.M_a << 1.01, 0, 0, 0.008, 0.99, 0, -0.006, 0.004, 1.005;
  p.M_g << 0.99, 0, 0, -0.005, 1.012, 0, 0.007, -0.003, 1.008;
  p.A << 1e-3, -2e-4, 5e-4, 3e-4, -8e-4, 1e-4, -6e-4, 2e-4, 9e-4;
  p.C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.01, -0.015, 0.005)).matrix();
  p.ry_i = Eigen::Vector3d(0.005, 0.0, -0.003);
  p.rz_i = Eigen::Vector3d(-0.004, 0.006, 0.0);
  return imu;
}

// The same IMU mounted 12 cm from the body origin, rotated, on a clock 3 ms late.
inline ImuCalibration MountedImu(ImuModelKind model) {
  ImuCalibration imu = ConsumerImu(model);
  imu.intrinsics.C_i_b = SO3d::Exp(Eigen::Vector3d(0.3, -1.2, 2.0)).matrix();
  imu.intrinsics.r_b = Eigen::Vector3d(0.1, -0.05, 0.02);
  imu.time_offset_s = 0.003;
  return imu;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_CONSUMER_IMU_H_
