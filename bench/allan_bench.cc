// Benchmarks of `splinecal allan` (targets in docs/performance.md):
//   - BM_AllanDeviationOneAxis: one axis of 10^7 samples at 65 log-spaced averaging times
//     (target <= 0.35 s; allantools takes 3.6 s).
//   - BM_DeviationPassesOneAxis / BM_IntegrateOneAxis: its two parts.
//   - BM_ReadEuroc10M: parsing a 10^7-row EuRoC imu0/data.csv (1.3 GB, written to the temp folder
//     once; allantools' CSV parse takes 2 s).
//   - BM_WholeRun10M: what `splinecal allan --imu` does on that file: parse, six axes on the
//     machine's threads, noise fit (target <= 3 s on 2 cores).
//
// Run: build-xxx/bench/allan_bench --benchmark_filter=OneAxis
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "splinecal/allan/allan.h"
#include "splinecal/allan/allan_deviation.h"
#include "splinecal/io/static_recording.h"

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

// Arg: threads. The input is copied outside the timed region (it is in memory already).
void BM_AllanDeviationOneAxis(benchmark::State& state) {
  const std::vector<int64_t> sizes = SixtyFiveClusterSizes();
  for (auto _ : state) {
    state.PauseTiming();
    std::vector<double> copy = Samples();
    state.ResumeTiming();
    const IntegratedSignal signal(std::move(copy), kRateHz, "gyro x");
    const AllanCurve curve = signal.Deviation(sizes, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(curve.adev.data());
  }
  state.counters["taus"] = static_cast<double>(sizes.size());
  state.counters["samples"] = static_cast<double>(kNumSamples);
}
BENCHMARK(BM_AllanDeviationOneAxis)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0)
    ->Arg(1)
    ->Arg(2);

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
    state.PauseTiming();
    std::vector<double> copy = Samples();
    state.ResumeTiming();
    const IntegratedSignal signal(std::move(copy), kRateHz, "gyro x");
    benchmark::DoNotOptimize(signal.mean());
  }
}
BENCHMARK(BM_IntegrateOneAxis)->Unit(benchmark::kMillisecond);

// A 10^7-row static EuRoC file in the temp folder, written on first use, removed at exit.
class EurocFile {
 public:
  EurocFile() {
    path_ = (std::filesystem::temp_directory_path() / "splinecal_allan_bench_imu0.csv").string();
    std::FILE* file = std::fopen(path_.c_str(), "w");
    std::fputs(
        "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
        "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n",
        file);
    std::mt19937_64 engine(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    const double white[6] = {2.4e-3, 2.4e-3, 2.4e-3, 2.8e-2, 2.8e-2, 2.8e-2};
    const double step[6] = {1.4e-6, 1.4e-6, 1.4e-6, 2.1e-4, 2.1e-4, 2.1e-4};
    double bias[6] = {0.01, -0.02, 0.003, 0.1, -0.2, 9.81};
    for (int64_t k = 0; k < kNumSamples; ++k) {
      double y[6];
      for (int a = 0; a < 6; ++a) {
        bias[a] += step[a] * normal(engine);
        y[a] = bias[a] + white[a] * normal(engine);
      }
      std::fprintf(file,
                   "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                   static_cast<long long>(1403636579758555392LL + 5000000LL * k),
                   y[0],
                   y[1],
                   y[2],
                   y[3],
                   y[4],
                   y[5]);
    }
    std::fclose(file);
  }
  ~EurocFile() { std::filesystem::remove(path_); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

const std::string& EurocPath() {
  static const EurocFile file;
  return file.path();
}

void BM_ReadEuroc10M(benchmark::State& state) {
  const std::string& path = EurocPath();
  for (auto _ : state) {
    const StaticRecording recording = ReadEurocStaticRecording(path);
    benchmark::DoNotOptimize(recording.axes.data());
  }
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(path)) / 1e6;
}
BENCHMARK(BM_ReadEuroc10M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

void BM_WholeRun10M(benchmark::State& state) {
  const std::string& path = EurocPath();
  for (auto _ : state) {
    const AllanResult result = ComputeAllan(ReadEurocStaticRecording(path));
    benchmark::DoNotOptimize(result.gyroscope_noise_density.value);
  }
}
BENCHMARK(BM_WholeRun10M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// Six axes of 10^7 samples in memory on the machine's threads (no parsing).
void BM_SixAxesInMemory10M(benchmark::State& state) {
  for (auto _ : state) {
    state.PauseTiming();
    StaticRecording recording;
    recording.rate_hz = kRateHz;
    for (int a = 0; a < 6; ++a) {
      AxisSeries axis;
      axis.sensor = a < 3 ? ImuSensor::kGyroscope : ImuSensor::kAccelerometer;
      axis.axis = a % 3;
      axis.samples = Samples();
      recording.axes.push_back(std::move(axis));
    }
    state.ResumeTiming();
    const AllanResult result = ComputeAllan(std::move(recording));
    benchmark::DoNotOptimize(result.gyroscope_noise_density.value);
  }
}
BENCHMARK(BM_SixAxesInMemory10M)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
