#include "splinecal/vio/time_offset_correlation.h"

#include <Eigen/Core>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "splinecal/imu/imu_rate.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

namespace {

// Poses slower than this [Hz], or angular speeds that vary less than this [rad/s] (std), cannot
// align the clocks by correlation.
constexpr double kCorrelationMinPoseRateHz = 5.0;
constexpr double kCorrelationMinSpeedStd = 0.05;

}  // namespace

bool EstimateTimeOffsetByCorrelation(const std::vector<ImuSample>& imu,
                                     const std::vector<StampedPose>& poses,
                                     double centre_s,
                                     double range_s,
                                     double* offset_s,
                                     bool* at_edge) {
  if (at_edge != nullptr) *at_edge = false;
  if (imu.size() < 2 || poses.size() < 3 || !(range_s > 0.0)) return false;
  const double duration = 1e-9 * static_cast<double>(poses.back().t_ns - poses.front().t_ns);
  if (!(duration > 0.0) ||
      static_cast<double>(poses.size() - 1) / duration < kCorrelationMinPoseRateHz) {
    return false;
  }
  // Mean body rate of each pose interval, in the pose source's body frame m.
  std::vector<Eigen::Vector3d> rate(poses.size() - 1);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (size_t j = 0; j + 1 < poses.size(); ++j) {
    const double dt = 1e-9 * static_cast<double>(poses[j + 1].t_ns - poses[j].t_ns);
    const SO3d R_a = SO3d::FromQuaternion(poses[j].q);
    const SO3d R_b = SO3d::FromQuaternion(poses[j + 1].q);
    rate[j] = (R_a.inverse() * R_b).Log() / dt;
    mean += rate[j];
  }
  mean /= static_cast<double>(rate.size());
  double spread = 0.0;
  for (const Eigen::Vector3d& x : rate) spread += (x - mean).squaredNorm();
  if (std::sqrt(spread / static_cast<double>(rate.size())) < kCorrelationMinSpeedStd) return false;

  // The gyro as a piecewise-linear function of time; integral[k] = its integral from t_0 to t_k.
  std::vector<Eigen::Vector3d> integral(imu.size(), Eigen::Vector3d::Zero());
  for (size_t k = 1; k < imu.size(); ++k) {
    integral[k] = integral[k - 1] + 0.5e-9 * static_cast<double>(imu[k].t_ns - imu[k - 1].t_ns) *
                                        (imu[k].gyro + imu[k - 1].gyro);
  }
  auto integral_to = [&](int64_t t) -> Eigen::Vector3d {  // t in [t_0, t_last]
    size_t k = static_cast<size_t>(
        std::upper_bound(imu.begin(),
                         imu.end(),
                         t,
                         [](int64_t value, const ImuSample& s) { return value < s.t_ns; }) -
        imu.begin());
    k = std::clamp<size_t>(k, 1, imu.size() - 1) - 1;  // t in [t_k, t_k+1]
    const double h = 1e-9 * static_cast<double>(imu[k + 1].t_ns - imu[k].t_ns);
    const double d = 1e-9 * static_cast<double>(t - imu[k].t_ns);
    return integral[k] + d * imu[k].gyro + (0.5 * d * d / h) * (imu[k + 1].gyro - imu[k].gyro);
  };
  const double step = 1.0 / ImuRateHz(imu);
  const int steps = std::max(1, static_cast<int>(std::floor(range_s / step)));
  std::vector<double> costs(2 * steps + 1, std::numeric_limits<double>::infinity());
  double best_cost = std::numeric_limits<double>::infinity();
  int best = 0;
  std::vector<Eigen::Vector3d> x;
  std::vector<Eigen::Vector3d> y;
  for (int s = -steps; s <= steps; ++s) {
    const int64_t tau_ns = std::llround((centre_s + s * step) * 1e9);
    x.clear();
    y.clear();
    for (size_t j = 0; j + 1 < poses.size(); ++j) {
      const int64_t a = poses[j].t_ns + tau_ns;
      const int64_t b = poses[j + 1].t_ns + tau_ns;
      if (a < imu.front().t_ns || b > imu.back().t_ns) continue;
      x.push_back(rate[j]);
      y.push_back((integral_to(b) - integral_to(a)) / (1e-9 * static_cast<double>(b - a)));
    }
    if (x.size() < 10) continue;
    // Least squares over an unknown rotation R (extrinsic) and gyro bias b of
    // sum |x_j - R (y_j - b)|^2: centre both sets, then Kabsch. The minimum is
    // sum |x'|^2 + sum |y'|^2 - 2 (s_1 + s_2 + sign s_3), s the singular values of sum y' x'^T.
    Eigen::Vector3d x_mean = Eigen::Vector3d::Zero();
    Eigen::Vector3d y_mean = Eigen::Vector3d::Zero();
    for (size_t j = 0; j < x.size(); ++j) {
      x_mean += x[j];
      y_mean += y[j];
    }
    x_mean /= static_cast<double>(x.size());
    y_mean /= static_cast<double>(y.size());
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    double sum_sq = 0.0;
    for (size_t j = 0; j < x.size(); ++j) {
      const Eigen::Vector3d xc = x[j] - x_mean;
      const Eigen::Vector3d yc = y[j] - y_mean;
      H += yc * xc.transpose();
      sum_sq += xc.squaredNorm() + yc.squaredNorm();
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H);
    const double sign = H.determinant() < 0.0 ? -1.0 : 1.0;
    const Eigen::Vector3d sv = svd.singularValues();
    const double cost =
        (sum_sq - 2.0 * (sv[0] + sv[1] + sign * sv[2])) / static_cast<double>(x.size());
    costs[s + steps] = cost;
    if (cost < best_cost) {
      best_cost = cost;
      best = s;
    }
  }
  if (!std::isfinite(best_cost)) return false;
  // Sub-sample refinement: the vertex of the parabola through the best cost and its neighbours.
  double refinement = 0.0;
  if (std::abs(best) < steps) {
    const double c_minus = costs[best + steps - 1];
    const double c_zero = costs[best + steps];
    const double c_plus = costs[best + steps + 1];
    const double curvature = c_minus - 2.0 * c_zero + c_plus;
    if (std::isfinite(curvature) && curvature > 0.0) {
      refinement = std::clamp(0.5 * (c_minus - c_plus) / curvature, -0.5, 0.5);
    }
  }
  *offset_s = centre_s + (best + refinement) * step;
  if (at_edge != nullptr) *at_edge = std::abs(best) == steps;
  return true;
}

}  // namespace splinecal
