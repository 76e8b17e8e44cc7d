// Spline and IMU-model benchmarks: ns per pose evaluation, per IMU prediction, and per gyro /
// accel residual with Jacobians, analytic vs Ceres automatic differentiation through the same
// templated spline.
//
// Residuals are full ceres::CostFunction objects on four 7-parameter pose blocks
// {px, py, pz, qx, qy, qz, qw} (lie/se3_manifold.h) plus a 3-parameter bias block, called through
// CostFunction::Evaluate exactly as Ceres calls them:
//   *Analytic        the spline's cached knot deltas (what a fit uses when an
//                    EvaluationCallback refreshes the spline once per iteration), tangent
//                    Jacobians lifted to the 7-parameter blocks with the manifold's Minus
//                    Jacobian (J_ambient = J_tangent * MinusJacobian, so that J_ambient *
//                    PlusJacobian = J_tangent).
//   *AnalyticBlocks  the same but rebuilding the three knot deltas (Log + Jacobian caches) from
//                    the four pose blocks inside every Evaluate (no shared spline).
//   *AutoDiff        ceres::AutoDiffCostFunction over the same five blocks (Jet<double, 31>),
//                    which necessarily rebuilds the knot deltas from the blocks.
// Each sample's segment (index, u, basis) is computed once at construction, as a cost function
// of a fixed-time measurement would. Build with -DSPLINECAL_NATIVE=ON for -march=native.
#include <benchmark/benchmark.h>
#include <ceres/autodiff_cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "benchmark_control_poses.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment_jacobians.h"

namespace splinecal {
namespace {

using bench::kDtNs;
using bench::kNumSamples;
using bench::kT0Ns;
constexpr double kSqrtInformation = 100.0;

struct Fixture {
  std::unique_ptr<SE3Splined> spline;
  std::vector<int64_t> times_ns;
  std::vector<Segment<double>> segments;
  std::vector<std::array<double, 7>> blocks;  // control poses as pose blocks
  Eigen::Vector3d bias = Eigen::Vector3d(0.01, -0.02, 0.03);
};

const Fixture& GetFixture() {
  static const Fixture* fixture = [] {
    auto* f = new Fixture;
    std::mt19937 rng(42);
    const std::vector<SE3d> poses = bench::BenchmarkControlPoses(&rng);
    f->spline = std::make_unique<SE3Splined>(poses, kT0Ns, kDtNs);
    std::uniform_int_distribution<int64_t> time(f->spline->start_time_ns(),
                                                f->spline->end_time_ns());
    for (int i = 0; i < kNumSamples; ++i) {
      f->times_ns.push_back(time(rng));
      f->segments.push_back(f->spline->SegmentAtNs(f->times_ns.back()));
    }
    for (const SE3d& pose : poses) {
      std::array<double, 7> block;
      PoseToBlock(pose, block.data());
      f->blocks.push_back(block);
    }
    return f;
  }();
  return *fixture;
}

// J_ambient (3x7, row-major) = J_tangent (3x6) * MinusJacobian(x) with (lie/se3_manifold.h)
// d rho / d t = R^T and d phi / d (qx, qy, qz, qw) = 2 [w I - [v]x, -v]; J_ambient *
// PlusJacobian(x) = J_tangent. The first three columns are skipped when the translation
// Jacobian is known to be zero (gyro).
void LiftToPoseBlock(const Eigen::Matrix<double, 3, 6>& J_tangent,
                     const double* block,
                     bool translation_is_zero,
                     double* J_ambient) {
  Eigen::Map<Eigen::Matrix<double, 3, 7, Eigen::RowMajor>> J(J_ambient);
  const Eigen::Quaterniond q(block[6], block[3], block[4], block[5]);
  if (translation_is_zero) {
    J.leftCols<3>().setZero();
  } else {
    J.leftCols<3>() = J_tangent.leftCols<3>() * q.toRotationMatrix().transpose();
  }
  const Eigen::Vector3d v = q.vec();
  Eigen::Matrix<double, 3, 4> M;
  M.leftCols<3>() = 2.0 * (q.w() * Eigen::Matrix3d::Identity() - Hat(v));
  M.col(3) = -2.0 * v;
  J.rightCols<4>() = J_tangent.rightCols<3>() * M;
}

// Gyro or accel residual sqrt_info * (prediction - measurement) on (P0..P3, bias).
class AnalyticImuCost final : public ceres::SizedCostFunction<3, 7, 7, 7, 7, 3> {
 public:
  // spline == nullptr: rebuild the knot data from the pose blocks in every Evaluate.
  AnalyticImuCost(const SE3Splined* spline,
                  const Segment<double>& segment,
                  bool gyro,
                  const Eigen::Vector3d& measurement)
      : spline_(spline), segment_(segment), gyro_(gyro), measurement_(measurement) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> bias(parameters[4]);
    ControlPoseJacobian<3> J;
    ControlPoseJacobian<3>* J_ptr = jacobians != nullptr ? &J : nullptr;
    Eigen::Vector3d prediction;
    if (spline_ != nullptr) {
      Predict(spline_->Knots(segment_), bias, &prediction, J_ptr);
    } else {
      const SegmentKnotData<double> data(PoseFromBlock(parameters[0]),
                                         PoseFromBlock(parameters[1]),
                                         PoseFromBlock(parameters[2]),
                                         PoseFromBlock(parameters[3]),
                                         jacobians != nullptr);
      Predict(data.knots(), bias, &prediction, J_ptr);
    }
    Eigen::Map<Eigen::Vector3d> r(residuals);
    r = kSqrtInformation * (prediction - measurement_);
    if (jacobians == nullptr) return true;
    for (int k = 0; k < 4; ++k) {
      if (jacobians[k] == nullptr) continue;
      LiftToPoseBlock(kSqrtInformation * J.blocks[k], parameters[k], gyro_, jacobians[k]);
    }
    if (jacobians[4] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J_r_bias(jacobians[4]);
      J_r_bias = kSqrtInformation * Eigen::Matrix3d::Identity();
    }
    return true;
  }

