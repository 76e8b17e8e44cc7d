// Monte-Carlo consistency of a further IMU's model (label "slow"): the reference IMU `calibrated`,
// the further one (calib/several_imus_round_trip.h's kImu1, turned ~75 deg, 11 cm away, 2 ms
// late) with `scale-misalignment` or `scale-misalignment-size-effect` and WithModel's errors
// (`--imu-model calibrated,scale-misalignment`). Per group of its parameters -- M_a, M_g (lower
// triangles), A, C_gyro_i, the size effect's ry_i, rz_i (one group), its rotation C_i_b (right
// tangent), lever arm r_b and time offset -- the exact NEES e_g^T Sigma_g^-1 e_g, Sigma_g the
// group's block of FurtherImuEstimate::covariance (calib/imu_model_nees.h), summed over 20 seeds
// must lie in chi-square(20 x dof)'s two-sided 95% interval (testing/chi_square.h). The diagonal
// sums sum_i (e_i / std_i)^2 are printed beside them: with the entries' correlations (up to 0.73
// within A, 0.85 within ry_i, rz_i, 0.65 within r_b over these runs) they spread wider than that
// interval, which is why the exact NEES is the one asserted. docs/imu_models.md ("A further IMU's
// model: NEES over 20 seeds") has the sums.
//
// Data: the closed-form trajectory (calib/calibrate_test_scenario.h, closed_form; no spline
// represents it exactly), both IMUs' readings from it (calib/closed_form_simulation.h, the
// further one through its model at its pose and clock offset), the ADIS16448's noise on both.
// Each seed draws another trajectory (periods, phases), other camera and reference-IMU noise
// (ScenarioOptions::seed) and another noise of the further IMU (MountedImu::seed =
// FurtherImuSeed(seed, 1), a stream no other sensor of the run draws from).
#include <gtest/gtest.h>

#include <vector>

#include "calib/imu_model_nees.h"
#include "calib/several_imus_round_trip.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace {

constexpr int kSeeds = 20;

struct Options {
  ImuModelKind model;
  double duration_s;
  double shake_amplitude_rad = 0.0;  // testing::ScenarioOptions::shake_amplitude_rad
  double knot_spacing_s = 0.05;      // the estimator's (CalibrateOptions::model)
};

void ExpectNeesInsideIntervals(const Options& opt) {
  const testing::MountedImu truth = testing::WithModel(testing::kImu1, opt.model);
  testing::NeesRuns runs;
  runs.groups = testing::ImuModelNeesGroups(opt.model);
  for (const testing::ImuNeesGroup& group : testing::FurtherImuNeesGroups()) {
    runs.groups.push_back(group);
  }
  for (int seed = 1; seed <= kSeeds; ++seed) {
    testing::ScenarioOptions o;
    o.closed_form = true;
    o.duration_s = opt.duration_s;
    o.line_delay_s = 0.0;
    o.seed = static_cast<uint64_t>(seed);
    o.shake_amplitude_rad = opt.shake_amplitude_rad;
    const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
    double w_rms = 0.0;
    double dw_rms = 0.0;
    testing::Excitation(*s.trajectory, opt.duration_s, &w_rms, &dw_rms);
    testing::MountedImu mounted = truth;
    mounted.seed = testing::FurtherImuSeed(o.seed, 1);
    CalibrateOptions options = testing::FastOptions();
    options.keep_residuals = false;
    options.model.knot_spacing_s = opt.knot_spacing_s;
    options.further_imus.push_back(testing::Simulate(s, opt.duration_s, mounted));
    const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
    ASSERT_TRUE(r.covariance_ok) << "seed " << seed;
    ASSERT_EQ(r.further_imus.size(), 1u);
    const FurtherImuEstimate& e = r.further_imus[0];
    ASSERT_FALSE(e.lever_arm_held) << "seed " << seed;
    runs.Add(
        seed,
        r.solve.solve_time_s,
        w_rms,
        dw_rms,
        e.covariance,
        testing::ImuCovarianceError(e.covariance, e.calibration, testing::CalibrationOf(mounted)),
        {});
    if (::testing::Test::HasFatalFailure()) return;
  }
  runs.Expect(kSeeds);
}

// 4 s recordings: 20 calibrations in 13.7 s of Release CPU (42 s wall on the loaded 2-core
// machine, 2026-11-28).
TEST(CalibrateImusModelMonteCarlo, FurtherScaleMisalignment) {
  ExpectNeesInsideIntervals({ImuModelKind::kScaleMisalignment, 4.0});
}

// The size effect's lever arms need angular acceleration: the shaken trajectory and 0.025 s knots
// of the reference's test (calibrate_imu_model_nees_slow_test.cc says why). ry_i, rz_i's exact
// NEES sum on seeds 1-20 is 86.85, below its own 95% interval [91.57, 152.21] but inside the
// family-wise one of the test's 8 groups (their stds pessimistic; the diagonal sum 78.52), on
// seeds 21-40 112.46 (a temporary change of the seeds, 2026-11-29), pooled 199.31 over 240 dof,
// at the bottom of chi-square(240)'s interval: the lever arms' stds look ~10% large, likely the
// covariance's inflation (each std the larger of two cluster-robust estimates, never below the
// noise model's, calibrate.h). docs/imu_models.md has the sums. 4 s recordings: 20 calibrations
// in 24.0 s of Release CPU (87 s wall on the loaded 2-core machine, 2026-11-28).
TEST(CalibrateImusModelMonteCarlo, FurtherScaleMisalignmentSizeEffect) {
  ExpectNeesInsideIntervals({ImuModelKind::kScaleMisalignmentSizeEffect, 4.0, 0.1, 0.025});
}

}  // namespace
}  // namespace splinecal
