// Kalibr's IMU models in `calibrate --imu-model`: one Evaluate pass, residuals and every
// Jacobian, of the gyro and accelerometer costs of a spline segment, as Ceres calls them, for
//   calibrated                       GyroSegmentCostFunction<4> + AccelSegmentCostFunction<4>
//                                    (estimation/detail/imu_costs.h: what `calibrated` runs)
//   scale_misalignment[_size_effect] NewImuModelGyroCost + NewImuModelAccelCost, analytic
//                                    (estimation/detail/imu_model_costs.h)
//   *_autodiff                       their automatic-differentiation twins
//                                    (tests/testing/autodiff_imu_model_costs.h: the costs before
//                                    the analytic Jacobians)
// on bench/benchmark_control_poses.h's lively spline, 0.05 s knots (calibrate's default) and 10
// samples per segment (200 Hz), the bias spline's four points per segment (calibrate's default),
// every segment of the spline once per iteration. The model parameters are away from nominal
// (A != 0 and lever arms != 0, as after the solver's first step: at nominal some Jacobian terms
// are exactly zero and skipped). Reported per IMU sample (gyro + accel rows).
//
//   imu_model_bench
#include <benchmark/benchmark.h>
#include <ceres/cost_function.h>

#include <array>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "benchmark_control_poses.h"
#include "cost_evaluation_bench.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/detail/imu_model_costs.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/autodiff_imu_model_costs.h"

namespace splinecal {
namespace {

constexpr int kSamplesPerSegment = 10;
constexpr int kBiasBlocks = 4;

enum class Path { kCalibrated, kAnalytic, kAutoDiff };

// Both costs of every segment with their parameter blocks.
struct Problem {
  explicit Problem(std::mt19937* rng) : spline(rng) {}
  bench::ImuSplineBlocks<kBiasBlocks> spline;
  std::array<double, 3> gravity = {0.0, 0.0, -9.81};
  ImuModelParameters model;
  std::vector<bench::EvaluatedCost> costs;
  int samples = 0;
};

void AddCost(ceres::CostFunction* cost, std::vector<double*> blocks, Problem* p) {
  p->costs.push_back(bench::MakeEvaluatedCost(cost, std::move(blocks)));
}

std::unique_ptr<Problem> MakeProblem(Path path, ImuModelKind kind) {
  std::mt19937 rng(11);
  auto p = std::make_unique<Problem>(&rng);
  std::normal_distribution<double> normal(0.0, 1.0);
  bench::SetModelAwayFromNominal(&p->model);
  const double dt_s = 1e-9 * static_cast<double>(bench::kDtNs);
  for (int index = 1; index + 2 < bench::kNumControlPoses; ++index) {
    ImuModelSegment gyro;
    gyro.kind = kind;
    gyro.bias_blocks = kBiasBlocks;
    gyro.segment.segment_index = index;
    gyro.segment.dt_s = dt_s;
    gyro.segment.sigma = 0.003;
    for (int k = 0; k < kSamplesPerSegment; ++k) {
      ImuResidualSample sample;
      sample.u = (k + 0.5) / kSamplesPerSegment;
      sample.bias_weights = {0.1, 0.4, 0.4, 0.1};
      for (int a = 0; a < 3; ++a) sample.measured[a] = normal(rng);
      gyro.samples.push_back(sample);
    }
    ImuModelSegment accel = gyro;
    accel.segment.sigma = 0.03;
    std::vector<double*> common;
    for (int k = 0; k < 4; ++k) common.push_back(p->spline.poses[index - 1 + k].data());
    std::vector<double*> gyro_blocks = common;
    std::vector<double*> accel_blocks = common;
    for (int j = 0; j < kBiasBlocks; ++j) {
      gyro_blocks.push_back(p->spline.gyro_bias[j].data());
      accel_blocks.push_back(p->spline.accel_bias[j].data());
    }
    accel_blocks.push_back(p->gravity.data());
    p->samples += kSamplesPerSegment;
    if (path == Path::kCalibrated) {
      AddCost(new GyroSegmentCostFunction<kBiasBlocks>(gyro.segment, gyro.samples),
              gyro_blocks,
              p.get());
      AddCost(new AccelSegmentCostFunction<kBiasBlocks>(accel.segment, accel.samples),
              accel_blocks,
              p.get());
      continue;
    }
    gyro_blocks.insert(
        gyro_blocks.end(),
        {p->gravity.data(), p->model.m_g.data(), p->model.a.data(), p->model.phi_gyro_i.data()});
    accel_blocks.push_back(p->model.m_a.data());
    if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
      accel_blocks.insert(accel_blocks.end(), {p->model.ry_i.data(), p->model.rz_i.data()});
    }
    const bool analytic = path == Path::kAnalytic;
    AddCost(analytic ? NewImuModelGyroCost(gyro) : testing::NewAutoDiffImuModelGyroCost(gyro),
            gyro_blocks,
            p.get());
    AddCost(analytic ? NewImuModelAccelCost(accel) : testing::NewAutoDiffImuModelAccelCost(accel),
            accel_blocks,
            p.get());
  }
  return p;
}

void BM_ImuModelEvaluate(benchmark::State& state, Path path, ImuModelKind kind) {
  const std::unique_ptr<Problem> p = MakeProblem(path, kind);
  bench::EvaluateEveryCost(state, p->costs, p->samples);
}
BENCHMARK_CAPTURE(BM_ImuModelEvaluate, calibrated, Path::kCalibrated, ImuModelKind::kCalibrated);
BENCHMARK_CAPTURE(BM_ImuModelEvaluate,
                  scale_misalignment,
                  Path::kAnalytic,
                  ImuModelKind::kScaleMisalignment);
BENCHMARK_CAPTURE(BM_ImuModelEvaluate,
                  scale_misalignment_size_effect,
                  Path::kAnalytic,
                  ImuModelKind::kScaleMisalignmentSizeEffect);
BENCHMARK_CAPTURE(BM_ImuModelEvaluate,
                  scale_misalignment_autodiff,
                  Path::kAutoDiff,
                  ImuModelKind::kScaleMisalignment);
BENCHMARK_CAPTURE(BM_ImuModelEvaluate,
                  scale_misalignment_size_effect_autodiff,
                  Path::kAutoDiff,
                  ImuModelKind::kScaleMisalignmentSizeEffect);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