 private:
  void Predict(const SegmentKnots<double>& knots,
               const Eigen::Vector3d& bias,
               Eigen::Vector3d* prediction,
               ControlPoseJacobian<3>* J) const {
    if (gyro_) {
      PredictGyroWithJacobian(knots, segment_, bias, prediction, J);
    } else {
      PredictAccelWithJacobian(knots, segment_, GravityWorld(), bias, prediction, J);
    }
  }

  const SE3Splined* spline_;
  Segment<double> segment_;
  bool gyro_;
  Eigen::Vector3d measurement_;
};

struct AutoDiffImuResidual {
  int segment_index;
  double u;
  double dt_s;
  bool gyro;
  Eigen::Vector3d measurement;

  template <typename T>
  bool operator()(
      const T* p0, const T* p1, const T* p2, const T* p3, const T* b, T* residual) const {
    const SegmentKnotData<T> data(
        PoseFromBlock(p0), PoseFromBlock(p1), PoseFromBlock(p2), PoseFromBlock(p3), false);
    const Segment<T> segment = MakeSegment(segment_index, T(u), dt_s);
    const Eigen::Map<const Vector3<T>> bias(b);
    const Vector3<T> zero = Vector3<T>::Zero();
    Vector3<T> prediction;
    if (gyro) {
      PredictImu<T>(data.knots(), segment, GravityWorld<T>(), bias, zero, &prediction, nullptr);
    } else {
      PredictImu<T>(data.knots(), segment, GravityWorld<T>(), zero, bias, nullptr, &prediction);
    }
    Eigen::Map<Vector3<T>> r(residual);
    r = T(kSqrtInformation) * (prediction - measurement.cast<T>());
    return true;
  }
};

// ---------------------------------------------------------------------------------------------

void BM_SegmentAtNs(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.spline->SegmentAtNs(f.times_ns[i]));
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_SegmentAtNs);

void BM_Pose(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  SE3d T_w_s;
  for (auto _ : state) {
    f.spline->Evaluate(f.segments[i], &T_w_s);
    benchmark::DoNotOptimize(T_w_s);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_Pose);

void BM_PoseWithLookup(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.spline->PoseNs(f.times_ns[i]));
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_PoseWithLookup);

