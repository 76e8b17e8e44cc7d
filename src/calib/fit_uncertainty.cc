#include "fit_uncertainty.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "splinecal/estimation/gravity_tangent.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

void ReportFitUncertainty(const FitOptions& options, const Eigen::MatrixXd& C, FitResult* result) {
  const ExcitationThresholds& limit = options.excitation;
  result->covariance_ok = true;
  result->covariance = C;
  const Eigen::VectorXd std_dev = C.diagonal().cwiseMax(0.0).cwiseSqrt();
  result->gyro_bias_std = std_dev.segment<3>(0);
  result->accel_bias_std = std_dev.segment<3>(3);
  const Eigen::Matrix2d C_dir = C.block<2, 2>(6, 6);
  const Eigen::Matrix<double, 3, 2> J_g =
      options.model.gravity_m_s2 * GravityTangentBasis(result->gravity_w);
  result->gravity_w_std = (J_g * C_dir * J_g.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  // Direction std: the larger principal std of the 2-D tangent covariance.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> dir_eigen(C_dir);
  result->gravity_direction_std_deg =
      std::sqrt(std::max(0.0, dir_eigen.eigenvalues()[1])) * kRadToDeg;
  int next = 8;
  if (options.estimate_time_offset) result->time_offset_std_s = std_dev[next++];
  if (options.estimate_extrinsic) {
    result->T_m_s_translation_std_m = std_dev.segment<3>(next);
    result->T_m_s_rotation_std_rad = std_dev.segment<3>(next + 3);
  }

  // Plain-words excitation warnings.
  auto max_of = [](const Eigen::Vector3d& v) { return v.maxCoeff(); };
  if (max_of(result->gyro_bias_std) > limit.gyro_bias_std_rad_s) {
    result->not_determined.push_back("gyro_bias");
    result->warnings.push_back(
        "gyro_bias is not determined by this data (std up to " +
        StringPrintf("%.3g", max_of(result->gyro_bias_std)) +
        " rad/s): too little data, or poses too noisy to pin down the rotation");
  }
  if (max_of(result->accel_bias_std) > limit.accel_bias_std_m_s2) {
    result->not_determined.push_back("accel_bias");
    result->warnings.push_back(
        "accel_bias is not determined by this data (std up to " +
        StringPrintf("%.3g", max_of(result->accel_bias_std)) +
        " m/s^2): the accelerometer bias can only be told apart from gravity when the IMU is "
        "held in several orientations; rotate it about at least two axes");
  }
  if (result->gravity_direction_std_deg > limit.gravity_direction_std_deg) {
    result->not_determined.push_back("gravity_w");
    result->warnings.push_back(
        "gravity_w's direction is not determined by this data (std " +
        StringPrintf("%.3g", result->gravity_direction_std_deg) +
        " deg): it trades off against the accelerometer bias unless the IMU rotates");
  }
  if (options.estimate_time_offset && result->time_offset_std_s > limit.time_offset_std_s) {
    result->not_determined.push_back("time_offset_s");
    result->warnings.push_back(
        "time_offset_s is not determined by this data (std " +
        StringPrintf("%.3g", 1e3 * result->time_offset_std_s) +
        " ms): the clocks are aligned by changes of the rotation rate; the motion needs "
        "rotational accelerations");
  }
  if (options.estimate_extrinsic) {
    if (max_of(result->T_m_s_translation_std_m) > limit.extrinsic_translation_std_m ||
        max_of(result->T_m_s_rotation_std_rad) * kRadToDeg >
            limit.extrinsic_rotation_std_deg) {
      result->not_determined.push_back("T_pose_imu");
    }
    if (max_of(result->T_m_s_translation_std_m) > limit.extrinsic_translation_std_m) {
      result->warnings.push_back(
          "the translation of T_pose_imu is not determined by this data (std up to " +
          StringPrintf("%.3g", max_of(result->T_m_s_translation_std_m)) +
          " m): it shows only through lever-arm accelerations; rotate faster about at least two "
          "axes");
    }
    if (max_of(result->T_m_s_rotation_std_rad) * kRadToDeg >
        limit.extrinsic_rotation_std_deg) {
      result->warnings.push_back(
          "the rotation of T_pose_imu is not determined by this data (std up to " +
          StringPrintf("%.3g", max_of(result->T_m_s_rotation_std_rad) * kRadToDeg) +
          " deg): rotate about at least two axes");
    }
  }
  // Near-perfect correlations between different quantities.
  const std::vector<std::string>& labels = result->covariance_labels;
  auto group = [](const std::string& label) { return label.substr(0, label.rfind('_')); };
  for (int a = 0; a < C.rows(); ++a) {
    for (int b = a + 1; b < C.rows(); ++b) {
      if (group(labels[a]) == group(labels[b])) continue;
      const double denominator = std::sqrt(C(a, a) * C(b, b));
      if (!(denominator > 0.0)) continue;
      const double rho = C(a, b) / denominator;
      if (std::abs(rho) > limit.max_correlation) {
        result->warnings.push_back(
            labels[a] + " and " + labels[b] + " are almost perfectly correlated (" +
            StringPrintf("%.4f", rho) + "): this data cannot tell them apart");
      }
    }
  }
}

void ReportSingularFitInformation(const FitOptions& options, FitResult* result) {
  result->covariance_ok = false;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  result->gyro_bias_std.setConstant(nan);
  result->accel_bias_std.setConstant(nan);
  result->gravity_w_std.setConstant(nan);
  result->gravity_direction_std_deg = nan;
  result->time_offset_std_s = nan;
  result->T_m_s_translation_std_m.setConstant(nan);
  result->T_m_s_rotation_std_rad.setConstant(nan);
  result->not_determined = {"gyro_bias", "accel_bias", "gravity_w"};
  if (options.estimate_time_offset) result->not_determined.push_back("time_offset_s");
  if (options.estimate_extrinsic) result->not_determined.push_back("T_pose_imu");
  result->warnings.push_back(
      "the information matrix is singular: some parameters are not determined by this data at "
      "all, so no standard deviations are reported. Typical reasons: the IMU did not rotate "
      "(accelerometer bias and gravity cannot be told apart), it rotated about one axis only "
      "(extrinsic), or its rotation rate never changed (time offset)");
}

}  // namespace splinecal
