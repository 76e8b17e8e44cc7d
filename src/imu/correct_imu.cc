#include "splinecal/imu/correct_imu.h"

#include <algorithm>
#include <string>

#include "splinecal/error.h"
#include "splinecal/imu/imu_intrinsic_model.h"

namespace splinecal {
namespace {

// Rounds of (1) and (2) with the size effect (see the header: the third is converged).
constexpr int kSizeEffectRounds = 3;

// M^-1 of a lower-triangular M, refusing a singular one (a zero on the diagonal).
Eigen::Matrix3d InverseLowerTriangular(const Eigen::Matrix3d& M, const char* name) {
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(M(k, k)) > 1e-6)) {
      throw Error(std::string(name) + " is singular: diagonal entry " + std::to_string(k) + " is " +
                  std::to_string(M(k, k)));
    }
  }
  return M.triangularView<Eigen::Lower>().solve(Eigen::Matrix3d::Identity());
}

// s of the header: row k of dw_i x r_k + w_i x (w_i x r_k), r_x = 0.
Eigen::Vector3d SizeEffectTerms(const ImuIntrinsicsd& p,
                                const Eigen::Vector3d& w_i,
                                const Eigen::Vector3d& dw_i) {
  const Eigen::Matrix3d L = LeverArmJacobian(w_i, dw_i);  // [dw]x + [w]x^2
  return Eigen::Vector3d(0.0, L.row(1).dot(p.ry_i), L.row(2).dot(p.rz_i));
}

}  // namespace

std::vector<Eigen::Vector3d> SmoothedDerivative(const std::vector<ImuSample>& samples,
                                                const std::vector<Eigen::Vector3d>& values,
                                                int half_window) {
  const int n = static_cast<int>(samples.size());
  std::vector<Eigen::Vector3d> slope(n, Eigen::Vector3d::Zero());
  for (int i = 0; i < n; ++i) {
    const int first = std::max(0, i - half_window);
    const int last = std::min(n - 1, i + half_window);
    if (last == first) continue;
    // Times relative to sample i, in seconds: no loss of precision on 1e18 ns stamps.
    double t_mean = 0.0;
    Eigen::Vector3d v_mean = Eigen::Vector3d::Zero();
    for (int j = first; j <= last; ++j) {
      t_mean += (samples[j].t_ns - samples[i].t_ns) * 1e-9;
      v_mean += values[j];
    }
    const double count = last - first + 1;
    t_mean /= count;
    v_mean /= count;
    double stt = 0.0;
    Eigen::Vector3d stv = Eigen::Vector3d::Zero();
    for (int j = first; j <= last; ++j) {
      const double dt = (samples[j].t_ns - samples[i].t_ns) * 1e-9 - t_mean;
      stt += dt * dt;
      stv += dt * (values[j] - v_mean);
    }
    slope[i] = stv / stt;
  }
  return slope;
}

std::vector<ImuSample> CorrectImuReadings(const ImuCalibration& imu,
                                          const std::vector<ImuSample>& raw,
                                          const ImuCorrectionOptions& options) {
  if (options.derivative_half_window < 1) {
    throw Error("the derivative window's half width must be at least 1 sample, got " +
                std::to_string(options.derivative_half_window));
  }
  if (!options.gyro_bias.allFinite() || !options.accel_bias.allFinite()) {
    throw Error("the biases to subtract must be finite");
  }
  for (size_t k = 1; k < raw.size(); ++k) {
    if (raw[k].t_ns <= raw[k - 1].t_ns) {
      throw Error("IMU timestamps must increase: row " + std::to_string(k + 1) + " (" +
                  std::to_string(raw[k].t_ns) + " ns) is not after the one before");
    }
  }
  const ImuIntrinsicsd p = ModelIntrinsics(imu.model, imu.intrinsics);
  const Eigen::Matrix3d M_a_inv = InverseLowerTriangular(p.M_a, "accelerometers/M");
  const Eigen::Matrix3d M_g_inv = InverseLowerTriangular(p.M_g, "gyroscopes/M");
  const Eigen::Matrix3d gyro_map = p.C_gyro_i.transpose() * M_g_inv;  // (2)
  const Eigen::Matrix3d A_gyro = p.A * p.C_gyro_i;

  std::vector<ImuSample> out(raw.size());
  std::vector<Eigen::Vector3d> u(raw.size()), w(raw.size());
  for (size_t k = 0; k < raw.size(); ++k) {
    out[k].t_ns = raw[k].t_ns;
    u[k] = M_a_inv * (raw[k].accel - options.accel_bias);  // f_i + s
    out[k].accel = u[k];
  }
  const auto update_gyro = [&] {
    for (size_t k = 0; k < raw.size(); ++k) {
      out[k].gyro = gyro_map * (raw[k].gyro - options.gyro_bias - A_gyro * out[k].accel);
      w[k] = out[k].gyro;
    }
  };
  update_gyro();
  if (imu.model != ImuModelKind::kScaleMisalignmentSizeEffect) return out;
  for (int round = 0; round < kSizeEffectRounds; ++round) {
    const std::vector<Eigen::Vector3d> dw =
        SmoothedDerivative(out, w, options.derivative_half_window);
    for (size_t k = 0; k < raw.size(); ++k) out[k].accel = u[k] - SizeEffectTerms(p, w[k], dw[k]);
    update_gyro();
  }
  return out;
}

}  // namespace splinecal
