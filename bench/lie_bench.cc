// Google Benchmark of the Lie-group layer (lie/so3.h, lie/se3.h), double precision.
//
//   cmake --build build --target lie_bench && ./build/bench/lie_bench
//
// Inputs cycle through a fixed, seeded set of generic arguments (angles uniform in [0, pi),
// translations ~ N(0, 3^2)) so that branch prediction sees realistic data; the small-angle
// series branches are measured separately (the *Small variants, |phi| = 1e-4 rad).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

constexpr int kNumInputs = 1024;  // Power of two: the index wraps with a mask.

std::vector<Vector6d> MakeTwists(double max_angle) {
  std::mt19937 rng(42);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(0.0, max_angle);
  std::vector<Vector6d> out;
  for (int i = 0; i < kNumInputs; ++i) {
    const Eigen::Vector3d axis =
        Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    Vector6d xi;
    xi << 3.0 * normal(rng), 3.0 * normal(rng), 3.0 * normal(rng), uniform(rng) * axis;
    out.push_back(xi);
  }
  return out;
}

const std::vector<Vector6d>& GenericTwists() {
  static const std::vector<Vector6d> twists = MakeTwists(kPi);
  return twists;
}

const std::vector<Vector6d>& SmallTwists() {
  static const std::vector<Vector6d> twists = [] {
    std::vector<Vector6d> out = MakeTwists(1.0);
    for (Vector6d& xi : out) xi.tail<3>() = 1e-4 * xi.tail<3>().normalized();
    return out;
  }();
  return twists;
}

void BM_SO3Exp(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  int i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d phi = (*inputs)[i++ & (kNumInputs - 1)].tail<3>();
    benchmark::DoNotOptimize(SO3d::Exp(phi));
  }
}

void BM_SO3Log(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  std::vector<SO3d> rotations;
  for (const Vector6d& xi : *inputs) rotations.push_back(SO3d::Exp(Eigen::Vector3d(xi.tail<3>())));
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(rotations[i++ & (kNumInputs - 1)].Log());
  }
}

void BM_SE3Exp(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(SE3d::Exp((*inputs)[i++ & (kNumInputs - 1)]));
  }
}

void BM_SE3Log(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  std::vector<SE3d> poses;
  for (const Vector6d& xi : *inputs) poses.push_back(SE3d::Exp(xi));
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(poses[i++ & (kNumInputs - 1)].Log());
  }
}

void BM_RightJacobianSO3(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  int i = 0;
  for (auto _ : state) {
    const Eigen::Vector3d phi = (*inputs)[i++ & (kNumInputs - 1)].tail<3>();
    benchmark::DoNotOptimize(RightJacobianSO3(phi));
  }
}

void BM_RightJacobianSE3(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(RightJacobianSE3((*inputs)[i++ & (kNumInputs - 1)]));
  }
}

void BM_RightJacobianInverseSE3(benchmark::State& state, const std::vector<Vector6d>* inputs) {
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(RightJacobianInverseSE3((*inputs)[i++ & (kNumInputs - 1)]));
  }
}

BENCHMARK_CAPTURE(BM_SO3Exp, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_SO3Exp, Small, &SmallTwists());
BENCHMARK_CAPTURE(BM_SO3Log, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_SO3Log, Small, &SmallTwists());
BENCHMARK_CAPTURE(BM_SE3Exp, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_SE3Log, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_RightJacobianSO3, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_RightJacobianSE3, Generic, &GenericTwists());
BENCHMARK_CAPTURE(BM_RightJacobianSE3, Small, &SmallTwists());
BENCHMARK_CAPTURE(BM_RightJacobianInverseSE3, Generic, &GenericTwists());

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
