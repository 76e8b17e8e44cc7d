// The automatic-differentiation twins of the IMU residuals of estimation/imu_costs.h: the same
// residuals on the same parameter blocks, written once on a scalar template and differentiated by
// ceres::AutoDiffCostFunction. They are the oracle the analytic Jacobians are tested against and
// the baseline the benchmark compares with (ResidualOptions::differentiation, estimation/
// spline_problem.h); no estimate uses them by default. Each lives in a unit of its own
// (src/estimation/imu_autodiff_costs.cc): the Jets of 31 to 43 parameters are slow to compile.
#ifndef SPLINECAL_ESTIMATION_IMU_AUTODIFF_COSTS_H_
#define SPLINECAL_ESTIMATION_IMU_AUTODIFF_COSTS_H_

#include <ceres/cost_function.h>

#include "splinecal/estimation/imu_costs.h"

namespace splinecal {

namespace internal {

// The segment of four pose blocks in scalar T (no Jacobian caches: autodiff needs none).
template <typename T>
SegmentKnotData<T> KnotDataFromBlocks(const T* const* poses) {
  return SegmentKnotData<T>(PoseFromBlock(poses[0]),
                            PoseFromBlock(poses[1]),
                            PoseFromBlock(poses[2]),
                            PoseFromBlock(poses[3]),
                            /*with_jacobians=*/false);
}

template <typename T, int kBiasBlocks>
Vector3<T> WeightedBiasT(const ImuResidualSample& sample, const T* const* bias_blocks) {
  Vector3<T> bias = Vector3<T>::Zero();
  for (int j = 0; j < kBiasBlocks; ++j) {
    bias += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(bias_blocks[j]);
  }
  return bias;
}

}  // namespace internal

// Functor for ceres::AutoDiffCostFunction<GyroResidual<k>, 3, 7, 7, 7, 7, 3 (x k)>.
template <int kBiasBlocks>
struct GyroResidual {
  GyroResidual(const ImuResidualSegment& segment_in, const ImuResidualSample& sample_in)
      : segment(segment_in), sample(sample_in) {}

  template <typename T>
  bool Compute(const T* const* blocks, T* residual) const {
    const SegmentKnotData<T> data = internal::KnotDataFromBlocks(blocks);
    const Segment<T> seg = MakeSegment(segment.segment_index, T(sample.u), segment.dt_s);
    const Vector3<T> bias = internal::WeightedBiasT<T, kBiasBlocks>(sample, blocks + 4);
    Vector3<T> gyro;
    PredictImu<T>(data.knots(), seg, Vector3<T>::Zero(), bias, Vector3<T>::Zero(), &gyro, nullptr);
    const T inv_sigma = T(1.0 / segment.sigma);
    for (int a = 0; a < 3; ++a) residual[a] = (gyro[a] - T(sample.measured[a])) * inv_sigma;
    return true;
  }

  template <typename T>
  bool operator()(const T* p0, const T* p1, const T* p2, const T* p3, const T* b0, T* r) const {
    const T* blocks[] = {p0, p1, p2, p3, b0};
    return Compute(blocks, r);
  }
  template <typename T>
  bool operator()(const T* p0,
                  const T* p1,
                  const T* p2,
                  const T* p3,
                  const T* b0,
                  const T* b1,
                  const T* b2,
                  const T* b3,
                  T* r) const {
    const T* blocks[] = {p0, p1, p2, p3, b0, b1, b2, b3};
    return Compute(blocks, r);
  }

  ImuResidualSegment segment;
  ImuResidualSample sample;
};

// Functor for ceres::AutoDiffCostFunction<AccelResidual<k>, 3, 7, 7, 7, 7, 3 (x k), 3>.
template <int kBiasBlocks>
struct AccelResidual {
  AccelResidual(const ImuResidualSegment& segment_in, const ImuResidualSample& sample_in)
      : segment(segment_in), sample(sample_in) {}

  template <typename T>
  bool Compute(const T* const* blocks, T* residual) const {
    const SegmentKnotData<T> data = internal::KnotDataFromBlocks(blocks);
    const Segment<T> seg = MakeSegment(segment.segment_index, T(sample.u), segment.dt_s);
    const Vector3<T> bias = internal::WeightedBiasT<T, kBiasBlocks>(sample, blocks + 4);
    const Vector3<T> g_w = Eigen::Map<const Vector3<T>>(blocks[4 + kBiasBlocks]);
    Vector3<T> accel;
    PredictImu<T>(segment.model, data.knots(), seg, g_w, Vector3<T>::Zero(), bias, nullptr, &accel);
    const T inv_sigma = T(1.0 / segment.sigma);
    for (int a = 0; a < 3; ++a) residual[a] = (accel[a] - T(sample.measured[a])) * inv_sigma;
    return true;
  }

  template <typename T>
  bool operator()(
      const T* p0, const T* p1, const T* p2, const T* p3, const T* b0, const T* g, T* r) const {
    const T* blocks[] = {p0, p1, p2, p3, b0, g};
    return Compute(blocks, r);
  }
  template <typename T>
  bool operator()(const T* p0,
                  const T* p1,
                  const T* p2,
                  const T* p3,
                  const T* b0,
                  const T* b1,
                  const T* b2,
                  const T* b3,
                  const T* g,
                  T* r) const {
    const T* blocks[] = {p0, p1, p2, p3, b0, b1, b2, b3, g};
    return Compute(blocks, r);
  }

  ImuResidualSegment segment;
  ImuResidualSample sample;
};

// The autodiff twins as cost functions (caller owns the result).
ceres::CostFunction* NewAutoDiffGyroCost(int bias_blocks,
                                         const ImuResidualSegment& segment,
                                         const ImuResidualSample& sample);
ceres::CostFunction* NewAutoDiffAccelCost(int bias_blocks,
                                          const ImuResidualSegment& segment,
                                          const ImuResidualSample& sample);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_AUTODIFF_COSTS_H_
