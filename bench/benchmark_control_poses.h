// The spline the spline benchmarks share (bench/spline_bench.cc,
// bench/spline_vs_reference_bench.cc): 200 control poses 0.05 s apart, each a step of 0.1-1 rad
// about a random axis and up to 0.5 m per axis from the one before, and 1024 query times drawn over
// the valid range by the caller.
#ifndef SPLINECAL_BENCH_BENCHMARK_CONTROL_POSES_H_
#define SPLINECAL_BENCH_BENCHMARK_CONTROL_POSES_H_

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/types.h"

namespace splinecal {
namespace bench {

constexpr int kNumControlPoses = 200;
constexpr int kNumSamples = 1024;  // distinct sample times, cycled (a power of two)
constexpr int64_t kT0Ns = 1403715273262142976;
constexpr int64_t kDtNs = 50000000;  // 0.05 s

// A twist with a rotation of 0.1 .. max_angle rad about a random axis and a translation of up to
// max_translation per axis.
inline Vector6d RandomTwist(std::mt19937* rng, double max_angle, double max_translation) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> angle(0.1, max_angle);
  std::uniform_real_distribution<double> offset(-max_translation, max_translation);
  Vector6d xi;
  xi.head<3>() = Eigen::Vector3d(offset(*rng), offset(*rng), offset(*rng));
  xi.tail<3>() =
      angle(*rng) * Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)).normalized();
  return xi;
}

// The control poses, drawn from `rng` (which the caller goes on using for the query times).
inline std::vector<SE3d> BenchmarkControlPoses(std::mt19937* rng) {
  std::vector<SE3d> poses{SE3d::Exp(RandomTwist(rng, 2.0, 3.0))};
  for (int i = 1; i < kNumControlPoses; ++i) {
    poses.push_back(poses.back() * SE3d::Exp(RandomTwist(rng, 1.0, 0.5)));
  }
  return poses;
}

}  // namespace bench
}  // namespace splinecal

#endif  // SPLINECAL_BENCH_BENCHMARK_CONTROL_POSES_H_
