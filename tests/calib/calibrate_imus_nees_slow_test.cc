// Monte-Carlo consistency of the further IMU's reported standard deviations (label "slow"): the
// diagonal NEES of its rotation C_i_b (3, right tangent), lever arm r_b (3) and time offset (1)
// over 20 seeds of a two-IMU rig (calib/several_imus_round_trip.h's kImu1 on the reference IMU's
// closed-form trajectory, calib/closed_form_simulation.h, which the estimator's spline only
// approximates). Each seed draws another trajectory (periods, phases), camera and reference-IMU
// noise (ScenarioOptions::seed) and another noise of the further IMU (MountedImu::seed).
//
// As in calibrate_nees_slow_test.cc the NEES is the diagonal one, sum_i (e_i / std_i)^2:
// FurtherImuEstimate reports per-axis stds, not their correlations. Its mean is the dimension
// when the stds are honest; for the 3-D groups the sum over seeds is not exactly chi-square
// (correlated axes widen its spread), the 1-D time offset's is. Each group's sum must lie in the
// two-sided 95% interval of chi-square with seeds x dof degrees of freedom (testing/chi_square.h).
//
// OPEN: the rotation C_i_b is outside its interval, overconfident, and is printed, not asserted
// (2026-11-28, this test: NEES sum 105.0 over 20 runs, mean 5.25 per run, 95% interval
// [40.47, 83.30]; the lever arm 70.5 and the time offset 31.5 [9.57, 34.17] inside). What runs
// with temporary switches in this test showed (10 seeds each unless said; mean NEES per run of
// rotation / lever arm / time offset; seeds 1-10 as they are: 6.18 / 3.71 / 2.49):
//   - not the spline's approximation of the closed-form motion: 0.025 s knots instead of 0.05 s,
//     20 seeds, 5.26 / 3.59 / 1.61, every error and std nearly as at 0.05 s;
//   - not the IMU-noise estimation: ImuNoiseMode::kGiven 6.21 / 3.76 / 2.51, the same errors;
//     the reference IMU's measured white noise is 0.99-1.03 of the given density (seeds 1-3);
//   - not a wrong derivative of the further IMU's residuals: their Jacobians match central
//     differences (tests/estimation/further_imu_cost_test.cc);
//   - not an unconverged solve: the further IMU's time offset started 0.3 ms off converged to the
//     same estimate on every seed (8 seeds);
//   - not the mounting: C_i_b = I 4.19 / 3.16 / 1.87; no clock offset 6.25 / 3.66 / 2.58;
//   - not seeds shared with the camera's noise (further IMU seeds 1001-1010: 5.17 / 2.90 / 1.28);
//   - it is the reference IMU's gyro white noise: with it 100x smaller in the simulation (the
//     estimator still assuming the ADIS16448's), 2.91 / 3.55 / 1.00; with the reference's
//     accelerometer noise 100x smaller instead, 5.83 / 1.62 / 2.46; with the reference IMU
//     noise-free, 2.62 / 1.25 / 1.03.
// So the reported covariance under-counts how the reference gyro's noise reaches C_i_b (and the
// time offset, inside its interval over 20 seeds but near its top) through the spline's angular
// velocity, by about a factor 2 in variance.
// Ruled out next (docs/calibrate.md "Are the further IMUs' stds honest?"): the reported covariance
// equals Ceres' SPARSE_QR covariance of the uncompressed problem (the full marginal; the
// re-weightings' inflation 1.000-1.013); tolerances of 1e-20 give the same estimates; the errors
// are centred (mean z per rotation axis -0.14, -0.15, -0.10 over seeds 1-19); the generator's
// gyro noise is white with the assumed std. With kGiven densities, the reference's gyro white
// noise 100x smaller gives 2.91 / 3.57 / 1.00 while the covariance still counts about half of the
// gyro share for it: the further IMU's own gyro noise too reaches C_i_b about twice as much in
// variance as the covariance says. Open.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calib/several_imus_round_trip.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace {

// 4 s recordings: 20 seeds in 9.5 s of Release CPU with two IMUs (the 8 s round trip costs 3.9 s
// of CPU per calibration, calibrate_imus_test.cc).
constexpr double kDurationS = 4.0;
constexpr int kSeeds = 20;
// The normalised errors of one further IMU (rotation 3, lever arm 3, time offset 1) and of the
// camera's T_cam_imu (rotation 3, translation 3), in that order in a run's error vector.
constexpr int kPerImu = 7;
constexpr int kCamera = 6;

