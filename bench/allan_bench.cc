// Benchmarks of `splinecal allan` (issue 4 targets, docs/performance.md):
//   - BM_AllanDeviationOneAxis: one axis of 10^7 samples at 65 log-spaced averaging times
//     (target <= 0.35 s; allantools takes 3.6 s).
//   - BM_IntegrateOneAxis: building the integrated signal alone (part of the above).
//
// Run: build-xxx/bench/allan_bench --benchmark_filter=OneAxis
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "splinecal/allan/allan_deviation.h"

namespace splinecal {
namespace {

constexpr int64_t kNumSamples = 10'000'000;
constexpr double kRateHz = 200.0;

// 65 distinct cluster sizes, log-spaced from 1 to 10^6 (a tenth of the record).
std::vector<int64_t> SixtyFiveClusterSizes() {
  constexpr int kCount = 65;
  std::vector<int64_t> sizes;
  for (int j = 0; j < kCount; ++j) {
    int64_t m = std::llround(std::pow(10.0, 6.0 * j / (kCount - 1)));
    if (!sizes.empty()) m = std::max(m, sizes.back() + 1);
    sizes.push_back(m);
  }
  return sizes;
}

// A gyro-like axis: white noise plus a bias random walk (EuRoC ADIS16448 densities at 200 Hz).
std::vector<double> GyroAxis(int64_t n) {
  std::mt19937_64 engine(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double white_std = 1.6968e-4 * std::sqrt(kRateHz);
  const double step_std = 1.9393e-5 / std::sqrt(kRateHz);
  std::vector<double> y(n);
  double bias = 0.01;
  for (int64_t i = 0; i < n; ++i) {
    bias += step_std * normal(engine);
    y[i] = bias + white_std * normal(engine);
  }
  return y;
}

const std::vector<double>& Samples() {
  static const std::vector<double> samples = GyroAxis(kNumSamples);
  return samples;
}

void BM_AllanDeviationOneAxis(benchmark::State& state) {
  const std::vector<int64_t> sizes = SixtyFiveClusterSizes();
  for (auto _ : state) {
    std::vector<double> copy = Samples();
    const IntegratedSignal signal(std::move(copy), kRateHz, "gyro x");
    const AllanCurve curve = signal.Deviation(sizes);
    benchmark::DoNotOptimize(curve.adev.data());
  }
  state.counters["taus"] = static_cast<double>(sizes.size());
  state.counters["samples"] = static_cast<double>(kNumSamples);
}
BENCHMARK(BM_AllanDeviationOneAxis)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// The passes over the integrated signal alone (the 65 averaging times).
void BM_DeviationPassesOneAxis(benchmark::State& state) {
  const std::vector<int64_t> sizes = SixtyFiveClusterSizes();
  std::vector<double> copy = Samples();
  const IntegratedSignal signal(std::move(copy), kRateHz, "gyro x");
  for (auto _ : state) {
    const AllanCurve curve = signal.Deviation(sizes);
    benchmark::DoNotOptimize(curve.adev.data());
  }
}
BENCHMARK(BM_DeviationPassesOneAxis)->Unit(benchmark::kMillisecond);

void BM_IntegrateOneAxis(benchmark::State& state) {
  for (auto _ : state) {
    std::vector<double> copy = Samples();
    const IntegratedSignal signal(std::move(copy), kRateHz, "gyro x");
    benchmark::DoNotOptimize(signal.mean());
  }
}
BENCHMARK(BM_IntegrateOneAxis)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
