// The pieces the Monte-Carlo consistency (NEES) tests of the IMU models share: the normalised
// errors (error / reported std) of a model's entries, their groups, and the excitation of a
// trajectory. calibrate_imu_model_nees_slow_test.cc uses them on the reference IMU,
// calibrate_imus_model_nees_slow_test.cc on a further IMU.
#ifndef SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_
#define SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "splinecal/calib/calibrate.h"
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

// The normalised errors of one matrix's entries (the lower triangle only when lower_triangle).
inline void AppendEntries(const Eigen::Matrix3d& estimate,
                          const Eigen::Matrix3d& truth,
                          const Eigen::Matrix3d& std_dev,
                          bool lower_triangle,
                          std::vector<double>* z) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < (lower_triangle ? r + 1 : 3); ++c) {
      z->push_back((estimate(r, c) - truth(r, c)) / std_dev(r, c));
    }
  }
}

inline void AppendVector(const Eigen::Vector3d& error,
                         const Eigen::Vector3d& std_dev,
                         std::vector<double>* z) {
  for (int a = 0; a < 3; ++a) z->push_back(error[a] / std_dev[a]);
}

// The normalised errors of a model's entries in the order of ImuModelNeesGroups: M_a and M_g
// (lower triangles), A, C_gyro_i (its error in the right tangent, C_true^T C_est = Exp(phi), in
// degrees as its std), and with the size effect ry_i, rz_i.
inline void AppendImuModelErrors(ImuModelKind kind,
                                 const ImuIntrinsicsd& estimate,
                                 const ImuIntrinsicsd& truth,
                                 const ImuModelStd& std_dev,
                                 std::vector<double>* z) {
  AppendEntries(estimate.M_a, truth.M_a, std_dev.M_a, true, z);
  AppendEntries(estimate.M_g, truth.M_g, std_dev.M_g, true, z);
  AppendEntries(estimate.A, truth.A, std_dev.A, false, z);
  AppendVector(SO3d::FromMatrix(truth.C_gyro_i.transpose() * estimate.C_gyro_i).Log() * kRadToDeg,
               std_dev.C_gyro_i_deg,
               z);
  if (kind != ImuModelKind::kScaleMisalignmentSizeEffect) return;
  AppendVector(estimate.ry_i - truth.ry_i, std_dev.ry_i, z);
  AppendVector(estimate.rz_i - truth.rz_i, std_dev.rz_i, z);
}

// The groups of AppendImuModelErrors' entries (indices from 0): 24 entries, 30 with the size
// effect.
inline std::vector<NeesGroup> ImuModelNeesGroups(ImuModelKind kind) {
  std::vector<NeesGroup> groups = {{"M_a", 0, 6}, {"M_g", 6, 6}, {"A", 12, 9}, {"C_gyro_i", 21, 3}};
  if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) groups.push_back({"ry_i, rz_i", 24, 6});
  return groups;
}

// The number of entries the groups cover (the index of the next group).
inline int NeesEntries(const std::vector<NeesGroup>& groups) {
  return groups.empty() ? 0 : groups.back().first + groups.back().dof;
}

// The NEES sums of a Monte-Carlo test's groups over its runs, and the lowest excitation.
struct NeesRuns {
  std::vector<NeesGroup> groups;
  std::vector<double> entry_sums;  // each entry's sum of squares over the runs
  double w_rms_min = 1e9;
  double dw_rms_min = 1e9;

  // Prints one run's normalised errors with its solve time and excitation (Excitation) and adds
  // their squares to the groups' sums; every one must be finite (a held entry has a NaN std).
  void Add(
      int run, double solve_time_s, double w_rms, double dw_rms, const std::vector<double>& z) {
    w_rms_min = std::min(w_rms_min, w_rms);
    dw_rms_min = std::min(dw_rms_min, dw_rms);
    std::printf("seed %2d (%.1f s solve, w RMS %.2f rad/s, dw RMS %.2f rad/s^2): z =",
                run,
                solve_time_s,
                w_rms,
                dw_rms);
    for (double v : z) std::printf(" %+.2f", v);
    std::printf("\n");
    std::fflush(stdout);
    entry_sums.resize(z.size(), 0.0);
    for (std::size_t i = 0; i < z.size(); ++i) entry_sums[i] += z[i] * z[i];
    for (NeesGroup& group : groups) {
      for (int i = group.first; i < group.first + group.dof; ++i) {
        ASSERT_TRUE(std::isfinite(z[i])) << group.name << " seed " << run;
        group.sum += z[i] * z[i];
      }
    }
  }

  // Prints the lowest excitation and expects every group's sum inside its 95% interval.
  void Expect(int runs) const {
    PrintExcitation();
    ExpectNeesSumsInsideInterval95(groups, runs);
  }

  // Prints the lowest excitation and each group's sum with its chi-square interval (not
  // expected: the interval holds for uncorrelated entries only), and expects each entry's sum
  // inside chi-square(runs)'s interval at the family-wise 95% level
  // (ExpectEachEntryNeesInsideFamilyInterval95).
  void ExpectEachEntry(int runs) const {
    PrintExcitation();
    for (const NeesGroup& group : groups) {
      const ChiSquareInterval band = ChiSquareInterval95(runs * group.dof);
      std::printf("%s: NEES sum %.2f over %d runs (dof %d; [%.2f, %.2f] if uncorrelated)\n",
                  group.name,
                  group.sum,
                  runs,
                  group.dof,
                  band.low,
                  band.high);
    }
    ExpectEachEntryNeesInsideFamilyInterval95(entry_sums, runs);
  }

  void PrintExcitation() const {
    std::printf(
        "excitation, lowest over the seeds: rotation rate RMS %.2f rad/s, angular "
        "acceleration RMS %.2f rad/s^2\n",
        w_rms_min,
        dw_rms_min);
  }
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_IMU_MODEL_NEES_H_
