// `splinecal fit` speed (docs/performance.md):
//
//   Reference problem: 1000 control poses at 0.1 s (99.7 s), 200 Hz IMU with ADIS16448 white
//   noise and constant biases, poses at 1 Hz, initial guess = truth perturbed by 0.05 (every
//   control pose by Exp(d), d ~ N(0, 0.05^2) in metres and radians; gravity 0.05 rad off; biases
//   zero), SPARSE_NORMAL_CHOLESKY, 1 thread. Timed: FitProblem::Solve() without the covariance
//   (what Ceres' "Total" measures), wall and process CPU time. Target: <= 0.5 s, and >= 10x
//   faster than our autodiff path (BM_FitReference/autodiff) to the same final cost.
//
//   Scale: 1, 10 and 60 minutes of 200 Hz IMU with 20 Hz poses (noise, 0.1 s knots), the whole
//   Fit() (initialisation, solve, covariance; per-sample outputs not kept) with 2 threads and the
//   default options (LinearSolver::kAuto: SPARSE_SCHUR above ~11 minutes).
//   Target for 60 min: <= 60 s and <= 2 GB peak (counter peak_rss_mb: the process's peak so far,
//   so run the sizes in increasing order, as registered, or one per process with
//   --benchmark_filter).
//
//   build-*/bench/fit_bench --benchmark_filter=Reference
//   build-*/bench/fit_bench --benchmark_filter=Scale/60
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <ctime>
#include <memory>
#include <random>
#include <vector>

#include "splinecal/calib/fit.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "testing/autodiff_costs.h"

namespace splinecal {
namespace {

constexpr int64_t kStartNs = 1'403'715'273'262'142'976;
constexpr int64_t kKnotNs = 100'000'000;

struct Dataset {
  SE3Splined truth = SE3Splined(std::vector<SE3d>(4), 0, 1);
  std::vector<ImuSample> imu;
  std::vector<StampedPose> poses;
  Eigen::Vector3d gyro_bias{0.012, -0.021, 0.006};
  Eigen::Vector3d accel_bias{0.05, 0.11, -0.08};
};

// duration_ns of motion, 200 Hz noisy IMU, poses every pose_step_ns (plus the last instant, so
// that the pose data covers the whole spline), from the "random" trajectory.
Dataset MakeDataset(int64_t duration_ns, int64_t pose_step_ns) {
  Dataset data;
  data.truth = FitAnalyticTrajectory(MakeTrajectory("random", 3),
                                     kStartNs,
                                     kStartNs + duration_ns,
                                     kKnotNs,
                                     /*pose_step_ns=*/kKnotNs / 2)
                   .MakeSpline();
  SimulationOptions simulation;
  simulation.noise.gyroscope_random_walk = 0.0;
  simulation.noise.accelerometer_random_walk = 0.0;
  simulation.gyro_bias = data.gyro_bias;
  simulation.accel_bias = data.accel_bias;
  simulation.seed = 5;
  SimulateImu(data.truth,
              data.truth.start_time_ns(),
              data.truth.end_time_ns(),
              simulation,
              &data.imu,
              nullptr);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 1e-3);
  auto add_pose = [&](int64_t t) {
    const SE3d T = data.truth.PoseNs(t);
    StampedPose pose;
    pose.t_ns = t;
    pose.p = T.translation() + Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    pose.q =
        (T.so3() * SO3d::Exp(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)))).quaternion();
    data.poses.push_back(pose);
  };
  int64_t t = data.truth.start_time_ns();
  for (; t <= data.truth.end_time_ns(); t += pose_step_ns) add_pose(t);
  if (data.poses.back().t_ns != data.truth.end_time_ns()) add_pose(data.truth.end_time_ns());
  return data;
}

