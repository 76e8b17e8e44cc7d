// splinecal's two trajectory models -- the coupled SE(3) spline and the split SO(3) x R^3 spline
// (spline/trajectory_model.h) -- side by side with a reference split spline (the trajectory model
// of basalt-headers' Se3Spline, tests/spline/reference_split_spline.h) on the same control poses
// and the same query times (docs/performance.md). Run with interleaved repetitions so that every
// side sees the same machine state:
//
//   build-bench/bench/spline_vs_reference_bench --benchmark_repetitions=10
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
//       --benchmark_min_time=0.3
//
// Four operations, each for five implementations:
//   Splinecal           SE3Spline<double>, coupled SE(3) model, with its per-knot caches (what
//                       fit/calibrate use by default)
//   SplinecalSplit      the split SO(3) x R^3 model on the same per-knot caches, through the
//                       model dispatch fit/calibrate use with --trajectory split
//   SplinecalPerQuery   the coupled model with the knot deltas (Log + Jacobian caches) rebuilt
//                       from the four control poses in every call (SegmentKnotData)
//   ReferencePerQuery   the split spline computing its three Logs in every call, as
//                       basalt-headers does
//   ReferenceCached     the split spline with its knot deltas cached per knot
// Operations:
//   Pose            T_w_s(t)
//   ImuPrediction   gyro and accelerometer readings (w_s + b_g, R^T (a_w - g_w) + b_a)
//   GyroResidual    w_s + b_g - measured, with Jacobians w.r.t. 4 control poses and the bias
//   AccelResidual   R^T (a_w - g_w) + b_a - measured, with Jacobians w.r.t. 4 control poses, the
//                   bias and g_w
// Jacobians are in each implementation's own tangent (splinecal, both models: T Exp([rho; phi]);
// reference: p + dp, R Exp(dphi)), 3x6 per control pose, without the lift to Ceres' 7-parameter
// blocks. splinecal's split model pays for that tangent: its position columns are
// Bddot_k R_w_s^T R_k (three more 3x3 products) where the reference's are Bddot_k R_w_s^T.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "benchmark_control_poses.h"
#include "spline/reference_split_spline.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace {

// The fixture of bench/spline_bench.cc (bench/benchmark_control_poses.h): 200 control poses 0.05 s
// apart, steps of 0.1-1 rad and up to 0.5 m per axis, 1024 query times over the valid range.
using bench::kDtNs;
using bench::kNumSamples;
using bench::kT0Ns;

struct Fixture {
  std::vector<SE3d> poses;
  std::unique_ptr<SE3Splined> spline;
  std::unique_ptr<reference::SplitSpline> per_query;
  std::unique_ptr<reference::SplitSpline> cached;
  std::vector<Segment<double>> segments;
  std::vector<reference::Query> queries;
  Eigen::Vector3d bias = Eigen::Vector3d(0.01, -0.02, 0.03);
  Eigen::Vector3d g_w = GravityWorld();
  Eigen::Vector3d gyro_measured = Eigen::Vector3d(0.1, -0.2, 0.3);
  Eigen::Vector3d accel_measured = Eigen::Vector3d(0.1, -0.2, 9.7);
};

const Fixture& GetFixture() {
  static const Fixture* fixture = [] {
    auto* f = new Fixture;
    std::mt19937 rng(42);
    f->poses = bench::BenchmarkControlPoses(&rng);
    f->spline = std::make_unique<SE3Splined>(f->poses, kT0Ns, kDtNs);
    std::vector<Eigen::Matrix3d> R;
    std::vector<Eigen::Vector3d> p;
    for (const SE3d& T : f->poses) {
      R.push_back(T.rotationMatrix());
      p.push_back(T.translation());
    }
    f->per_query = std::make_unique<reference::SplitSpline>(
        R, p, kT0Ns, kDtNs, reference::KnotMode::kPerQuery);
    f->cached =
        std::make_unique<reference::SplitSpline>(R, p, kT0Ns, kDtNs, reference::KnotMode::kCached);
    std::uniform_int_distribution<int64_t> time(f->spline->start_time_ns(),
                                                f->spline->end_time_ns());
    for (int i = 0; i < kNumSamples; ++i) {
      const int64_t t_ns = time(rng);
      f->segments.push_back(f->spline->SegmentAtNs(t_ns));
      f->queries.push_back(f->cached->QueryAtNs(t_ns));
    }
    return f;
  }();
  return *fixture;
}

