// The pieces the Monte-Carlo consistency (NEES) tests of the IMUs share: an IMU's error in the
// entries of its reported covariance (calib/imu_covariance.h), the parameter groups and their
// exact NEES sums, and the excitation of a trajectory. calibrate_imu_model_nees_slow_test.cc uses
// them on the reference IMU's model, calibrate_imus_model_nees_slow_test.cc on a further IMU's,
// calibrate_imus_nees_slow_test.cc on the further IMUs' poses and clocks.
#ifndef SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_
#define SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calib/several_imus_round_trip.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/imu_covariance.h"
#include "splinecal/lie/so3.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/units.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace testing {

// The RMS rotation rate [rad/s] and angular acceleration [rad/s^2] of the trajectory over the
// recording (the excitation the lever arms' accuracy rests on), sampled at 200 Hz; the angular
// acceleration by central differences of the exact rate (h = 1e-5 s, as the simulator does).
inline void Excitation(const AnalyticTrajectory& trajectory,
                       double duration_s,
                       double* w_rms,
                       double* dw_rms) {
  constexpr double kH = 1e-5;
  double w_sq = 0.0;
  double dw_sq = 0.0;
  const int n = static_cast<int>(duration_s * 200.0);
  for (int k = 0; k < n; ++k) {
    const double t = k / 200.0;
    w_sq += trajectory.Evaluate(t).w_s.squaredNorm();
    dw_sq += ((trajectory.Evaluate(t + kH).w_s - trajectory.Evaluate(t - kH).w_s) / (2.0 * kH))
                 .squaredNorm();
  }
  *w_rms = std::sqrt(w_sq / n);
  *dw_rms = std::sqrt(dw_sq / n);
}

inline void AppendVector(const Eigen::Vector3d& error,
                         const Eigen::Vector3d& std_dev,
                         std::vector<double>* z) {
  for (int a = 0; a < 3; ++a) z->push_back(error[a] / std_dev[a]);
}

// The error of an IMU's estimate against the truth in the entries and units of its covariance
// (calib/imu_covariance.h says which error each entry's variance is of): estimate - truth,
// C_gyro_i's phi = Log(C_gyro_i) of each (the parameter itself), C_i_b's Log(C_true^T C_est) (its
// right tangent), radians.
inline Eigen::VectorXd ImuCovarianceError(const ImuCovariance& covariance,
                                          const ImuCalibration& estimate,
                                          const ImuCalibration& truth) {
  const ImuIntrinsicsd& p = estimate.intrinsics;
  const ImuIntrinsicsd& t = truth.intrinsics;
  const Eigen::Vector3d gyro_phi =
      SO3d::FromMatrix(p.C_gyro_i).Log() - SO3d::FromMatrix(t.C_gyro_i).Log();
  const Eigen::Vector3d rotation_phi = SO3d::FromMatrix(t.C_i_b.transpose() * p.C_i_b).Log();
  Eigen::VectorXd e(covariance.entries.size());
  for (std::size_t k = 0; k < covariance.entries.size(); ++k) {
    const ImuCovarianceEntry& entry = covariance.entries[k];
    const int r = entry.row;
    const int c = entry.col;
    switch (entry.parameter) {
      case ImuParameter::kMa:
        e[k] = p.M_a(r, c) - t.M_a(r, c);
        break;
      case ImuParameter::kMg:
        e[k] = p.M_g(r, c) - t.M_g(r, c);
        break;
      case ImuParameter::kA:
        e[k] = p.A(r, c) - t.A(r, c);
        break;
      case ImuParameter::kCGyroI:
        e[k] = gyro_phi[r];
        break;
      case ImuParameter::kRyI:
        e[k] = p.ry_i[r] - t.ry_i[r];
        break;
      case ImuParameter::kRzI:
        e[k] = p.rz_i[r] - t.rz_i[r];
        break;
      case ImuParameter::kCIB:
        e[k] = rotation_phi[r];
        break;
      case ImuParameter::kRB:
        e[k] = p.r_b[r] - t.r_b[r];
        break;
      case ImuParameter::kTimeOffset:
        e[k] = estimate.time_offset_s - truth.time_offset_s;
        break;
    }
  }
  return e;
}

