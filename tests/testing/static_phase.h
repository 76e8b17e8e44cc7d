// What an IMU recording and its ground truth say while the sensor sits still (EuRoC V1_01_easy's
// first 4 s: the MAV is on the ground until ~4.5 s, its ground truth moving by at most 2 mm). The
// true acceleration, velocity and rate are zero there, so these numbers are the data's own errors
// and an estimate of gravity that does not depend on the code under test.
#ifndef SPLINECAL_TESTS_TESTING_STATIC_PHASE_H_
#define SPLINECAL_TESTS_TESTING_STATIC_PHASE_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "splinecal/imu/ground_truth.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace testing {

// EuRoC V1_01_easy: the MAV sits still for the first 4 s of its ground truth.
inline constexpr int64_t kV101StaticDurationNs = 4'000'000'000;

struct StaticPhase {
  // Mean of R_w_s (accel - b_a) over the IMU samples, with the ground truth's orientation and
  // accelerometer bias (the latest row at or before each sample): -g_w plus the data's
  // acceleration error [m/s^2].
  Eigen::Vector3d mean_specific_force_w = Eigen::Vector3d::Zero();
  // Mean of gyro - b_g: the ground truth's gyro bias error [rad/s].
  Eigen::Vector3d gyro_bias_error = Eigen::Vector3d::Zero();
  double max_speed_m_s = 0.0;     // largest ground-truth |v_w|: its velocity error
  double max_rotation_rad = 0.0;  // largest angle from the first ground-truth orientation
  int num_imu_samples = 0;
};

// Over [truth.front().t_ns, truth.front().t_ns + duration_ns].
inline StaticPhase MeasureStaticPhase(const std::vector<ImuSample>& imu,
                                      const std::vector<GroundTruthState>& truth,
                                      int64_t duration_ns) {
  StaticPhase phase;
  const int64_t start_ns = truth.front().t_ns;
  const int64_t end_ns = start_ns + duration_ns;
  const SO3d R_first = SO3d::FromQuaternion(truth.front().q_w_s);
  size_t row = 0;
  for (const ImuSample& sample : imu) {
    if (sample.t_ns < start_ns || sample.t_ns > end_ns) continue;
    while (row + 1 < truth.size() && truth[row + 1].t_ns <= sample.t_ns) ++row;
    const GroundTruthState& state = truth[row];
    const SO3d R_w_s = SO3d::FromQuaternion(state.q_w_s);
    phase.mean_specific_force_w += R_w_s * (sample.accel - state.accel_bias);
    phase.gyro_bias_error += sample.gyro - state.gyro_bias;
    ++phase.num_imu_samples;
  }
  EXPECT_GT(phase.num_imu_samples, 0);
  phase.mean_specific_force_w /= static_cast<double>(phase.num_imu_samples);
  phase.gyro_bias_error /= static_cast<double>(phase.num_imu_samples);
  for (const GroundTruthState& state : truth) {
    if (state.t_ns > end_ns) break;
    phase.max_speed_m_s = std::max(phase.max_speed_m_s, state.v_w.norm());
    phase.max_rotation_rad =
        std::max(phase.max_rotation_rad,
                 (R_first.inverse() * SO3d::FromQuaternion(state.q_w_s)).Log().norm());
  }
  return phase;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_STATIC_PHASE_H_