// What every residual benchmark writes, on both sides.
struct ResidualOutput {
  Eigen::Vector3d residual;
  ControlPoseJacobian<3> control;
  Eigen::Matrix3d bias;
  Eigen::Matrix3d gravity;
};

enum class Side {
  kSplinecal,
  kSplinecalSplit,
  kSplinecalPerQuery,
  kReferencePerQuery,
  kReferenceCached
};

bool IsSplinecal(Side side) {
  return side == Side::kSplinecal || side == Side::kSplinecalSplit ||
         side == Side::kSplinecalPerQuery;
}

TrajectoryModel ModelOf(Side side) {
  return side == Side::kSplinecalSplit ? TrajectoryModel::kSplitSO3R3 : TrajectoryModel::kSE3;
}

const reference::SplitSpline& Reference(const Fixture& f, Side side) {
  return side == Side::kReferenceCached ? *f.cached : *f.per_query;
}

// Runs body(knots, segment) on splinecal's knot data for sample i (the spline's caches, or
// rebuilt from the four control poses).
template <typename Body>
void WithSplinecalKnots(const Fixture& f, int i, bool per_query, bool jacobians, const Body& body) {
  const Segment<double>& seg = f.segments[i];
  if (!per_query) {
    body(f.spline->Knots(seg), seg);
    return;
  }
  const int first = seg.first_index();
  const SegmentKnotData<double> data(
      f.poses[first], f.poses[first + 1], f.poses[first + 2], f.poses[first + 3], jacobians, first);
  body(data.knots(), seg);
}

void BM_Pose(benchmark::State& state, Side side) {
  const Fixture& f = GetFixture();
  int i = 0;
  for (auto _ : state) {
    if (IsSplinecal(side)) {
      SE3d T_w_s;
      WithSplinecalKnots(f,
                         i,
                         side == Side::kSplinecalPerQuery,
                         false,
                         [&](const SegmentKnots<double>& knots, const Segment<double>& seg) {
                           EvaluateSegment(ModelOf(side), knots, seg, &T_w_s);
                         });
      benchmark::DoNotOptimize(T_w_s);
    } else {
      Eigen::Matrix3d R;
      Eigen::Vector3d p;
      Reference(f, side).Pose(f.queries[i], &R, &p);
      benchmark::DoNotOptimize(R);
      benchmark::DoNotOptimize(p);
    }
    i = (i + 1) & (kNumSamples - 1);
  }
}

void BM_ImuPrediction(benchmark::State& state, Side side) {
  const Fixture& f = GetFixture();
  int i = 0;
  Eigen::Vector3d gyro;
  Eigen::Vector3d accel;
  for (auto _ : state) {
    if (IsSplinecal(side)) {
      WithSplinecalKnots(f,
                         i,
                         side == Side::kSplinecalPerQuery,
                         false,
                         [&](const SegmentKnots<double>& knots, const Segment<double>& seg) {
                           PredictImu(
                               ModelOf(side), knots, seg, f.g_w, f.bias, f.bias, &gyro, &accel);
                         });
    } else {
      Reference(f, side).PredictImu(f.queries[i], f.g_w, f.bias, f.bias, &gyro, &accel);
    }
    benchmark::DoNotOptimize(gyro);
    benchmark::DoNotOptimize(accel);
    i = (i + 1) & (kNumSamples - 1);
  }
}