// A mounted further IMU's truth (calib/several_imus_round_trip.h) as ImuCovarianceError takes it.
inline ImuCalibration CalibrationOf(const MountedImu& m) {
  ImuCalibration c;
  c.model = m.model;
  c.intrinsics = m.intrinsics;
  c.intrinsics.C_i_b = m.C_i_b.matrix();
  c.intrinsics.r_b = m.r_b;
  c.time_offset_s = m.time_offset_s;
  return c;
}

// A group of an IMU's parameters whose NEES a Monte-Carlo test sums over its runs: the exact one,
// e_g^T Sigma_g^-1 e_g with Sigma_g the group's block of the reported covariance (cross terms
// within the group included; testing::Mahalanobis), which is chi-square(dof) per run for honest
// Gaussian errors; and, for comparison, the diagonal one sum_i (e_i / sigma_i)^2, whose spread
// over the runs is wider than chi-square's when the entries correlate.
struct ImuNeesGroup {
  std::string name;
  std::vector<ImuParameter> parameters;
  int dof = 0;  // its rows in the covariance (a held entry would leave fewer: asserted)
  double sum = 0.0;
  double diagonal_sum = 0.0;
};

// The model's groups: scale/misalignment as two groups (M_a, M_g: the two sensors' own matrices),
// the g-sensitivity A, the gyro frame C_gyro_i, and with the size effect the accelerometers' lever
// arms ry_i, rz_i as one group. `prefix` starts their names.
inline std::vector<ImuNeesGroup> ImuModelNeesGroups(ImuModelKind kind,
                                                    const std::string& prefix = "") {
  std::vector<ImuNeesGroup> groups = {{prefix + "M_a", {ImuParameter::kMa}, 6},
                                      {prefix + "M_g", {ImuParameter::kMg}, 6},
                                      {prefix + "A", {ImuParameter::kA}, 9},
                                      {prefix + "C_gyro_i", {ImuParameter::kCGyroI}, 3}};
  if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
    groups.push_back({prefix + "ry_i, rz_i", {ImuParameter::kRyI, ImuParameter::kRzI}, 6});
  }
  return groups;
}

// A further IMU's pose and clock: its rotation C_i_b, lever arm r_b and time offset.
inline std::vector<ImuNeesGroup> FurtherImuNeesGroups(const std::string& prefix = "") {
  return {{prefix + "C_i_b", {ImuParameter::kCIB}, 3},
          {prefix + "r_b", {ImuParameter::kRB}, 3},
          {prefix + "time offset", {ImuParameter::kTimeOffset}, 1}};
}

// Adds one run's NEES of each group (its error e in `covariance`'s entries, ImuCovarianceError)
// to the groups' sums and prints it; every group must have its dof rows and a finite NEES.
inline void AddImuNees(const ImuCovariance& covariance,
                       const Eigen::VectorXd& e,
                       std::vector<ImuNeesGroup>* groups) {
  for (ImuNeesGroup& group : *groups) {
    const std::vector<int> rows = covariance.Rows(group.parameters);
    ASSERT_EQ(static_cast<int>(rows.size()), group.dof) << group.name;
    Eigen::VectorXd e_g(group.dof);
    double diagonal = 0.0;
    for (int i = 0; i < group.dof; ++i) {
      e_g[i] = e[rows[i]];
      diagonal += e_g[i] * e_g[i] / covariance.matrix(rows[i], rows[i]);
    }
    const double nees = Mahalanobis(e_g, covariance.Block(group.parameters));
    ASSERT_TRUE(std::isfinite(nees) && std::isfinite(diagonal)) << group.name;
    group.sum += nees;
    group.diagonal_sum += diagonal;
    std::printf(" %s %.2f (diag %.2f)", group.name.c_str(), nees, diagonal);
  }
}

