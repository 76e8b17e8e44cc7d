// `splinecal calibrate` on simulated rolling-shutter sequences: the target (docs/performance.md,
// "Camera-IMU calibration") is a 60 s calibration (20 Hz camera -> 1200 frames, an aprilgrid with
// ~100 visible corners, 200 Hz IMU with the ADIS16448 noise) in at most 30 s on 2 cores. Reports
// the wall time of the whole Calibrate call (initial guess, solver rounds, covariance) and its
// parts as counters, for sequence lengths 15, 30 and 60 s (docs/calibrate.md, "Speed"). The
// sequence is simulated once per length, outside the timed region.
//
//   calibrate_bench --benchmark_filter=Calibrate/60
//
// BM_CalibrateEuroc: the real EuRoC calibration recording (../shared/data/euroc_imu_april,
// SPLINECAL_SHARED_DATA_DIR; 72 s, cam0: 1416 frames, 179k target corners, 200 Hz IMU) with
// `splinecal calibrate --cameras 0 --threads 2`'s options, at knot spacings of 0.05, 0.02 and
// 0.01 s (Kalibr's density; the target: 0.01 s in at most 20 s on 2 cores). Files are read
// once, outside the timed region. peak_rss_MB is the process's peak so far (getrusage).
//
//   calibrate_bench --benchmark_filter=CalibrateEuroc
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/memory_reuse.h"

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

// The solve's iterations and rounds, its parts' wall times and the reprojection RMS.
void SetResultCounters(const CalibrationResult& result, benchmark::State* state) {
  state->counters["iterations"] = result.solve.iterations;
  state->counters["rounds"] = result.solve.rounds;
  state->counters["init_s"] = result.initialisation_time_s;
  state->counters["solve_s"] = result.solve.solve_time_s;
  state->counters["covariance_s"] = result.covariance_time_s;
  state->counters["rms_px"] = result.reprojection_rms_px;
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
  SetResultCounters(result, &state);
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

struct EurocRecording {
  std::vector<ImuSample> imu;
  std::vector<Observation> observations;  // cam0's only
  Camchain camchain;                      // cam0 only
  CalibrationTarget target;
};

const EurocRecording& GetEurocRecording() {
  static const EurocRecording* recording = [] {
    const std::string dir = std::string(SPLINECAL_SHARED_DATA_DIR) + "/euroc_imu_april/";
    auto* r = new EurocRecording;
    r->imu = ReadEurocImu(dir + "imu0.csv");
    for (const Observation& o : ReadObservationsCsv(dir + "observations.csv")) {
      if (o.cam_id == 0) r->observations.push_back(o);
    }
    r->camchain = {ReadCamchainYaml(dir + "camchain_euroc.yaml").front()};
    r->target = ReadTargetYaml(dir + "aprilgrid.yaml");
    return r;
  }();
  return *recording;
}

void BM_CalibrateEuroc(benchmark::State& state) {
  const std::string dir = std::string(SPLINECAL_SHARED_DATA_DIR) + "/euroc_imu_april";
  if (!std::filesystem::exists(dir)) {
    state.SkipWithError(("shared data absent: " + dir).c_str());
    return;
  }
  const EurocRecording& r = GetEurocRecording();
  CalibrateOptions options;  // the command's defaults (cli/calibrate_command.cc)
  options.model.knot_spacing_s = 1e-3 * static_cast<double>(state.range(0));
  options.solver.num_threads = 2;
  CalibrationResult result;
  for (auto _ : state) {
    result = Calibrate(r.imu, r.observations, r.camchain, &r.target, options);
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
  SetResultCounters(result, &state);
}
BENCHMARK(BM_CalibrateEuroc)
    ->ArgNames({"knot_ms"})
    ->Arg(50)
    ->Arg(20)
    ->Arg(10)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace splinecal

// The tool's allocator setting (splinecal/memory_reuse.h), so that the library call is measured
// as the command runs it.
int main(int argc, char** argv) {
  splinecal::KeepFreedMemoryForReuse();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
