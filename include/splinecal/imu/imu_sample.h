// One IMU reading: EuRoC imu0/data.csv row (docs/conventions.md, "IMU model").
#ifndef SPLINECAL_IMU_IMU_SAMPLE_H_
#define SPLINECAL_IMU_IMU_SAMPLE_H_

#include <cstdint>

#include <Eigen/Core>

namespace splinecal {

struct ImuSample {
  int64_t t_ns = 0;                                  // timestamp [ns]
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();    // angular rate in s [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();   // specific force in s [m/s^2]
};

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_SAMPLE_H_
