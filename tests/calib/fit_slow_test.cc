// Monte-Carlo checks that the fit's covariance is honest (issue: "the normalised estimation error
// squared for the 6-D bias is inside its 95% chi-square interval"), and the same for gravity's
// direction, the time offset and the extrinsic T_m_s on data from a closed-form trajectory
// (calib/closed_form_simulation.h) that the fit's spline does not represent exactly.
// Slow-labelled.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "calib/fit_test_data.h"
#include "splinecal/calib/fit.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/units.h"
#include "testing/chi_square.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

using testing::FitData;
using testing::FitScenario;
using testing::MakeFitData;

// Runs and degrees of freedom per run (the 6-D bias).
constexpr int kRuns = 25;
constexpr int kDof = 6;

TEST(FitMonteCarlo, BiasNeesIsInsideItsNinetyFivePercentInterval) {
  double nees_sum = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    FitScenario scenario;
    scenario.duration_s = 30.0;
    scenario.trajectory_seed = 100 + run;
    scenario.noise_seed = 1000 + run;
    scenario.imu_noise = true;
    scenario.pose_noise = true;
    std::mt19937_64 rng(5000 + run);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int a = 0; a < 3; ++a) {
      scenario.gyro_bias[a] = 0.01 * normal(rng);
      scenario.accel_bias[a] = 0.1 * normal(rng);
    }
    const FitData data = MakeFitData(scenario);
    FitOptions options;
    options.model.knot_spacing_s = 0.1;
    options.model.noise = scenario.noise;
    options.keep_samples = false;
    const FitResult result = Fit(data.imu, data.poses, options);
    ASSERT_TRUE(result.covariance_ok) << "run " << run;
    Eigen::Matrix<double, 6, 1> error;
    error.head<3>() = result.gyro_bias - scenario.gyro_bias;
    error.tail<3>() = result.accel_bias - scenario.accel_bias;
    const Eigen::Matrix<double, 6, 6> covariance = result.covariance.topLeftCorner<6, 6>();
    const double nees = error.dot(covariance.ldlt().solve(error));
    nees_sum += nees;
    RecordProperty("nees_run_" + std::to_string(run), std::to_string(nees));
  }
  const double k = kRuns * kDof;
  const double low = testing::ChiSquareInterval95(k).low;
  const double high = testing::ChiSquareInterval95(k).high;
  RecordProperty("nees_mean", std::to_string(nees_sum / kRuns));
  EXPECT_GE(nees_sum, low) << "mean NEES " << nees_sum / kRuns << ": covariance too pessimistic";
  EXPECT_LE(nees_sum, high) << "mean NEES " << nees_sum / kRuns << ": covariance overconfident";
  std::printf("Monte Carlo: %d runs, mean 6-D bias NEES %.3f, 95%% interval [%.3f, %.3f]\n",
              kRuns,
              nees_sum / kRuns,
              low / kRuns,
              high / kRuns);
}

