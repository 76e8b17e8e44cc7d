// Monte-Carlo check of the noise fit (label "slow"): 10 independent 4-hour recordings of the
// EuRoC ADIS16448 at 200 Hz; the mean recovered/true ratio of every key within 10%.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "allan/static_series.h"
#include "splinecal/allan/allan_deviation.h"
#include "splinecal/allan/noise_fit.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

constexpr double kRateHz = 200.0;
constexpr int kSeeds = 10;
// The bar for the mean over 10 seeds (docs/allan.md, "How each term is decided"): 10%.
constexpr double kMeanTolerance = 0.10;

struct Sensor {
  const char* name;
  double noise_density;
  double random_walk;
  double offset;
};

TEST(FitNoiseMonteCarlo, MeanOverTenSeedsWithinTenPercent) {
  const Sensor sensors[] = {{"gyro", 1.6968e-4, 1.9393e-5, 0.01}, {"accel", 2.0e-3, 3.0e-3, 9.81}};
  constexpr int64_t kSamples = static_cast<int64_t>(4 * 3600 * kRateHz);
  const std::vector<int64_t> sizes = AllanClusterSizes(kSamples, 10, 0.1);
  for (const Sensor& sensor : sensors) {
    double sum_n = 0.0;
    double sum_k = 0.0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      const testing::UnitDraws draws = testing::MakeUnitDraws(kSamples, 1000 * seed + 7);
      std::vector<double> y = testing::StaticAxis(
          draws, kRateHz, sensor.noise_density, sensor.random_walk, sensor.offset);
      const AxisNoiseFit fit =
          FitNoise(IntegratedSignal(std::move(y), kRateHz, sensor.name).Deviation(sizes));
      ASSERT_TRUE(fit[NoiseTerm::kWhite].identified) << fit[NoiseTerm::kWhite].reason;
      ASSERT_TRUE(fit[NoiseTerm::kRandomWalk].identified) << fit[NoiseTerm::kRandomWalk].reason;
      const double n_ratio = fit[NoiseTerm::kWhite].value / sensor.noise_density;
      const double k_ratio = fit[NoiseTerm::kRandomWalk].value / sensor.random_walk;
      std::printf("%s seed %d: N ratio %.4f, K ratio %.4f (model N %.4f, K %.4f)\n",
                  sensor.name,
                  seed,
                  n_ratio,
                  k_ratio,
                  fit.model[NoiseTerm::kWhite] / sensor.noise_density,
                  fit.model[NoiseTerm::kRandomWalk] / sensor.random_walk);
      sum_n += n_ratio;
      sum_k += k_ratio;
    }
    std::printf(
        "%s mean: N ratio %.4f, K ratio %.4f\n", sensor.name, sum_n / kSeeds, sum_k / kSeeds);
    EXPECT_NEAR(sum_n / kSeeds, 1.0, kMeanTolerance) << sensor.name;
    EXPECT_NEAR(sum_k / kSeeds, 1.0, kMeanTolerance) << sensor.name;
  }
}

}  // namespace
}  // namespace splinecal
