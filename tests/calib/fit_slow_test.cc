// Monte-Carlo check that the fit's covariance is honest (issue: "the normalised estimation error
// squared for the 6-D bias is inside its 95% chi-square interval"). Slow-labelled.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calib/fit_test_data.h"
#include "splinecal/calib/fit.h"

namespace splinecal {
namespace {

using testing::FitData;
using testing::FitScenario;
using testing::MakeFitData;

// Runs and degrees of freedom per run (the 6-D bias).
constexpr int kRuns = 25;
constexpr int kDof = 6;

// Quantile of the chi-square distribution with k degrees of freedom by the Wilson-Hilferty
// approximation (chi2_k ~ k (1 - 2/(9k) + z sqrt(2/(9k)))^3, z the normal quantile); relative
// error < 1e-3 for k >= 100.
double ChiSquareQuantile(double k, double z) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

TEST(FitMonteCarlo, BiasNeesIsInsideItsNinetyFivePercentInterval) {
  constexpr double kZ975 = 1.959963984540054;  // standard normal 97.5% quantile
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
  const double low = ChiSquareQuantile(k, -kZ975);
  const double high = ChiSquareQuantile(k, kZ975);
  RecordProperty("nees_mean", std::to_string(nees_sum / kRuns));
  EXPECT_GE(nees_sum, low) << "mean NEES " << nees_sum / kRuns << ": covariance too pessimistic";
  EXPECT_LE(nees_sum, high) << "mean NEES " << nees_sum / kRuns << ": covariance overconfident";
  std::printf("Monte Carlo: %d runs, mean 6-D bias NEES %.3f, 95%% interval [%.3f, %.3f]\n",
              kRuns,
              nees_sum / kRuns,
              low / kRuns,
              high / kRuns);
}

}  // namespace
}  // namespace splinecal
