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
#include <utility>
#include <vector>

#include "benchmark_control_poses.h"
#include "cost_evaluation_bench.h"
#include "splinecal/estimation/detail/further_imu_cost.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/lie/se3_manifold.h"
#include "testing/autodiff_further_imu_cost.h"

namespace splinecal {
namespace {

constexpr int kSamplesPerSegment = 10;
constexpr int kBiasBlocks = 4;

struct Problem {
  explicit Problem(std::mt19937* rng) : spline(rng) {}
  bench::ImuSplineBlocks<kBiasBlocks> spline;
  std::array<double, 3> gravity = {0.0, 0.0, -9.81};
  std::array<double, 4> q_i_b = {0.0, 0.0, 0.0, 1.0};
  std::array<double, 3> r_b = {0.05, -0.10, 0.02};
  double time_offset_s = 0.002;
  ImuModelParameters model;
  std::vector<bench::EvaluatedCost> costs;
  int samples = 0;
};

std::unique_ptr<Problem> MakeProblem(bool analytic, ImuModelKind kind) {
  std::mt19937 rng(11);
  auto p = std::make_unique<Problem>(&rng);
  std::normal_distribution<double> normal(0.0, 1.0);
  RotationToBlock(SO3d::Exp(Eigen::Vector3d(0.3, -0.5, 1.2)), p->q_i_b.data());
  bench::SetModelAwayFromNominal(&p->model);
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
    std::vector<double*> blocks;
    for (int k = 0; k < 4; ++k) blocks.push_back(p->spline.poses[index - 1 + k].data());
    for (auto& b : p->spline.gyro_bias) blocks.push_back(b.data());
    for (auto& b : p->spline.accel_bias) blocks.push_back(b.data());
    blocks.insert(blocks.end(),
                  {p->gravity.data(), p->q_i_b.data(), p->r_b.data(), &p->time_offset_s});
    if (kind != ImuModelKind::kCalibrated) {
      blocks.insert(blocks.end(), {p->model.m_a.data(), p->model.m_g.data(), p->model.a.data(),
                                   p->model.phi_gyro_i.data()});
    }
    if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
      blocks.insert(blocks.end(), {p->model.ry_i.data(), p->model.rz_i.data()});
    }
    p->costs.push_back(bench::MakeEvaluatedCost(
        analytic ? NewFurtherImuCost(segment) : testing::NewAutoDiffFurtherImuCost(segment),
        std::move(blocks)));
    p->samples += kSamplesPerSegment;
  }
  return p;
}

void BM_FurtherImuEvaluate(benchmark::State& state, bool analytic, ImuModelKind kind) {
  const std::unique_ptr<Problem> p = MakeProblem(analytic, kind);
  bench::EvaluateEveryCost(state, p->costs, p->samples);
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
