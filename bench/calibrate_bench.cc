// `splinecal calibrate` on simulated rolling-shutter sequences: the target is a 60 s
// calibration (20 Hz camera -> 1200 frames, an aprilgrid with ~100 visible corners, 200 Hz IMU
// with the ADIS16448 noise) in at most 30 s on 2 cores. Reports the wall time of the whole
// Calibrate call (initial guess, solver rounds, covariance) and its parts as counters, for
// sequence lengths 15, 30 and 60 s (docs/calibrate.md, "Speed"). The sequence is simulated
// once per length, outside the timed region.
//
//   calibrate_bench --benchmark_filter=Calibrate/60
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>

#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"

namespace splinecal {
namespace {

// The tests' scenario (tests/calib/calibrate_test_scenario.h) at the given length, simulated once
// per length outside the timed region.
const testing::CalibrationScenario& GetScenario(int seconds) {
  static std::map<int, std::unique_ptr<testing::CalibrationScenario>> cache;
  std::unique_ptr<testing::CalibrationScenario>& s = cache[seconds];
  if (!s) {
    testing::ScenarioOptions options;
    options.duration_s = seconds;
    s = std::make_unique<testing::CalibrationScenario>(testing::MakeCalibrationScenario(options));
  }
  return *s;
}

void BM_Calibrate(benchmark::State& state) {
  const testing::CalibrationScenario& s = GetScenario(static_cast<int>(state.range(0)));
  CalibrateOptions options;
  options.rolling_shutter = true;
  options.solver.num_threads = static_cast<int>(state.range(1));
  options.keep_residuals = false;
  CalibrationResult result;
  for (auto _ : state) {
    result = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  }
  state.counters["frames"] = s.camera_result.num_frames;
  state.counters["corners"] = s.camera_result.num_target_observations;
  state.counters["iterations"] = result.solve.iterations;
  state.counters["rounds"] = result.solve.rounds;
  state.counters["init_s"] = result.initialisation_time_s;
  state.counters["solve_s"] = result.solve.solve_time_s;
  state.counters["covariance_s"] = result.covariance_time_s;
  state.counters["rms_px"] = result.reprojection_rms_px;
  if (std::getenv("CALIBRATE_BENCH_REPORT") != nullptr)
    std::fprintf(stderr, "%s\n", result.solve.report.c_str());
}
BENCHMARK(BM_Calibrate)
    ->ArgNames({"seconds", "threads"})
    ->Args({15, 2})
    ->Args({30, 2})
    ->Args({60, 2})
    ->Args({60, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
