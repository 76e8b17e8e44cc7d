#include "splinecal/vio/preintegration.h"

#include <algorithm>
#include <string>

#include "splinecal/error.h"

namespace splinecal {
namespace {

constexpr double kNsToS = 1e-9;

using Matrix15d = Eigen::Matrix<double, 15, 15>;

void CheckInterval(const std::vector<ImuSample>& imu, int64_t t_begin_ns, int64_t t_end_ns) {
  if (imu.size() < 2) throw Error("preintegration needs at least 2 IMU samples");
  if (t_end_ns <= t_begin_ns) {
    throw Error("preintegration interval is empty: end " + std::to_string(t_end_ns) +
                " ns is not after begin " + std::to_string(t_begin_ns) + " ns");
  }
  if (t_begin_ns < imu.front().t_ns || t_end_ns > imu.back().t_ns) {
    throw Error("preintegration interval [" + std::to_string(t_begin_ns) + ", " +
                std::to_string(t_end_ns) + "] ns is not inside the IMU data [" +
                std::to_string(imu.front().t_ns) + ", " + std::to_string(imu.back().t_ns) + "] ns");
  }
}

// The reading at t_ns from the samples a (t_a <= t_ns) and b (t_ns <= t_b):
// (1 - u) a + u b, u = (t - t_a) / (t_b - t_a); exactly a at u = 0 and exactly b at u = 1.
ImuSample Lerp(const ImuSample& a, const ImuSample& b, int64_t t_ns) {
  ImuSample out;
  out.t_ns = t_ns;
  if (t_ns == a.t_ns) {
    out.gyro = a.gyro;
    out.accel = a.accel;
    return out;
  }
  const double u = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  out.gyro = (1.0 - u) * a.gyro + u * b.gyro;
  out.accel = (1.0 - u) * a.accel + u * b.accel;
  return out;
}

// Calls step(h_s, reading_k, reading_k1) for every midpoint step of [t_begin_ns, t_end_ns]: the
// reading interpolated at t_begin, every sample strictly inside, the reading interpolated at
// t_end. Preconditions checked by CheckInterval.
template <typename StepFunction>
void ForEachStep(const std::vector<ImuSample>& imu,
                 int64_t t_begin_ns,
                 int64_t t_end_ns,
                 StepFunction&& step) {
  // First sample strictly after t_begin (exists: t_begin < t_end <= back).
  auto next =
      std::upper_bound(imu.begin(), imu.end(), t_begin_ns, [](int64_t t, const ImuSample& sample) {
        return t < sample.t_ns;
      });
  ImuSample previous = Lerp(*(next - 1), *next, t_begin_ns);
  for (; next != imu.end() && next->t_ns < t_end_ns; ++next) {
    step(static_cast<double>(next->t_ns - previous.t_ns) * kNsToS, previous, *next);
    previous = *next;
  }
  // t_end lies in (previous.t_ns, next->t_ns] (next exists: t_end <= back).
  const ImuSample last = Lerp(*(next - 1), *next, t_end_ns);
  step(static_cast<double>(t_end_ns - previous.t_ns) * kNsToS, previous, last);
}

}  // namespace

SO3d ImuPreintegration::CorrectedDeltaR(const Eigen::Vector3d& new_gyro_bias) const {
  return delta_R * SO3d::Exp(J_dR_bg * (new_gyro_bias - gyro_bias));
}

Eigen::Vector3d ImuPreintegration::CorrectedDeltaV(const Eigen::Vector3d& new_gyro_bias,
                                                   const Eigen::Vector3d& new_accel_bias) const {
  return delta_v + J_dv_bg * (new_gyro_bias - gyro_bias) + J_dv_ba * (new_accel_bias - accel_bias);
}

Eigen::Vector3d ImuPreintegration::CorrectedDeltaP(const Eigen::Vector3d& new_gyro_bias,
                                                   const Eigen::Vector3d& new_accel_bias) const {
  return delta_p + J_dp_bg * (new_gyro_bias - gyro_bias) + J_dp_ba * (new_accel_bias - accel_bias);
}

ImuSample InterpolateImu(const std::vector<ImuSample>& imu, int64_t t_ns) {
  if (imu.empty() || t_ns < imu.front().t_ns || t_ns > imu.back().t_ns) {
    throw Error("time " + std::to_string(t_ns) + " ns is outside the IMU data");
  }
  auto next =
      std::lower_bound(imu.begin(), imu.end(), t_ns, [](const ImuSample& sample, int64_t t) {
        return sample.t_ns < t;
      });
  if (next->t_ns == t_ns) return *next;
  return Lerp(*(next - 1), *next, t_ns);
}

SO3d PreintegrateRotation(const std::vector<ImuSample>& imu,
                          int64_t t_begin_ns,
                          int64_t t_end_ns,
                          const Eigen::Vector3d& gyro_bias,
                          Eigen::Matrix3d* J_dR_bg) {
  CheckInterval(imu, t_begin_ns, t_end_ns);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  ForEachStep(imu, t_begin_ns, t_end_ns, [&](double h, const ImuSample& r0, const ImuSample& r1) {
    const Eigen::Vector3d phi = (0.5 * (r0.gyro + r1.gyro) - gyro_bias) * h;
    const SO3d step = SO3d::Exp(phi);
    q = q * step.quaternion();
    if (J_dR_bg != nullptr) {
      // J' = Exp(phi)^T J - Jr(phi) h (header comment).
      J = step.matrix().transpose() * J - RightJacobianSO3(phi) * h;
    }
  });
  if (J_dR_bg != nullptr) *J_dR_bg = J;
  return SO3d::FromQuaternion(q);
}

ImuPreintegration Preintegrate(const std::vector<ImuSample>& imu,
                               int64_t t_begin_ns,
                               int64_t t_end_ns,
                               const Eigen::Vector3d& gyro_bias,
                               const Eigen::Vector3d& accel_bias,
                               const ImuNoise* noise) {
  CheckInterval(imu, t_begin_ns, t_end_ns);
  ImuPreintegration out;
  out.t_begin_ns = t_begin_ns;
  out.t_end_ns = t_end_ns;
  out.dt_s = static_cast<double>(t_end_ns - t_begin_ns) * kNsToS;
  out.gyro_bias = gyro_bias;
  out.accel_bias = accel_bias;
  out.has_covariance = noise != nullptr;

  double gyro_var = 0.0, accel_var = 0.0, gyro_rw_var = 0.0, accel_rw_var = 0.0;
  if (noise != nullptr) {
    gyro_var = noise->gyroscope_noise_density * noise->gyroscope_noise_density;
    accel_var = noise->accelerometer_noise_density * noise->accelerometer_noise_density;
    gyro_rw_var = noise->gyroscope_random_walk * noise->gyroscope_random_walk;
    accel_rw_var = noise->accelerometer_random_walk * noise->accelerometer_random_walk;
  }

  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();  // dR_k as a matrix
  Matrix15d& P = out.covariance;
  Matrix15d M;

  ForEachStep(imu, t_begin_ns, t_end_ns, [&](double h, const ImuSample& r0, const ImuSample& r1) {
    const Eigen::Vector3d phi = (0.5 * (r0.gyro + r1.gyro) - gyro_bias) * h;
    const SO3d step = SO3d::Exp(phi);
    const Eigen::Matrix3d Rs = step.matrix();
    const Eigen::Matrix3d R1 = R0 * Rs;
    const Eigen::Vector3d f0 = r0.accel - accel_bias;
    const Eigen::Vector3d f1 = r1.accel - accel_bias;
    const Eigen::Vector3d acc = 0.5 * (R0 * f0 + R1 * f1);
    const Eigen::Matrix3d Jr_h = RightJacobianSO3(phi) * h;

    // Blocks of the step's Jacobian (header comment): d acc / d dphi, d acc / d b_g,
    // d acc / d b_a.
    const Eigen::Matrix3d R1_f1x = R1 * Hat(f1);
    const Eigen::Matrix3d A = -0.5 * (R0 * Hat(f0) + R1_f1x * Rs.transpose());
    const Eigen::Matrix3d Bg = 0.5 * R1_f1x * Jr_h;
    const Eigen::Matrix3d Ba = -0.5 * (R0 + R1);
    const double half_h2 = 0.5 * h * h;

    if (noise != nullptr) {
      // P = F P F^T + G Q G^T, block by block. With X = [h A, h B_g, h B_a] (the v row of F over
      // z = (dphi, db_g, db_a)) the p row is (h/2) X, so each product with X is formed once:
      //   F = [[I, h I, (h/2) X], [0, I, X], [0, 0, F_z]],  F_z = [[Exp(phi)^T, -Jr h, 0], [0, I,
      //   0], [0, 0, I]].
      const Eigen::Matrix3d hA = h * A, hBg = h * Bg, hBa = h * Ba;
      // M = F P.
      const Eigen::Matrix<double, 3, 15> W = hA * P.middleRows<3>(kPreintPhi) +
                                             hBg * P.middleRows<3>(kPreintBg) +
                                             hBa * P.middleRows<3>(kPreintBa);
      M.middleRows<3>(kPreintP) =
          P.middleRows<3>(kPreintP) + h * P.middleRows<3>(kPreintV) + (0.5 * h) * W;
      M.middleRows<3>(kPreintV) = P.middleRows<3>(kPreintV) + W;
      M.middleRows<3>(kPreintPhi) =
          Rs.transpose() * P.middleRows<3>(kPreintPhi) - Jr_h * P.middleRows<3>(kPreintBg);
      M.middleRows<6>(kPreintBg) = P.middleRows<6>(kPreintBg);
      // P = M F^T.
      const Eigen::Matrix<double, 15, 3> V = M.middleCols<3>(kPreintPhi) * hA.transpose() +
                                             M.middleCols<3>(kPreintBg) * hBg.transpose() +
                                             M.middleCols<3>(kPreintBa) * hBa.transpose();
      P.middleCols<3>(kPreintP) =
          M.middleCols<3>(kPreintP) + h * M.middleCols<3>(kPreintV) + (0.5 * h) * V;
      P.middleCols<3>(kPreintV) = M.middleCols<3>(kPreintV) + V;
      P.middleCols<3>(kPreintPhi) =
          M.middleCols<3>(kPreintPhi) * Rs - M.middleCols<3>(kPreintBg) * Jr_h.transpose();
      P.middleCols<6>(kPreintBg) = M.middleCols<6>(kPreintBg);

      // Noise of the step: white gyro n_g enters like b_g, white accel n_a like b_a.
      Eigen::Matrix<double, 9, 3> G_g;
      G_g << (0.5 * h) * hBg, hBg, -Jr_h;
      Eigen::Matrix<double, 6, 3> G_a;
      G_a << (0.5 * h) * hBa, hBa;
      P.topLeftCorner<9, 9>().noalias() += (gyro_var / h) * G_g * G_g.transpose();
      P.topLeftCorner<6, 6>().noalias() += (accel_var / h) * G_a * G_a.transpose();
      P.diagonal().segment<3>(kPreintBg).array() += gyro_rw_var * h;
      P.diagonal().segment<3>(kPreintBa).array() += accel_rw_var * h;
    }

    // Bias Jacobians (with J_dR_bg of step k, before its update).
    const Eigen::Matrix3d dacc_dbg = A * out.J_dR_bg + Bg;
    out.J_dp_bg += h * out.J_dv_bg + half_h2 * dacc_dbg;
    out.J_dp_ba += h * out.J_dv_ba + half_h2 * Ba;
    out.J_dv_bg += h * dacc_dbg;
    out.J_dv_ba += h * Ba;
    out.J_dR_bg = Rs.transpose() * out.J_dR_bg - Jr_h;

    // The means.
    out.delta_p += h * out.delta_v + half_h2 * acc;
    out.delta_v += h * acc;
    q = q * step.quaternion();
    R0 = q.toRotationMatrix();
  });

  out.delta_R = SO3d::FromQuaternion(q);
  if (noise != nullptr) {
    // Remove the asymmetry rounding leaves.
    P = (0.5 * (P + P.transpose())).eval();
  }
  return out;
}

}  // namespace splinecal
