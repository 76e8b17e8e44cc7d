// Applying a calibration to raw IMU readings (`splinecal correct`, docs/imu_models.md "Applying a
// calibration"): the inverse of the IMU models of imu/imu_intrinsic_model.h.
//
// The output is what an ideal IMU at this IMU's origin, in its accelerometer frame i, reads
// without bias: the angular velocity w_i = C_i_b w_b and the specific force f_i = C_i_b f_b(r_b).
// From the models (Kalibr's IccSensors.py, with constant biases b_g, b_a):
//
//     accel = M_a (f_i + s) + b_a,     s = sum_k e_k e_k^T (dw_i x r_k + w_i x (w_i x r_k))
//     gyro  = M_g C_gyro_i w_i + A C_gyro_i f_i + b_g
//
// so, with s = 0 except for the size effect,
//
//     f_i = M_a^-1 (accel - b_a) - s(w_i, dw_i)                                          (1)
//     w_i = C_gyro_i^T M_g^-1 (gyro - b_g - A C_gyro_i f_i)                              (2)
//
// Without the size effect (1) then (2) is exact. With it, (1) needs w_i and its derivative dw_i
// and (2) needs f_i: three fixed-point rounds, starting from s = 0. Each round changes f_i by
// |A| |d s| (~1e-3 (rad/s)/(m/s^2) times millimetre lever arms): the third is converged to
// rounding. dw_i is the least-squares slope of w_i over the 2 h + 1 samples around each one
// (h = derivative_half_window, fewer at the ends), a stated smoothing derivative of the
// corrected gyro: there is no spline outside a calibration's time range.
//
// The biases subtracted are the constants given (options), e.g. a calibration's mean biases, not
// a bias trajectory.
#ifndef SPLINECAL_IMU_CORRECT_IMU_H_
#define SPLINECAL_IMU_CORRECT_IMU_H_

#include <Eigen/Core>
#include <vector>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_sample.h"

namespace splinecal {

struct ImuCorrectionOptions {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // b_g subtracted [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // b_a subtracted [m/s^2]
  // h: the size effect's angular acceleration is the slope of the corrected gyro over 2 h + 1
  // samples (h = 2 at 200 Hz: 20 ms). At least 1.
  int derivative_half_window = 2;
};

// Equations (1), (2) for every raw reading; the timestamps are kept (the IMU's clock: the
// calibration's time_offset is not applied). Throws Error for a singular M_a or M_g, a
// derivative_half_window < 1, non-finite biases, or timestamps that do not increase.
std::vector<ImuSample> CorrectImuReadings(const ImuCalibration& imu,
                                          const std::vector<ImuSample>& raw,
                                          const ImuCorrectionOptions& options = {});

// The least-squares slope d/dt of the vectors `values` at the times of `samples` (their t_ns)
// over the 2 h + 1 neighbours of each (a window clipped at the ends; zero for a single sample).
std::vector<Eigen::Vector3d> SmoothedDerivative(const std::vector<ImuSample>& samples,
                                                const std::vector<Eigen::Vector3d>& values,
                                                int half_window);

}  // namespace splinecal

#endif  // SPLINECAL_IMU_CORRECT_IMU_H_