const Dataset& ReferenceData() {
  // 997 knot intervals: 1000 control poses.
  static const Dataset data = MakeDataset(997 * kKnotNs, 1'000'000'000);
  return data;
}

double PeakRssMb() {
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}

enum class Path { kAnalytic, kAnalyticPerSample, kAnalyticUnshared, kAnalyticSchur, kAutoDiff };

void BM_FitReference(benchmark::State& state, Path path) {
  const Dataset& data = ReferenceData();
  FitOptions options;
  options.model.knot_spacing_s = 0.1;
  options.solver.num_threads = 1;
  options.covariance.compute = false;
  options.keep_samples = false;
  // Ceres' default stopping rules, as in the reference measurements.
  options.solver.function_tolerance = 1e-6;
  options.solver.gradient_tolerance = 1e-10;
  options.solver.parameter_tolerance = 1e-8;
  options.solver.linear_solver = path == Path::kAnalyticSchur ? LinearSolver::kSparseSchur
                                                       : LinearSolver::kSparseNormalCholesky;
  options.residuals.layout = path == Path::kAnalyticPerSample ? ImuResidualLayout::kPerSample
                                                    : ImuResidualLayout::kPerSegment;
  options.residuals.share_knot_caches = path != Path::kAnalyticUnshared;
  if (path == Path::kAutoDiff) options.residuals.replacement = testing::AutoDiffReplacementCosts();
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 0.05);
  std::vector<SE3d> initial = data.truth.control_poses();
  for (SE3d& T : initial) {
    Vector6d d;
    for (int k = 0; k < 6; ++k) d[k] = normal(rng);
    T = T * SE3d::Exp(d);
  }
  double cpu_s = 0.0;
  double wall_s = 0.0;
  FitResult result;
  for (auto _ : state) {
    state.PauseTiming();
    auto problem = std::make_unique<FitProblem>(data.imu, data.poses, options);
    problem->SetControlPoses(initial);
    problem->SetBiases(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
    problem->SetGravity(SO3d::Exp(Eigen::Vector3d(0.05, 0.0, 0.0)) * GravityWorld());
    state.ResumeTiming();
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    result = problem->Solve();
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    cpu_s += static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    state.PauseTiming();
    problem.reset();
    state.ResumeTiming();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["iterations"] = result.solve.iterations;
  state.counters["final_cost"] = result.solve.final_cost;
  state.counters["solve_wall_s"] = wall_s / n;
  state.counters["solve_cpu_s"] = cpu_s / n;
  state.counters["control_poses"] = result.layout.num_control_poses;
  state.counters["imu_samples"] = result.num_imu_samples;
}
BENCHMARK_CAPTURE(BM_FitReference, analytic, Path::kAnalytic)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(5);
BENCHMARK_CAPTURE(BM_FitReference, analytic_per_sample_blocks, Path::kAnalyticPerSample)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_FitReference, analytic_unshared_knots, Path::kAnalyticUnshared)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_FitReference, analytic_sparse_schur, Path::kAnalyticSchur)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);
BENCHMARK_CAPTURE(BM_FitReference, autodiff, Path::kAutoDiff)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void BM_FitScale(benchmark::State& state) {
  const int64_t minutes = state.range(0);
  const Dataset data = MakeDataset(minutes * 60 * 1'000'000'000LL, 50'000'000);  // 20 Hz poses
  FitOptions options;
  options.model.knot_spacing_s = 0.1;
  options.solver.num_threads = 2;
  options.keep_samples = false;
  FitResult result;
  double wall_s = 0.0;
  for (auto _ : state) {
    const auto wall_start = std::chrono::steady_clock::now();
    result = Fit(data.imu, data.poses, options);
    wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["fit_wall_s"] = wall_s / n;
  state.counters["solve_s"] = result.solve.solve_time_s;
  state.counters["covariance_s"] = result.covariance_time_s;
  state.counters["iterations"] = result.solve.iterations;
  state.counters["imu_samples"] = result.num_imu_samples;
  state.counters["peak_rss_mb"] = PeakRssMb();
  state.SetLabel(result.solve.linear_solver + ", covariance: " + result.covariance_method);
  state.counters["gyro_bias_err"] = (result.gyro_bias - data.gyro_bias).norm();
  state.counters["accel_bias_err"] = (result.accel_bias - data.accel_bias).norm();
}
BENCHMARK(BM_FitScale)->Arg(1)->Arg(10)->Arg(60)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