// Prints each group's exact and diagonal sums with chi-square(runs x dof)'s 95% interval, and
// expects the exact sum inside the family-wise interval of all `num_groups` groups the test
// asserts (ChiSquareFamilyInterval95): below it the reported uncertainty is too pessimistic,
// above it overconfident.
inline void ExpectImuNeesInsideFamilyInterval95(const std::vector<ImuNeesGroup>& groups,
                                                int runs,
                                                int num_groups) {
  for (const ImuNeesGroup& group : groups) {
    const ChiSquareInterval band = ChiSquareInterval95(runs * group.dof);
    const ChiSquareInterval family = ChiSquareFamilyInterval95(runs * group.dof, num_groups);
    std::printf(
        "%s: NEES sum %.2f over %d runs (dof %d; diagonal sum %.2f), 95%% interval [%.2f, "
        "%.2f]%s, family-wise over %d groups [%.2f, %.2f]\n",
        group.name.c_str(),
        group.sum,
        runs,
        group.dof,
        group.diagonal_sum,
        band.low,
        band.high,
        group.sum < band.low || group.sum > band.high ? " (outside)" : "",
        num_groups,
        family.low,
        family.high);
    EXPECT_GE(group.sum, family.low) << group.name << ": uncertainty too pessimistic";
    EXPECT_LE(group.sum, family.high) << group.name << ": uncertainty overconfident";
  }
}

// The NEES sums of a Monte-Carlo test over its runs, and the lowest excitation.
struct NeesRuns {
  std::vector<ImuNeesGroup> groups;        // from an IMU's covariance: exact
  std::vector<NeesGroup> diagonal_groups;  // of per-entry normalised errors only (T_cam_imu: the
                                           // result has its stds, not its covariance)
  double w_rms_min = 1e9;
  double dw_rms_min = 1e9;

  // One run: prints its solve time, excitation (Excitation) and each group's NEES, and adds
  // them to the sums; `covariance` and `e` (ImuCovarianceError) for `groups`, `z` the normalised
  // errors indexed by `diagonal_groups` (each must be finite).
  void Add(int run,
           double solve_time_s,
           double w_rms,
           double dw_rms,
           const ImuCovariance& covariance,
           const Eigen::VectorXd& e,
           const std::vector<double>& z) {
    w_rms_min = std::min(w_rms_min, w_rms);
    dw_rms_min = std::min(dw_rms_min, dw_rms);
    std::printf("seed %2d (%.1f s solve, w RMS %.2f rad/s, dw RMS %.2f rad/s^2):",
                run,
                solve_time_s,
                w_rms,
                dw_rms);
    AddImuNees(covariance, e, &groups);
    for (NeesGroup& group : diagonal_groups) {
      double nees = 0.0;
      for (int i = group.first; i < group.first + group.dof; ++i) {
        ASSERT_TRUE(std::isfinite(z[i])) << group.name << " seed " << run;
        nees += z[i] * z[i];
      }
      group.sum += nees;
      std::printf(" %s %.2f (diag)", group.name, nees);
    }
    std::printf("\n");
    std::fflush(stdout);
  }

  // Prints the lowest excitation; expects every exact group's sum inside the family-wise interval
  // of the exact groups (ExpectImuNeesInsideFamilyInterval95), every diagonal group's inside its
  // 95% interval.
  void Expect(int runs) const {
    std::printf(
        "excitation, lowest over the seeds: rotation rate RMS %.2f rad/s, angular "
        "acceleration RMS %.2f rad/s^2\n",
        w_rms_min,
        dw_rms_min);
    ExpectImuNeesInsideFamilyInterval95(groups, runs, static_cast<int>(groups.size()));
    ExpectNeesSumsInsideInterval95(diagonal_groups, runs);
  }
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_
