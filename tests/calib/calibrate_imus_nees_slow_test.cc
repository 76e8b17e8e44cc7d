// Monte-Carlo consistency of the further IMUs' reported uncertainty (label "slow"): per further
// IMU the exact NEES e_g^T Sigma_g^-1 e_g of its rotation C_i_b (3, right tangent), lever arm r_b
// (3) and time offset (1), Sigma_g the group's block of FurtherImuEstimate::covariance
// (calib/imu_model_nees.h), and the diagonal NEES of the camera's T_cam_imu (rotation 3,
// translation 3: per-axis stds only in the result), over 20 seeds of a two-IMU rig
// (calib/several_imus_round_trip.h's kImu1) and of a three-IMU rig (kImu1 and kImu2), on the
// reference IMU's closed-form trajectory (calib/closed_form_simulation.h), which the estimator's
// spline only approximates. Each seed draws another trajectory (periods, phases), camera and
// reference-IMU noise (ScenarioOptions::seed) and another noise of each further IMU
// (FurtherImuSeed: its own stream). Each group's sum must lie in the two-sided 95% interval of
// chi-square with seeds x dof degrees of freedom (testing/chi_square.h); the further IMUs'
// diagonal sums are printed beside the exact ones.
//
// The further IMU's rotation was outside its interval (diagonal NEES sum 105.0 over 20 runs,
// interval [40.47, 83.30]) while this test seeded it with 100 + seed, the seed the scenario gives
// the camera (seed + 100): the further IMU's noise was then the camera's pixel noise, draw for
// draw, and its errors correlated with the camera's. With a stream of its own, 73.6 (2026-11-28,
// docs/calibrate.md "Are the further IMUs' stds honest?", where the rest of the hunt is). The
// further IMUs' sums on the same seeds move together (they share the reference IMU's and the
// camera's noise through the spline): seeds 21-40 give imu2's rotation 38.18, just below its
// interval, and seeds 1-40 pooled 116.21 and 109.98, inside chi-square(120)'s [91.57, 152.21].

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calib/imu_model_nees.h"
#include "calib/several_imus_round_trip.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace {

// 4 s recordings: 20 seeds in 9.5 s of Release CPU with two IMUs (the 8 s round trip costs 3.9 s
// of CPU per calibration, calibrate_imus_test.cc).
constexpr double kDurationS = 4.0;
constexpr int kSeeds = 20;
// The camera's normalised errors (T_cam_imu's rotation 3, translation 3).
constexpr int kCamera = 6;

// One seed's calibration of the reference IMU with `rig` mounted beside it (further IMU k drawing
// its noise from FurtherImuSeed(seed, k)): adds each further IMU's exact NEES per group to
// imu_groups[k] (its own covariance, FurtherImuEstimate::covariance) and cam0's diagonal NEES to
// camera_groups (kCamera normalised errors: rotation 3, translation 3).
void AddSeed(int seed,
             const std::vector<testing::MountedImu>& rig,
             std::vector<std::vector<testing::ImuNeesGroup>>* imu_groups,
             std::vector<testing::NeesGroup>* camera_groups) {
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
  ASSERT_TRUE(r.covariance_ok) << "seed " << seed;
  ASSERT_EQ(r.further_imus.size(), mounted.size());
  std::printf("seed %2d (%.1f s):", seed, r.solve.solve_time_s);
  for (size_t k = 0; k < mounted.size(); ++k) {
    const FurtherImuEstimate& e = r.further_imus[k];
    ASSERT_FALSE(e.lever_arm_held) << "seed " << seed << " imu" << k + 1;
    testing::AddImuNees(e.covariance,
                        testing::ImuCovarianceError(
                            e.covariance, e.calibration, testing::CalibrationOf(mounted[k])),
                        &(*imu_groups)[k]);
    if (::testing::Test::HasFatalFailure()) return;
  }
  const testing::Errors c = testing::ErrorsOf(r.cameras[0].calibration, s.truth[0]);
  std::vector<double> z;
  testing::AppendVector(c.rotation_deg, r.cameras[0].rotation_std_deg, &z);
  testing::AppendVector(c.translation_m, r.cameras[0].translation_std_m, &z);
  ASSERT_EQ(static_cast<int>(z.size()), kCamera);
  for (testing::NeesGroup& group : *camera_groups) {
    double nees = 0.0;
    for (int i = group.first; i < group.first + group.dof; ++i) nees += z[i] * z[i];
    group.sum += nees;
    std::printf(" %s %.2f (diag)", group.name, nees);
  }
  std::printf("\n");
  std::fflush(stdout);
}

// Every group's NEES summed over kSeeds seeds of the rig: each further IMU's C_i_b, r_b and time
// offset exactly, inside the family-wise interval of all the IMUs' groups; T_cam_imu's rotation
// and translation diagonally, inside their 95% intervals.
void ExpectRigNeesInsideIntervals(const std::vector<testing::MountedImu>& rig) {
  std::vector<std::vector<testing::ImuNeesGroup>> imu_groups;
  for (size_t k = 0; k < rig.size(); ++k) {
    imu_groups.push_back(testing::FurtherImuNeesGroups("imu" + std::to_string(k + 1) + " "));
  }
  std::vector<testing::NeesGroup> camera_groups = {{"cam0 T_cam_imu rotation", 0, 3},
                                                   {"cam0 T_cam_imu translation", 3, 3}};
  for (int seed = 1; seed <= kSeeds; ++seed) {
    AddSeed(seed, rig, &imu_groups, &camera_groups);
    if (::testing::Test::HasFatalFailure()) return;
  }
  const int num_groups = 3 * static_cast<int>(imu_groups.size());
  for (const std::vector<testing::ImuNeesGroup>& groups : imu_groups) {
    testing::ExpectImuNeesInsideFamilyInterval95(groups, kSeeds, num_groups);
  }
  testing::ExpectNeesSumsInsideInterval95(camera_groups, kSeeds);
}

TEST(CalibrateImusMonteCarlo, TwoImusNeesInsideItsIntervals) {
  ExpectRigNeesInsideIntervals({testing::kImu1});
}

TEST(CalibrateImusMonteCarlo, ThreeImusNeesInsideItsIntervals) {
  ExpectRigNeesInsideIntervals({testing::kImu1, testing::kImu2});
}

}  // namespace
}  // namespace splinecal