// Pose + body angular velocity + world linear acceleration in one pass.
void BM_ImuPrediction_PoseRateAccel(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  SE3d T_w_s;
  Eigen::Vector3d w_s, a_w;
  for (auto _ : state) {
    f.spline->Evaluate(f.segments[i], &T_w_s, &w_s, nullptr, nullptr, &a_w);
    benchmark::DoNotOptimize(T_w_s);
    benchmark::DoNotOptimize(w_s);
    benchmark::DoNotOptimize(a_w);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_ImuPrediction_PoseRateAccel);

// Gyro + accel readings (PredictImu).
void BM_ImuPrediction_GyroAccel(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const Eigen::Vector3d g_w = GravityWorld();
  int i = 0;
  Eigen::Vector3d gyro, accel;
  for (auto _ : state) {
    PredictImu(*f.spline, f.segments[i], g_w, f.bias, f.bias, &gyro, &accel);
    benchmark::DoNotOptimize(gyro);
    benchmark::DoNotOptimize(accel);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_ImuPrediction_GyroAccel);

// The spline's own Jacobian calls (tangent blocks, no Ceres lift).
void BM_PredictGyroWithJacobian(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  Eigen::Vector3d gyro;
  ControlPoseJacobian<3> J;
  for (auto _ : state) {
    PredictGyroWithJacobian(*f.spline, f.segments[i], f.bias, &gyro, &J);
    benchmark::DoNotOptimize(J);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_PredictGyroWithJacobian);

void BM_PredictAccelWithJacobian(benchmark::State& state) {
  const Fixture& f = GetFixture();
  const Eigen::Vector3d g_w = GravityWorld();
  int i = 0;
  Eigen::Vector3d accel;
  ControlPoseJacobian<3> J;
  for (auto _ : state) {
    PredictAccelWithJacobian(*f.spline, f.segments[i], g_w, f.bias, &accel, &J);
    benchmark::DoNotOptimize(J);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_PredictAccelWithJacobian);

void BM_PoseJacobian(benchmark::State& state) {
  const Fixture& f = GetFixture();
  int i = 0;
  SE3d T_w_s;
  ControlPoseJacobian<6> J;
  for (auto _ : state) {
    f.spline->EvaluatePoseJacobian(f.segments[i], &T_w_s, &J);
    benchmark::DoNotOptimize(J);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK(BM_PoseJacobian);

enum class Kind { kAnalytic, kAnalyticBlocks, kAutoDiff };

// Residual + Jacobians through ceres::CostFunction::Evaluate.
void BM_Residual(benchmark::State& state, bool gyro, Kind kind) {
  const Fixture& f = GetFixture();
  std::vector<std::unique_ptr<ceres::CostFunction>> costs;
  for (int i = 0; i < kNumSamples; ++i) {
    const Segment<double>& seg = f.segments[i];
    const Eigen::Vector3d measurement(0.1, -0.2, 9.7);
    if (kind == Kind::kAutoDiff) {
      costs.emplace_back(new ceres::AutoDiffCostFunction<AutoDiffImuResidual, 3, 7, 7, 7, 7, 3>(
          new AutoDiffImuResidual{seg.index, seg.u, f.spline->dt(), gyro, measurement}));
    } else {
      costs.emplace_back(new AnalyticImuCost(
          kind == Kind::kAnalytic ? f.spline.get() : nullptr, seg, gyro, measurement));
    }
  }
  double residuals[3];
  double jacobian_storage[4 * 21 + 9];
  double* jacobians[5] = {jacobian_storage,
                          jacobian_storage + 21,
                          jacobian_storage + 42,
                          jacobian_storage + 63,
                          jacobian_storage + 84};
  int i = 0;
  for (auto _ : state) {
    const int first = f.segments[i].first_index();
    const double* parameters[5] = {f.blocks[first].data(),
                                   f.blocks[first + 1].data(),
                                   f.blocks[first + 2].data(),
                                   f.blocks[first + 3].data(),
                                   f.bias.data()};
    costs[i]->Evaluate(parameters, residuals, jacobians);
    benchmark::DoNotOptimize(residuals);
    benchmark::DoNotOptimize(jacobian_storage);
    i = (i + 1) & (kNumSamples - 1);
  }
}
BENCHMARK_CAPTURE(BM_Residual, Gyro_Analytic, true, Kind::kAnalytic);
BENCHMARK_CAPTURE(BM_Residual, Gyro_AnalyticBlocks, true, Kind::kAnalyticBlocks);
BENCHMARK_CAPTURE(BM_Residual, Gyro_AutoDiff, true, Kind::kAutoDiff);
BENCHMARK_CAPTURE(BM_Residual, Accel_Analytic, false, Kind::kAnalytic);
BENCHMARK_CAPTURE(BM_Residual, Accel_AnalyticBlocks, false, Kind::kAnalyticBlocks);
BENCHMARK_CAPTURE(BM_Residual, Accel_AutoDiff, false, Kind::kAutoDiff);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