// NEES of gravity's direction (2-D tangent), the time offset (1) and the extrinsic T_m_s
// ([rho; phi], 6) from the joint covariance FitResult::covariance (rows 6..14: the fit's own
// tangent coordinates, so the full 9x9 block, correlations included). The errors are in the
// coordinates of the covariance, each as estimate - truth (the joint NEES depends on their
// relative signs through the correlations): gravity -Minus(g_true, g_est) of GravityManifold (in
// the tangent at the estimate, where the covariance is), the offset est - true, the extrinsic
// Log(T_true^-1 T_est) (SE3Manifold's Minus(est, true), to first order the same tangent). The data:
// 20 s of the "random" closed-form trajectory with periods 1-6 s (the default 2-20 s leaves the 0.1
// s spline nearly exact), 200 Hz ADIS16448 IMU noise with constant biases, 20 Hz poses with 1 mm /
// 1 mrad noise, a 5 ms offset and a ~10 cm / 5 deg extrinsic. Each group's sum over the runs and
// the joint sum must lie in the two-sided 95% chi-square interval of runs x dof degrees of freedom
// (Wilson-Hilferty, testing/chi_square.h). 120 seeds for the one-dimensional time offset: with 20,
// a variance 1.5 times too large passed its band 81% of the time and one 0.67 times too small
// 70%; with 120, 13% and 11% (P(band.low < chi2_120 / c < band.high) for c = 1.5, 0.67; exact
// chi-square CDF, docs/reliability.md "Power of the NEES bands").
TEST(FitMonteCarlo, GravityTimeOffsetAndExtrinsicNeesOnAClosedFormTrajectory) {
  constexpr int kSeeds = 120;
  // NeesGroup::first: row in FitResult::covariance.
  std::vector<testing::NeesGroup> groups = {
      {"gravity direction", 6, 2}, {"time offset", 8, 1}, {"T_m_s", 9, 6}, {"joint", 6, 9}};
  for (int run = 0; run < kSeeds; ++run) {
    FitScenario scenario;
    scenario.closed_form = true;
    scenario.duration_s = 20.0;
    scenario.trajectory_seed = 200 + run;
    scenario.random_trajectory.min_period_s = 1.0;
    scenario.random_trajectory.max_period_s = 6.0;
    scenario.random_trajectory.max_angular_rate_rad_s = 1.5;
    scenario.random_trajectory.max_acceleration_m_s2 = 3.0;
    scenario.noise_seed = 2000 + run;
    scenario.imu_noise = true;
    scenario.pose_noise = true;
    scenario.pose_rate_hz = 20.0;
    scenario.time_offset_s = 0.005;
    const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -1.0).normalized();
    scenario.T_m_s = SE3d(SO3d::Exp(5.0 / kRadToDeg * axis), Eigen::Vector3d(0.06, -0.05, 0.06));
    scenario.R_world = SO3d::Exp(Eigen::Vector3d(0.05, -0.08, 0.3));
    const FitData data = MakeFitData(scenario);
    FitOptions options;
    options.model.knot_spacing_s = 0.1;
    options.model.noise = scenario.noise;
    options.estimate_time_offset = true;
    options.estimate_extrinsic = true;
    options.keep_samples = false;
    const FitResult result = Fit(data.imu, data.poses, options);
    ASSERT_TRUE(result.covariance_ok) << "run " << run;
    ASSERT_EQ(result.covariance.rows(), 15);
    ASSERT_EQ(result.covariance_labels[6], "gravity_direction_1");
    ASSERT_EQ(result.covariance_labels[8], "time_offset");
    ASSERT_EQ(result.covariance_labels[9], "T_pose_imu_rho_x");
    Eigen::VectorXd error = Eigen::VectorXd::Zero(15);
    Eigen::Vector2d gravity_error = Eigen::Vector2d::Zero();
    ASSERT_TRUE(GravityManifold().Minus(
        data.gravity_w.data(), result.gravity_w.data(), gravity_error.data()));
    error.segment<2>(6) = -gravity_error;  // est - true, as the other errors
    error[8] = result.time_offset_s - scenario.time_offset_s;
    error.segment<6>(9) = (scenario.T_m_s.inverse() * result.T_m_s).Log();
    std::printf("run %2d:", run);
    for (testing::NeesGroup& group : groups) {
      const Eigen::VectorXd e = error.segment(group.first, group.dof);
      const Eigen::MatrixXd C =
          result.covariance.block(group.first, group.first, group.dof, group.dof);
      const double nees = e.dot(C.ldlt().solve(e));
      group.sum += nees;
      std::printf(" %s %.3f", group.name, nees);
    }
    std::printf("  (offset error %.3f ms, std %.3f ms)\n",
                1e3 * (result.time_offset_s - scenario.time_offset_s),
                1e3 * result.time_offset_std_s);
    std::fflush(stdout);
  }
  testing::ExpectNeesSumsInsideInterval95(groups, kSeeds);
}

}  // namespace
}  // namespace splinecal
