// The automatic-differentiation twins of the IMU and pose residuals of
// estimation/detail/imu_costs.h and estimation/detail/pose_cost.h: the same residuals on the same
// parameter blocks, written once on a scalar template and differentiated by
// ceres::AutoDiffCostFunction. They are the oracle the analytic Jacobians are tested against and
// the baseline the benchmark compares with (AutoDiffReplacementCosts: whole problems through
// ResidualOptions::replacement, estimation/spline_problem.h). Test code only: the library binary
// holds no automatic differentiation of these residuals, and the Jets of 31 to 43 parameters
// compile only into the tests that include this header.
#ifndef SPLINECAL_TESTS_TESTING_AUTODIFF_COSTS_H_
#define SPLINECAL_TESTS_TESTING_AUTODIFF_COSTS_H_

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>
#include <glog/logging.h>

#include <cmath>
#include <tuple>

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/detail/pose_cost.h"
#include "splinecal/estimation/spline_problem.h"

namespace splinecal {
namespace testing {

using internal::KnotDataFromBlocks;

// The sample's bias: its B-spline weights times the segment's kBiasBlocks bias points.
template <typename T, int kBiasBlocks>
Vector3<T> WeightedBiasT(const ImuResidualSample& sample, const T* const* bias_blocks) {
  Vector3<T> bias = Vector3<T>::Zero();
  for (int j = 0; j < kBiasBlocks; ++j) {
    bias += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(bias_blocks[j]);
  }
  return bias;
}

// What ceres::AutoDiffCostFunction calls, for a residual computed from an array of its parameter
// blocks (Derived::Compute(blocks, residual)): one pointer per block and the residual last, for
// any number of blocks (the IMU residuals take 1 or 4 bias blocks).
template <typename Derived>
struct BlockArrayFunctor {
  template <typename T, typename... Rest>
  bool operator()(const T* first, Rest... rest) const {
    const T* blocks[] = {first, rest...};  // the residual last, not read through it
    T* residual = std::get<sizeof...(Rest) - 1>(std::forward_as_tuple(rest...));
    return static_cast<const Derived&>(*this).Compute(blocks, residual);
  }
};

// Functor for ceres::AutoDiffCostFunction<GyroResidual<k>, 3, 7, 7, 7, 7, 3 (x k)>.
template <int kBiasBlocks>
struct GyroResidual : BlockArrayFunctor<GyroResidual<kBiasBlocks>> {
  GyroResidual(const ImuResidualSegment& segment_in, const ImuResidualSample& sample_in)
      : segment(segment_in), sample(sample_in) {}

  template <typename T>
  bool Compute(const T* const* blocks, T* residual) const {
    const SegmentKnotData<T> data = KnotDataFromBlocks(blocks);
    const Segment<T> seg = MakeSegment(segment.segment_index, T(sample.u), segment.dt_s);
    const Vector3<T> bias = WeightedBiasT<T, kBiasBlocks>(sample, blocks + 4);
    Vector3<T> gyro;
    PredictImu<T>(data.knots(), seg, Vector3<T>::Zero(), bias, Vector3<T>::Zero(), &gyro, nullptr);
    const T inv_sigma = T(1.0 / segment.sigma);
    for (int a = 0; a < 3; ++a) residual[a] = (gyro[a] - T(sample.measured[a])) * inv_sigma;
    return true;
  }

  ImuResidualSegment segment;
  ImuResidualSample sample;
};

// Functor for ceres::AutoDiffCostFunction<AccelResidual<k>, 3, 7, 7, 7, 7, 3 (x k), 3>.
template <int kBiasBlocks>
struct AccelResidual : BlockArrayFunctor<AccelResidual<kBiasBlocks>> {
  AccelResidual(const ImuResidualSegment& segment_in, const ImuResidualSample& sample_in)
      : segment(segment_in), sample(sample_in) {}

  template <typename T>
  bool Compute(const T* const* blocks, T* residual) const {
    const SegmentKnotData<T> data = KnotDataFromBlocks(blocks);
    const Segment<T> seg = MakeSegment(segment.segment_index, T(sample.u), segment.dt_s);
    const Vector3<T> bias = WeightedBiasT<T, kBiasBlocks>(sample, blocks + 4);
    const Vector3<T> g_w = Eigen::Map<const Vector3<T>>(blocks[4 + kBiasBlocks]);
    Vector3<T> accel;
    PredictImu<T>(segment.model, data.knots(), seg, g_w, Vector3<T>::Zero(), bias, nullptr, &accel);
    const T inv_sigma = T(1.0 / segment.sigma);
    for (int a = 0; a < 3; ++a) residual[a] = (accel[a] - T(sample.measured[a])) * inv_sigma;
    return true;
  }

