// A further IMU's residuals (estimation/detail/further_imu_cost.h): one Evaluate pass, residuals
// and every Jacobian, of every segment's cost as Ceres calls it, for each of Kalibr's models,
// analytic (NewFurtherImuCost) against its automatic-differentiation twin
// (tests/testing/autodiff_further_imu_cost.h: the cost before the analytic Jacobians), on
// bench/benchmark_control_poses.h's lively spline, 0.05 s knots (calibrate's default), 10 samples
// per segment (200 Hz), the bias spline's four points per segment (calibrate's default). The IMU
// is mounted away from the reference (turned, 11 cm away, 2 ms late) and its model away from
// nominal, as after the solver's first step. Reported per IMU sample (6 rows).
//
//   further_imu_bench
#include <benchmark/benchmark.h>
#include <ceres/cost_function.h>

#include <array>
#include <memory>
#include <random>
#include <vector>

#include "benchmark_control_poses.h"
#include "splinecal/estimation/detail/further_imu_cost.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/autodiff_further_imu_cost.h"

namespace splinecal {
namespace {

constexpr int kSamplesPerSegment = 10;
constexpr int kBiasBlocks = 4;

struct Problem {
  std::vector<std::array<double, 7>> poses;
  std::array<std::array<double, 3>, kBiasBlocks> gyro_bias;
  std::array<std::array<double, 3>, kBiasBlocks> accel_bias;
  std::array<double, 3> gravity = {0.0, 0.0, -9.81};
  std::array<double, 4> q_i_b = {0.0, 0.0, 0.0, 1.0};
  std::array<double, 3> r_b = {0.05, -0.10, 0.02};
  double time_offset_s = 0.002;
  ImuModelParameters model;
  struct Cost {
    std::unique_ptr<ceres::CostFunction> cost;
    std::vector<double*> blocks;
    std::vector<std::vector<double>> jacobians;
    std::vector<double*> jacobian_pointers;
    std::vector<double> residuals;
  };
  std::vector<Cost> costs;
  int samples = 0;
};

std::unique_ptr<Problem> MakeProblem(bool analytic, ImuModelKind kind) {
  auto p = std::make_unique<Problem>();
  std::mt19937 rng(11);
  for (const SE3d& pose : bench::BenchmarkControlPoses(&rng)) {
    p->poses.emplace_back();
    PoseToBlock(pose, p->poses.back().data());
  }
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int j = 0; j < kBiasBlocks; ++j) {
    for (int a = 0; a < 3; ++a) {
      p->gyro_bias[j][a] = 0.01 * normal(rng);
      p->accel_bias[j][a] = 0.1 * normal(rng);
    }
  }
  RotationToBlock(SO3d::Exp(Eigen::Vector3d(0.3, -0.5, 1.2)), p->q_i_b.data());
  p->model.m_a = {1.02, 0.01, 0.98, -0.012, 0.008, 1.01};
  p->model.m_g = {0.99, -0.01, 1.015, 0.007, -0.009, 1.02};
  for (int j = 0; j < 9; ++j) p->model.a[j] = 0.001 * (j - 4);
  p->model.phi_gyro_i = {0.002, -0.001, 0.003};
  p->model.ry_i = {0.001, 0.003, -0.002};
  p->model.rz_i = {-0.002, 0.001, 0.004};
  const double dt_s = 1e-9 * static_cast<double>(bench::kDtNs);
  for (int index = 1; index + 2 < bench::kNumControlPoses; ++index) {
    FurtherImuSegment segment;
    segment.segment_index = index;
    segment.dt_s = dt_s;
    segment.kind = kind;
    segment.sigma_gyro = 0.003;
    segment.sigma_accel = 0.03;
    segment.bias_blocks = kBiasBlocks;
    for (int k = 0; k < kSamplesPerSegment; ++k) {
      FurtherImuSample sample;
      sample.u0 = (k + 0.5) / kSamplesPerSegment;
      sample.bias_weights = {0.1, 0.4, 0.4, 0.1};
      for (int a = 0; a < 3; ++a) {
        sample.gyro[a] = normal(rng);
        sample.accel[a] = 10.0 * normal(rng);
      }
      segment.samples.push_back(sample);
    }
    Problem::Cost c;
    for (int k = 0; k < 4; ++k) c.blocks.push_back(p->poses[index - 1 + k].data());
    for (auto& b : p->gyro_bias) c.blocks.push_back(b.data());
    for (auto& b : p->accel_bias) c.blocks.push_back(b.data());
    c.blocks.insert(c.blocks.end(),
                    {p->gravity.data(), p->q_i_b.data(), p->r_b.data(), &p->time_offset_s});
    if (kind != ImuModelKind::kCalibrated) {
      c.blocks.insert(c.blocks.end(), {p->model.m_a.data(), p->model.m_g.data(),
                                       p->model.a.data(), p->model.phi_gyro_i.data()});
    }
    if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
      c.blocks.insert(c.blocks.end(), {p->model.ry_i.data(), p->model.rz_i.data()});
    }
    c.cost.reset(analytic ? NewFurtherImuCost(segment)
                          : testing::NewAutoDiffFurtherImuCost(segment));
    c.residuals.resize(c.cost->num_residuals());
    for (int size : c.cost->parameter_block_sizes()) {
      c.jacobians.emplace_back(static_cast<size_t>(size) * c.cost->num_residuals());
    }
    for (auto& j : c.jacobians) c.jacobian_pointers.push_back(j.data());
    p->costs.push_back(std::move(c));
    p->samples += kSamplesPerSegment;
  }
  return p;
}

void BM_FurtherImuEvaluate(benchmark::State& state, bool analytic, ImuModelKind kind) {
  const std::unique_ptr<Problem> p = MakeProblem(analytic, kind);
  for (auto _ : state) {
    for (Problem::Cost& c : p->costs) {
      c.cost->Evaluate(c.blocks.data(), c.residuals.data(), c.jacobian_pointers.data());
      benchmark::DoNotOptimize(c.residuals.data());
      benchmark::DoNotOptimize(c.jacobians.front().data());
    }
  }
  // items_per_second: IMU samples (gyro + accel rows) per second; 1e9 / it is ns per sample.
  state.SetItemsProcessed(state.iterations() * p->samples);
  state.counters["samples"] = p->samples;
}
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, calibrated, true, ImuModelKind::kCalibrated);
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, calibrated_autodiff, false, ImuModelKind::kCalibrated);
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, scale_misalignment, true,
                  ImuModelKind::kScaleMisalignment);
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, scale_misalignment_autodiff, false,
                  ImuModelKind::kScaleMisalignment);
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, scale_misalignment_size_effect, true,
                  ImuModelKind::kScaleMisalignmentSizeEffect);
BENCHMARK_CAPTURE(BM_FurtherImuEvaluate, scale_misalignment_size_effect_autodiff, false,
                  ImuModelKind::kScaleMisalignmentSizeEffect);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