void BM_GyroResidual(benchmark::State& state, Side side) {
  const Fixture& f = GetFixture();
  int i = 0;
  ResidualOutput out;
  reference::ResidualJacobians J_ref;
  for (auto _ : state) {
    if (IsSplinecal(side)) {
      // One gyro for both models (their rotations are the same).
      WithSplinecalKnots(f,
                         i,
                         side == Side::kSplinecalPerQuery,
                         true,
                         [&](const SegmentKnots<double>& knots, const Segment<double>& seg) {
                           Eigen::Vector3d gyro;
                           PredictGyroWithJacobian(knots, seg, f.bias, &gyro, &out.control);
                           out.residual = gyro - f.gyro_measured;
                           out.bias.setIdentity();
                         });
      benchmark::DoNotOptimize(out);
    } else {
      Reference(f, side).GyroResidual(f.queries[i], f.gyro_measured, f.bias, &out.residual, &J_ref);
      benchmark::DoNotOptimize(out.residual);
      benchmark::DoNotOptimize(J_ref);
    }
    i = (i + 1) & (kNumSamples - 1);
  }
}

void BM_AccelResidual(benchmark::State& state, Side side) {
  const Fixture& f = GetFixture();
  int i = 0;
  ResidualOutput out;
  reference::ResidualJacobians J_ref;
  for (auto _ : state) {
    if (IsSplinecal(side)) {
      WithSplinecalKnots(
          f,
          i,
          side == Side::kSplinecalPerQuery,
          true,
          [&](const SegmentKnots<double>& knots, const Segment<double>& seg) {
            Eigen::Vector3d accel;
            PredictAccelWithJacobian(
                ModelOf(side), knots, seg, f.g_w, f.bias, &accel, &out.control, &out.gravity);
            out.residual = accel - f.accel_measured;
            out.bias.setIdentity();
          });
      benchmark::DoNotOptimize(out);
    } else {
      Reference(f, side).AccelResidual(
          f.queries[i], f.accel_measured, f.bias, f.g_w, &out.residual, &J_ref);
      benchmark::DoNotOptimize(out.residual);
      benchmark::DoNotOptimize(J_ref);
    }
    i = (i + 1) & (kNumSamples - 1);
  }
}

BENCHMARK_CAPTURE(BM_Pose, Splinecal, Side::kSplinecal);
BENCHMARK_CAPTURE(BM_Pose, SplinecalSplit, Side::kSplinecalSplit);
BENCHMARK_CAPTURE(BM_Pose, SplinecalPerQuery, Side::kSplinecalPerQuery);
BENCHMARK_CAPTURE(BM_Pose, ReferencePerQuery, Side::kReferencePerQuery);
BENCHMARK_CAPTURE(BM_Pose, ReferenceCached, Side::kReferenceCached);
BENCHMARK_CAPTURE(BM_ImuPrediction, Splinecal, Side::kSplinecal);
BENCHMARK_CAPTURE(BM_ImuPrediction, SplinecalSplit, Side::kSplinecalSplit);
BENCHMARK_CAPTURE(BM_ImuPrediction, SplinecalPerQuery, Side::kSplinecalPerQuery);
BENCHMARK_CAPTURE(BM_ImuPrediction, ReferencePerQuery, Side::kReferencePerQuery);
BENCHMARK_CAPTURE(BM_ImuPrediction, ReferenceCached, Side::kReferenceCached);
BENCHMARK_CAPTURE(BM_GyroResidual, Splinecal, Side::kSplinecal);
BENCHMARK_CAPTURE(BM_GyroResidual, SplinecalSplit, Side::kSplinecalSplit);
BENCHMARK_CAPTURE(BM_GyroResidual, SplinecalPerQuery, Side::kSplinecalPerQuery);
BENCHMARK_CAPTURE(BM_GyroResidual, ReferencePerQuery, Side::kReferencePerQuery);
BENCHMARK_CAPTURE(BM_GyroResidual, ReferenceCached, Side::kReferenceCached);
BENCHMARK_CAPTURE(BM_AccelResidual, Splinecal, Side::kSplinecal);
BENCHMARK_CAPTURE(BM_AccelResidual, SplinecalSplit, Side::kSplinecalSplit);
BENCHMARK_CAPTURE(BM_AccelResidual, SplinecalPerQuery, Side::kSplinecalPerQuery);
BENCHMARK_CAPTURE(BM_AccelResidual, ReferencePerQuery, Side::kReferencePerQuery);
BENCHMARK_CAPTURE(BM_AccelResidual, ReferenceCached, Side::kReferenceCached);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