  ImuResidualSegment segment;
  ImuResidualSample sample;
};

// The twin of BiasRandomWalkCostFunction (estimation/bias_costs.h) for
// ceres::AutoDiffCostFunction<BiasRandomWalkResidual, 9, 3, 3, 3, 3>.
struct BiasRandomWalkResidual {
  BiasRandomWalkResidual(double knot_spacing_s, double random_walk_density)
      : weights(BiasRandomWalkSqrtInformation() /
                (random_walk_density * std::sqrt(knot_spacing_s))) {}

  template <typename T>
  bool operator()(const T* c0, const T* c1, const T* c2, const T* c3, T* residual) const {
    const T* c[4] = {c0, c1, c2, c3};
    for (int m = 0; m < 3; ++m) {
      for (int a = 0; a < 3; ++a) {
        T sum = T(0.0);
        for (int j = 0; j < 4; ++j) sum += T(weights(m, j)) * c[j][a];
        residual[3 * m + a] = sum;
      }
    }
    return true;
  }

  Eigen::Matrix<double, 3, 4> weights;  // S / (sigma_rw sqrt(db))
};

// Functor for ceres::AutoDiffCostFunction<PoseResidual, 6, 7, 7, 7, 7, 1, 7> (the time offset
// passes through u as a Jet): the twin of PoseCostFunction.
struct PoseResidual {
  explicit PoseResidual(const PoseResidualData& data_in) : data(data_in) {}

  template <typename T>
  bool operator()(const T* p0,
                  const T* p1,
                  const T* p2,
                  const T* p3,
                  const T* time_offset,
                  const T* T_m_s_block,
                  T* residual) const {
    const SegmentKnotData<T> knots(PoseFromBlock(p0),
                                   PoseFromBlock(p1),
                                   PoseFromBlock(p2),
                                   PoseFromBlock(p3),
                                   /*with_jacobians=*/false);
    const T u = (T(data.t_s) + time_offset[0]) / T(data.dt_s) - T(double(data.segment_index));
    const Segment<T> segment = MakeSegment(data.segment_index, u, data.dt_s);
    SE3<T> T_w_s;
    EvaluateSegment<T>(data.model, knots.knots(), segment, &T_w_s);
    const SE3<T> T_pred = T_w_s * PoseFromBlock(T_m_s_block).inverse();
    const SE3<T> T_meas = data.T_w_m.cast<T>();
    const Vector3<T> dp = T_pred.translation() - T_meas.translation();
    const Vector3<T> phi = (T_meas.so3().inverse() * T_pred.so3()).Log();
    for (int a = 0; a < 3; ++a) {
      residual[a] = dp[a] / T(data.sigma_m);
      residual[3 + a] = phi[a] / T(data.sigma_rad);
    }
    return true;
  }

  PoseResidualData data;
};

// The autodiff twins as cost functions (caller owns the result). Defined in autodiff_costs.cc,
// compiled once into the library splinecal_test_oracles (CMakeLists.txt) that the tests and
// benchmarks link: instantiated inline, their Jets of 31 to 43 parameters were most of the
// compile time of each of the five test files and the benchmark calling them (fit_test.cc:
// 190 CPU-s with them, 43 without; docs/reliability.md, "The cold build").
ceres::CostFunction* NewAutoDiffGyroCost(int bias_blocks,
                                         const ImuResidualSegment& segment,
                                         const ImuResidualSample& sample);
ceres::CostFunction* NewAutoDiffAccelCost(int bias_blocks,
                                          const ImuResidualSegment& segment,
                                          const ImuResidualSample& sample);
ceres::CostFunction* NewAutoDiffPoseCost(const PoseResidualData& data);

// The twins in place of the analytic residuals of a whole problem (fit, the spline problem):
// options.residuals.replacement = testing::AutoDiffReplacementCosts().
ReplacementCosts AutoDiffReplacementCosts();

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_AUTODIFF_COSTS_H_
