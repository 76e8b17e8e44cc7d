// The ground-truth state of an IMU at one instant, as EuRoC's state_groundtruth_estimate0 holds
// it (io/euroc.h reads and writes those files; imu/integrate.h starts from and compares with it).
#ifndef SPLINECAL_IMU_GROUND_TRUTH_H_
#define SPLINECAL_IMU_GROUND_TRUTH_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace splinecal {

// One row of EuRoC state_groundtruth_estimate0/data.csv: pose T_w_s, velocity, biases.
struct GroundTruthState {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w_s = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_w_s = Eigen::Quaterniond::Identity();  // unit norm
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
};

}  // namespace splinecal

#endif  // SPLINECAL_IMU_GROUND_TRUTH_H_
