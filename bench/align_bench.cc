// Visual-inertial alignment speed (issue: a 10 s window, 100 camera frames, 200 Hz IMU aligns in
// at most 5 ms). Data: the figure-eight trajectory with IMU and camera noise
// (tests/calib/align_test_data.h).
#include <benchmark/benchmark.h>

#include "calib/align_test_data.h"
#include "splinecal/vio/align.h"
#include "splinecal/vio/preintegration.h"

namespace splinecal {
namespace {

const testing::Scenario& Window() {
  static const testing::Scenario scenario = [] {
    testing::ScenarioOptions options;
    options.T_cam_imu = testing::EurocCam0TCamImu();
    options.imu_noise = true;
    options.camera_translation_std_m = 0.005;
    options.camera_rotation_std_rad = 0.002;
    return testing::MakeScenario(Figure8Trajectory(), options);
  }();
  return scenario;
}

AlignOptions Options(bool estimate_rotation) {
  AlignOptions options;
  options.T_cam_imu = testing::EurocCam0TCamImu();
  options.estimate_rotation_extrinsic = estimate_rotation;
  return options;
}

// The whole pipeline: gyro bias, preintegration with covariance, linear solve, refinement.
void BM_Align(benchmark::State& state) {
  const testing::Scenario& s = Window();
  const AlignOptions options = Options(state.range(0) != 0);
  for (auto _ : state) {
    AlignResult result = Align(s.imu, s.camera_poses, options);
    if (!result.success) state.SkipWithError(result.message.c_str());
    benchmark::DoNotOptimize(result);
  }
  state.counters["frames"] = static_cast<double>(s.camera_poses.size());
  state.counters["imu_samples"] = static_cast<double>(s.imu.size());
}
BENCHMARK(BM_Align)->Arg(0)->Arg(1)->ArgName("estimate_rotation")->Unit(benchmark::kMillisecond);

// One frame interval (20 IMU steps) with bias Jacobians and covariance.
void BM_PreintegrateWithCovariance(benchmark::State& state) {
  const testing::Scenario& s = Window();
  const ImuNoise noise;
  const int64_t t0 = s.camera_poses[10].t_ns;
  const int64_t t1 = s.camera_poses[11].t_ns;
  for (auto _ : state) {
    ImuPreintegration pre =
        Preintegrate(s.imu, t0, t1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &noise);
    benchmark::DoNotOptimize(pre);
  }
}
BENCHMARK(BM_PreintegrateWithCovariance)->Unit(benchmark::kMicrosecond);

void BM_PreintegrateRotation(benchmark::State& state) {
  const testing::Scenario& s = Window();
  const int64_t t0 = s.camera_poses[10].t_ns;
  const int64_t t1 = s.camera_poses[11].t_ns;
  Eigen::Matrix3d J;
  for (auto _ : state) {
    SO3d dR = PreintegrateRotation(s.imu, t0, t1, Eigen::Vector3d::Zero(), &J);
    benchmark::DoNotOptimize(dR);
    benchmark::DoNotOptimize(J);
  }
}
BENCHMARK(BM_PreintegrateRotation)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