// One seed's calibration of the reference IMU with `rig` mounted beside it (further IMU k drawing
// its noise from FurtherImuSeed(seed, k)): the normalised errors, kPerImu per further IMU, then
// kCamera for cam0.
std::vector<double> NormalisedErrors(int seed, const std::vector<testing::MountedImu>& rig) {
  testing::ScenarioOptions o;
  o.closed_form = true;
  o.duration_s = kDurationS;
  o.line_delay_s = 0.0;
  o.seed = static_cast<uint64_t>(seed);
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  std::vector<testing::MountedImu> mounted = rig;
  CalibrateOptions options = testing::FastOptions();
  options.keep_residuals = false;
  for (size_t k = 0; k < mounted.size(); ++k) {
    mounted[k].seed = testing::FurtherImuSeed(o.seed, static_cast<int>(k) + 1);
    options.further_imus.push_back(testing::Simulate(s, kDurationS, mounted[k]));
  }
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  EXPECT_TRUE(r.covariance_ok) << "seed " << seed;
  EXPECT_EQ(r.further_imus.size(), mounted.size());
  std::vector<double> z;
  std::printf("seed %2d (%.1f s):", seed, r.solve.solve_time_s);
  for (size_t k = 0; k < mounted.size() && k < r.further_imus.size(); ++k) {
    const FurtherImuEstimate& e = r.further_imus[k];
    const testing::MountedImu& m = mounted[k];
    EXPECT_FALSE(e.lever_arm_held) << "seed " << seed << " imu" << k + 1;
    // C_i_b's error in its right tangent (the std's): C_true^T C_est = Exp(phi).
    const Eigen::Vector3d phi_deg =
        (m.C_i_b.inverse() * SO3d::FromMatrix(e.calibration.intrinsics.C_i_b)).Log() * kRadToDeg;
    const Eigen::Vector3d dr = e.calibration.intrinsics.r_b - m.r_b;
    for (int a = 0; a < 3; ++a) z.push_back(phi_deg[a] / e.rotation_std_deg[a]);
    for (int a = 0; a < 3; ++a) z.push_back(dr[a] / e.r_b_std_m[a]);
    z.push_back((e.calibration.time_offset_s - m.time_offset_s) / e.time_offset_std_s);
  }
  const testing::Errors c = testing::ErrorsOf(r.cameras[0].calibration, s.truth[0]);
  for (int a = 0; a < 3; ++a) z.push_back(c.rotation_deg[a] / r.cameras[0].rotation_std_deg[a]);
  for (int a = 0; a < 3; ++a) z.push_back(c.translation_m[a] / r.cameras[0].translation_std_m[a]);
  for (size_t i = 0; i < z.size(); ++i) {
    std::printf("%s%+.2f", i % 3 == 0 && i % kPerImu != 0 ? " | " : " ", z[i]);
  }
  std::printf("\n");
  std::fflush(stdout);
  return z;
}

// The groups of a rig of `imus` further IMUs: each IMU's rotation, lever arm and time offset,
// then T_cam_imu's rotation and translation. `names` keeps the groups' names alive.
std::vector<testing::NeesGroup> Groups(int imus, std::vector<std::string>* names) {
  names->clear();
  for (int k = 1; k <= imus; ++k) {
    for (const char* what : {"rotation C_i_b", "lever arm r_b", "time offset"}) {
      names->push_back("imu" + std::to_string(k) + " " + what);
    }
  }
  names->push_back("cam0 T_cam_imu rotation");
  names->push_back("cam0 T_cam_imu translation");
  std::vector<testing::NeesGroup> groups;
  for (int k = 0; k < imus; ++k) {
    const int first = kPerImu * k;
    groups.push_back({(*names)[3 * k].c_str(), first, 3});
    groups.push_back({(*names)[3 * k + 1].c_str(), first + 3, 3});
    groups.push_back({(*names)[3 * k + 2].c_str(), first + 6, 1});
  }
  groups.push_back({(*names)[3 * imus].c_str(), kPerImu * imus, 3});
  groups.push_back({(*names)[3 * imus + 1].c_str(), kPerImu * imus + 3, 3});
  return groups;
}

// Every group's NEES summed over kSeeds seeds of the rig, inside its 95% interval.
void ExpectRigNeesInsideIntervals(const std::vector<testing::MountedImu>& rig) {
  std::vector<std::string> names;
  std::vector<testing::NeesGroup> groups = Groups(static_cast<int>(rig.size()), &names);
  for (int seed = 1; seed <= kSeeds; ++seed) {
    const std::vector<double> z = NormalisedErrors(seed, rig);
    ASSERT_EQ(z.size(), rig.size() * kPerImu + kCamera) << "seed " << seed;
    for (testing::NeesGroup& group : groups) {
      for (int i = group.first; i < group.first + group.dof; ++i) group.sum += z[i] * z[i];
    }
  }
  testing::ExpectNeesSumsInsideInterval95(groups, kSeeds);
}

TEST(CalibrateImusMonteCarlo, TwoImusDiagonalNeesInsideItsIntervals) {
  ExpectRigNeesInsideIntervals({testing::kImu1});
}

TEST(CalibrateImusMonteCarlo, ThreeImusDiagonalNeesInsideItsIntervals) {
  ExpectRigNeesInsideIntervals({testing::kImu1, testing::kImu2});
}

}  // namespace
}  // namespace splinecal
