// What the IMU cost benchmarks share (bench/imu_model_bench.cc, bench/further_imu_bench.cc): the
// spline's control poses and bias points as parameter blocks, the model parameters away from
// nominal, and one Evaluate pass of every cost, residuals and every Jacobian, as Ceres calls it.
#ifndef SPLINECAL_BENCH_COST_EVALUATION_BENCH_H_
#define SPLINECAL_BENCH_COST_EVALUATION_BENCH_H_

#include <benchmark/benchmark.h>
#include <ceres/cost_function.h>

#include <array>
#include <cstddef>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "benchmark_control_poses.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace bench {

// One cost with its parameter blocks and the buffers Evaluate writes.
struct EvaluatedCost {
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<double*> blocks;
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> jacobian_pointers;
  std::vector<double> residuals;
};

// Takes ownership of `cost` and sizes the residual and Jacobian buffers from it.
inline EvaluatedCost MakeEvaluatedCost(ceres::CostFunction* cost, std::vector<double*> blocks) {
  EvaluatedCost c;
  c.cost.reset(cost);
  c.blocks = std::move(blocks);
  c.residuals.resize(cost->num_residuals());
  for (int size : cost->parameter_block_sizes()) {
    c.jacobians.emplace_back(static_cast<size_t>(size) * cost->num_residuals());
  }
  for (auto& j : c.jacobians) c.jacobian_pointers.push_back(j.data());
  return c;
}

// Every cost evaluated once per iteration. items_per_second counts IMU samples (gyro + accel
// rows), so 1e9 / items_per_second is ns per sample.
inline void EvaluateEveryCost(benchmark::State& state,
                              std::vector<EvaluatedCost>& costs,
                              int samples) {
  for (auto _ : state) {
    for (EvaluatedCost& c : costs) {
      c.cost->Evaluate(c.blocks.data(), c.residuals.data(), c.jacobian_pointers.data());
      benchmark::DoNotOptimize(c.residuals.data());
      benchmark::DoNotOptimize(c.jacobians.front().data());
    }
  }
  state.SetItemsProcessed(state.iterations() * samples);
  state.counters["samples"] = samples;
}

// BenchmarkControlPoses' spline as pose blocks, and a bias spline's points for the gyro and the
// accelerometer (0.01 rad/s and 0.1 m/s^2 per axis), drawn from `rng` in that order.
template <int kBiasBlocks>
struct ImuSplineBlocks {
  explicit ImuSplineBlocks(std::mt19937* rng) {
    for (const SE3d& pose : BenchmarkControlPoses(rng)) {
      poses.emplace_back();
      PoseToBlock(pose, poses.back().data());
    }
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int j = 0; j < kBiasBlocks; ++j) {
      for (int a = 0; a < 3; ++a) {
        gyro_bias[j][a] = 0.01 * normal(*rng);
        accel_bias[j][a] = 0.1 * normal(*rng);
      }
    }
  }

  std::vector<std::array<double, 7>> poses;
  std::array<std::array<double, 3>, kBiasBlocks> gyro_bias;
  std::array<std::array<double, 3>, kBiasBlocks> accel_bias;
};

// Every model parameter away from nominal, as after the solver's first step: at nominal some
// Jacobian terms are exactly zero and skipped.
inline void SetModelAwayFromNominal(ImuModelParameters* model) {
  model->m_a = {1.02, 0.01, 0.98, -0.012, 0.008, 1.01};
  model->m_g = {0.99, -0.01, 1.015, 0.007, -0.009, 1.02};
  for (int j = 0; j < 9; ++j) model->a[j] = 0.001 * (j - 4);
  model->phi_gyro_i = {0.002, -0.001, 0.003};
  model->ry_i = {0.001, 0.003, -0.002};
  model->rz_i = {-0.002, 0.001, 0.004};
}

}  // namespace bench
}  // namespace splinecal

#endif  // SPLINECAL_BENCH_COST_EVALUATION_BENCH_H_
