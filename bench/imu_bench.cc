// IMU simulation and integration throughput (targets: simulation >= 3 million IMU
// samples/s including noise, without file writing; integration >= 10 million samples/s).
//
//   build-*/bench/imu_bench            items_per_second = IMU samples per second
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "splinecal/imu/integrate.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"

namespace splinecal {
namespace {

const Eigen::Vector3d kGravityW(0.0, 0.0, -9.81);

// 100 s of noise-free 200 Hz readings of the course trajectory (closed forms).
const std::vector<ImuSample>& CourseImu() {
  static const std::vector<ImuSample> imu = [] {
    const AnalyticTrajectory trajectory = VioCourseTrajectory();
    std::vector<ImuSample> samples;
    for (int64_t k = 0; k <= 20000; ++k) {
      const TrajectoryState state = trajectory.Evaluate(k * 0.005);
      ImuSample sample;
      sample.t_ns = k * 5'000'000;
      sample.gyro = state.w_s;
      sample.accel = state.T_w_s.so3().inverse() * (state.a_w - kGravityW);
      samples.push_back(sample);
    }
    return samples;
  }();
  return imu;
}

void BM_Integrate(benchmark::State& state, IntegrationMethod method, bool keep_trajectory) {
  const std::vector<ImuSample>& imu = CourseImu();
  NavState start;
  start.t_ns = imu.front().t_ns;
  std::vector<NavState> trajectory;
  for (auto _ : state) {
    trajectory.clear();
    const NavState end = IntegrateImu(imu,
                                      start,
                                      imu.back().t_ns,
                                      ImuBias(),
                                      kGravityW,
                                      method,
                                      keep_trajectory ? &trajectory : nullptr);
    benchmark::DoNotOptimize(end.p_w_s.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(imu.size() - 1));
}
BENCHMARK_CAPTURE(BM_Integrate, euler, IntegrationMethod::kEuler, false);
BENCHMARK_CAPTURE(BM_Integrate, midpoint, IntegrationMethod::kMidpoint, false);
BENCHMARK_CAPTURE(BM_Integrate, rk4, IntegrationMethod::kRk4, false);
BENCHMARK_CAPTURE(BM_Integrate, euler_with_trajectory, IntegrationMethod::kEuler, true);
BENCHMARK_CAPTURE(BM_Integrate, rk4_with_trajectory, IntegrationMethod::kRk4, true);

// The noise alone: white noise and bias random walk on both sensors (12 normal draws/sample).
void BM_NoiseGenerator(benchmark::State& state) {
  ImuNoiseGenerator generator(ImuNoise(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 1);
  ImuSample sample;
  Eigen::Vector3d gyro_bias, accel_bias;
  for (auto _ : state) {
    generator.Corrupt(&sample, &gyro_bias, &accel_bias);
    benchmark::DoNotOptimize(sample.gyro.data());
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_NoiseGenerator);

// The course spline for 20 s (knots every 50 ms), fitted once.
const SE3Splined& CourseSpline() {
  static const SE3Splined spline =
      FitAnalyticTrajectory(VioCourseTrajectory(), 50'000'000, 20'050'000'000, 50'000'000)
          .MakeSpline();
  return spline;
}

// Simulation throughput: spline evaluation, IMU model, noise (white + random walk), ground truth
// rows; no file writing. 4001 samples per iteration (20 s at 200 Hz).
void BM_Simulate(benchmark::State& state, bool noise_free, bool with_ground_truth) {
  const SE3Splined& spline = CourseSpline();
  SimulationOptions options;
  options.noise_free = noise_free;
  options.seed = 1;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
  for (auto _ : state) {
    SimulateImu(spline,
                spline.start_time_ns(),
                spline.start_time_ns() + 20'000'000'000,
                options,
                &imu,
                with_ground_truth ? &truth : nullptr);
    benchmark::DoNotOptimize(imu.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(imu.size()));
}
BENCHMARK_CAPTURE(BM_Simulate, noisy_with_ground_truth, false, true);
BENCHMARK_CAPTURE(BM_Simulate, noisy_imu_only, false, false);
BENCHMARK_CAPTURE(BM_Simulate, noise_free_with_ground_truth, true, true);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
