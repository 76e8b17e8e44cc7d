// IMU preintegration between two times (camera frames): the relative motion the IMU measured,
// independent of the unknown start state and of gravity, with its Jacobians with respect to the
// biases (first-order bias correction) and its covariance from Kalibr's noise densities.
//
// What this header implements
//   For readings (gyro w_k, accel a_k) at times t_k in [t_i, t_j] (readings at t_i and t_j
//   interpolated linearly when they fall between samples), with bias estimates b_g, b_a, the
//   MIDPOINT scheme with the exact SO(3) exponential, step h_k = t_{k+1} - t_k:
//
//     omega_k = (w_k + w_{k+1}) / 2 - b_g
//     dR_{k+1} = dR_k Exp(omega_k h_k)                                          (exact Exp)
//     acc_k    = ( dR_k (a_k - b_a) + dR_{k+1} (a_{k+1} - b_a) ) / 2
//     dp_{k+1} = dp_k + dv_k h_k + acc_k h_k^2 / 2
//     dv_{k+1} = dv_k + acc_k h_k
//
//   starting from dR = I, dv = dp = 0. The results are expressed in the IMU frame s_i at t_i
//   (the seed's gamma, beta, alpha) and relate the states at t_i and t_j by (T = t_j - t_i,
//   g_w the gravity vector, docs/conventions.md "IMU model"):
//
//     R_w_sj = R_w_si dR
//     v_j    = v_i + g_w T + R_w_si dv
//     p_j    = p_i + v_i T + g_w T^2 / 2 + R_w_si dp
//
//   These hold EXACTLY (to rounding) for a world trajectory integrated with the same scheme;
//   for a continuous trajectory the error is O(h^2) per unit time.
//
// Bias Jacobians (right perturbation of dR, lie/so3.h): for a bias change db,
//   dR(b_g + db_g) ~ dR Exp(J_dR_bg db_g),   dv(b + db) ~ dv + J_dv_bg db_g + J_dv_ba db_a, ...
// They are the exact derivatives of the discrete scheme above, propagated as
//   J_dR_bg' = Exp(omega h)^T J_dR_bg - Jr(omega h) h
//   d acc / d b_g = A J_dR_bg + B_g,  A = -(dR_k [f_k]x + dR_{k+1} [f_{k+1}]x Exp(omega h)^T) / 2,
//                   B_g = dR_{k+1} [f_{k+1}]x Jr(omega h) h / 2,  f = a - b_a
//   d acc / d b_a = -(dR_k + dR_{k+1}) / 2
//   J_dp' = J_dp + h J_dv + h^2/2 d acc/d b,   J_dv' = J_dv + h d acc/d b
// ([Forster17] derives them for Euler steps; these are the same derivation for the midpoint step.)
//
// Covariance: the error state e = [dp, dv, dphi, db_g, db_a] (15; dphi the right perturbation
// of dR; db the bias error over the interval, starting at 0) propagates as P' = F P F^T + G Q G^T
// with F the Jacobian of one step (the same blocks as above) and the noise of one step
//   Q = diag(sigma_g^2 / h I, sigma_a^2 / h I, sigma_bg^2 h I, sigma_ba^2 h I)
// sigma the Kalibr densities (imu/noise.h): the mean of white noise of density sigma over a time
// h has variance sigma^2 / h, whatever the sampling rate, so the covariance does not depend on
// the IMU rate or on how the interval is cut ([Kalibr]; [Forster17]: discrete noise covariance =
// continuous covariance / step).
//
// References
//   [Forster17] C. Forster, L. Carlone, F. Dellaert, D. Scaramuzza, "On-Manifold Preintegration
//               for Real-Time Visual-Inertial Odometry", IEEE T-RO 33(1), 2017.
//   [Kalibr]    Kalibr wiki, "IMU Noise Model".
//   [seed001]   VINS-Mono alignment notes (/work/shared/seeds/001_*.txt): alpha, beta, gamma.
#ifndef SPLINECAL_VIO_PREINTEGRATION_H_
#define SPLINECAL_VIO_PREINTEGRATION_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

// Index of the blocks of ImuPreintegration::covariance.
inline constexpr int kPreintP = 0;
inline constexpr int kPreintV = 3;
inline constexpr int kPreintPhi = 6;
inline constexpr int kPreintBg = 9;
inline constexpr int kPreintBa = 12;

struct ImuPreintegration {
  int64_t t_begin_ns = 0;  // t_i
  int64_t t_end_ns = 0;    // t_j
  double dt_s = 0.0;       // T = t_j - t_i [s]
  // The biases the readings were integrated with (the linearisation point of the Jacobians).
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // [m/s^2]

  SO3d delta_R;                                       // R_si_sj (gamma)
  Eigen::Vector3d delta_v = Eigen::Vector3d::Zero();  // beta, in s_i [m/s]
  Eigen::Vector3d delta_p = Eigen::Vector3d::Zero();  // alpha, in s_i [m]

  Eigen::Matrix3d J_dR_bg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d J_dv_bg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d J_dv_ba = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d J_dp_bg = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d J_dp_ba = Eigen::Matrix3d::Zero();

  // Covariance of [dp, dv, dphi, db_g, db_a] (offsets kPreintP...); zero unless has_covariance.
  bool has_covariance = false;
  Eigen::Matrix<double, 15, 15> covariance = Eigen::Matrix<double, 15, 15>::Zero();

  // First-order bias correction: the preintegrated values for other biases, without
  // re-integrating. Accurate to O(|b - bias|^2).
  SO3d CorrectedDeltaR(const Eigen::Vector3d& new_gyro_bias) const;
  Eigen::Vector3d CorrectedDeltaV(const Eigen::Vector3d& new_gyro_bias,
                                  const Eigen::Vector3d& new_accel_bias) const;
  Eigen::Vector3d CorrectedDeltaP(const Eigen::Vector3d& new_gyro_bias,
                                  const Eigen::Vector3d& new_accel_bias) const;
};

// The IMU reading at t_ns, linearly interpolated between the two samples around it (exactly a
// sample's values when t_ns is its timestamp). `imu` sorted by time; throws splinecal::Error when
// t_ns lies outside [imu.front().t_ns, imu.back().t_ns].
ImuSample InterpolateImu(const std::vector<ImuSample>& imu, int64_t t_ns);

// Preintegrates `imu` (sorted, strictly increasing times) over [t_begin_ns, t_end_ns] with the
// given biases. `noise` nullptr skips the covariance (has_covariance = false); otherwise its
// densities are used (its update rate is not: steps use the actual sample times).
// Throws splinecal::Error when t_end_ns <= t_begin_ns or the interval is not inside the IMU data.
ImuPreintegration Preintegrate(const std::vector<ImuSample>& imu,
                               int64_t t_begin_ns,
                               int64_t t_end_ns,
                               const Eigen::Vector3d& gyro_bias,
                               const Eigen::Vector3d& accel_bias,
                               const ImuNoise* noise);

// The rotation part only (dR and J_dR_bg), about 4x cheaper: for the gyro-bias iterations.
// J_dR_bg may be nullptr. Same preconditions as Preintegrate.
SO3d PreintegrateRotation(const std::vector<ImuSample>& imu,
                          int64_t t_begin_ns,
                          int64_t t_end_ns,
                          const Eigen::Vector3d& gyro_bias,
                          Eigen::Matrix3d* J_dR_bg);

}  // namespace splinecal

#endif  // SPLINECAL_VIO_PREINTEGRATION_H_
