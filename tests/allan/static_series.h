// Test helper: the static recording of one IMU axis in Kalibr's discrete noise model
// (docs/conventions.md, "IMU model"), generated directly from a seeded std::mt19937_64:
//
//     y_k = offset + b_k + sigma * sqrt(f) * z_k,    b_0 = 0,   b_k = b_{k-1} + sigma_rw / sqrt(f)
//     * w_k
//
// with z_k, w_k independent N(0, 1). The unit draws are kept so that the same noise can be scaled
// (the seed's 10x, 100x, 1000x experiment).
#ifndef SPLINECAL_TESTS_ALLAN_STATIC_SERIES_H_
#define SPLINECAL_TESTS_ALLAN_STATIC_SERIES_H_

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace splinecal {
namespace testing {

struct UnitDraws {
  std::vector<double> white;  // z_k
  std::vector<double> steps;  // w_k (w_0 unused)
};

inline UnitDraws MakeUnitDraws(int64_t n, uint64_t seed) {
  std::mt19937_64 engine(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  UnitDraws draws;
  draws.white.resize(n);
  draws.steps.resize(n);
  for (int64_t k = 0; k < n; ++k) {
    draws.white[k] = normal(engine);
    draws.steps[k] = normal(engine);
  }
  return draws;
}

// noise_density sigma [unit/sqrt(Hz)], random_walk sigma_rw [unit/s/sqrt(Hz)], rate f [Hz].
inline std::vector<double> StaticAxis(const UnitDraws& draws,
                                      double rate_hz,
                                      double noise_density,
                                      double random_walk,
                                      double offset) {
  const double white_std = noise_density * std::sqrt(rate_hz);
  const double step_std = random_walk / std::sqrt(rate_hz);
  std::vector<double> y(draws.white.size());
  double bias = 0.0;
  for (size_t k = 0; k < y.size(); ++k) {
    if (k > 0) bias += step_std * draws.steps[k];
    y[k] = offset + bias + white_std * draws.white[k];
  }
  return y;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_ALLAN_STATIC_SERIES_H_
