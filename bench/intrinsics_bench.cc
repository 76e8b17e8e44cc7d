// `splinecal intrinsics` on the real EuRoC calibration recording (the target: the
// two-camera intrinsics with every frame offered, the tool selecting, in under 20 s on 2
// cores): the whole CalibrateIntrinsics call (initialisation sweep, PnP, repeat removal, the
// robust and the final solve, covariance, observability), per camera model, reading the files
// outside the timed region. Needs ../shared/data/euroc_imu_april (SPLINECAL_SHARED_DATA_DIR).
//
//   intrinsics_bench --benchmark_filter=EurocTwoCameras
//   intrinsics_bench --benchmark_filter=free_target   (every target point free)
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"

namespace splinecal {
namespace {

void BM_EurocTwoCameras(benchmark::State& state, const std::string& model,
                        TargetDeformationKind target_deformation = TargetDeformationKind::kNone) {
  const std::string dir = std::string(SPLINECAL_SHARED_DATA_DIR) + "/euroc_imu_april/";
  const CalibrationTarget target = ReadTargetYaml(dir + "aprilgrid.yaml");
  const std::vector<Observation> observations = ReadObservationsCsv(dir + "observations.csv");
  IntrinsicsCameraSpec spec;
  if (!ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion)) {
    state.SkipWithError("unknown model");
    return;
  }
  spec.camera.width = 752;
  spec.camera.height = 480;
  IntrinsicsOptions options;
  options.solver.num_threads = static_cast<int>(state.range(0));
  options.target_deformation = target_deformation;
  IntrinsicsResult result;
  for (auto _ : state) {
    result = CalibrateIntrinsics(observations, target, {spec, spec}, options);
  }
  state.counters["views_used"] = result.cameras[0].views_used + result.cameras[1].views_used;
  state.counters["iterations"] = result.solve.iterations;
  state.counters["solve_s"] = result.solve.solve_time_s;
  state.counters["rms0_px"] = result.cameras[0].reprojection_rms_px;
}

BENCHMARK_CAPTURE(BM_EurocTwoCameras, pinhole_radtan, std::string("pinhole-radtan"))
    ->Arg(2)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_EurocTwoCameras, ds_none, std::string("ds-none"))
    ->Arg(2)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();
// Every target point free (target_deformation.h, "points"): 432 more unknowns, a residual block
// per corner, the covariance of every offset.
BENCHMARK_CAPTURE(BM_EurocTwoCameras, ds_none_free_target, std::string("ds-none"),
                  TargetDeformationKind::kPoints)
    ->Arg(2)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
