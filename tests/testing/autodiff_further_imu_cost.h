// The automatic-differentiation twin of a further IMU's residuals
// (estimation/detail/further_imu_cost.h): the same residuals on the same parameter blocks, every
// block a Jet, through the same templated prediction (PredictFurtherImuAt). The oracle the
// analytic Jacobians are tested against and the baseline the benchmark compares with. Test code
// only.
#ifndef SPLINECAL_TESTS_TESTING_AUTODIFF_FURTHER_IMU_COST_H_
#define SPLINECAL_TESTS_TESTING_AUTODIFF_FURTHER_IMU_COST_H_

#include <ceres/cost_function.h>
#include <ceres/dynamic_autodiff_cost_function.h>

#include <memory>

#include "splinecal/estimation/detail/further_imu_cost.h"
#include "splinecal/estimation/detail/imu_costs.h"

namespace splinecal {
namespace testing {

struct AutoDiffFurtherImuResidual {
  explicit AutoDiffFurtherImuResidual(const FurtherImuSegment& s) : s(s) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* residuals) const {
    const int nb = s.bias_blocks;
    const FurtherImuBlockIndex b(nb);
    const SegmentKnotData<T> data = internal::KnotDataFromBlocks(blocks);
    const ImuIntrinsics<T> p = FurtherImuIntrinsics<T>(s.kind, nb, blocks);
    const Vector3<T> g_w = Eigen::Map<const Vector3<T>>(blocks[b.gravity]);
    for (size_t k = 0; k < s.samples.size(); ++k) {
      const FurtherImuSample& sample = s.samples[k];
      Vector3<T> b_g = Vector3<T>::Zero();
      Vector3<T> b_a = Vector3<T>::Zero();
      for (int j = 0; j < nb; ++j) {
        b_g += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(blocks[b.gyro_bias + j]);
        b_a += T(sample.bias_weights[j]) * Eigen::Map<const Vector3<T>>(blocks[b.accel_bias + j]);
      }
      const T u = T(sample.u0) + blocks[b.time_offset][0] * T(1.0 / s.dt_s);
      Vector3<T> gyro;
      Vector3<T> accel;
      PredictFurtherImuAt<T>(s, data, u, g_w, p, b_g, b_a, &gyro, &accel);
      for (int r = 0; r < 3; ++r) {
        residuals[6 * k + r] = (gyro[r] - T(sample.gyro[r])) * T(1.0 / s.sigma_gyro);
        residuals[6 * k + 3 + r] = (accel[r] - T(sample.accel[r])) * T(1.0 / s.sigma_accel);
      }
    }
    return true;
  }
  FurtherImuSegment s;
};

// The autodiff cost with NewFurtherImuCost's blocks (sizes copied from an analytic instance).
inline ceres::CostFunction* NewAutoDiffFurtherImuCost(const FurtherImuSegment& segment) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<AutoDiffFurtherImuResidual, 8>(
      new AutoDiffFurtherImuResidual(segment));
  const std::unique_ptr<ceres::CostFunction> analytic(NewFurtherImuCost(segment));
  for (int size : analytic->parameter_block_sizes()) cost->AddParameterBlock(size);
  cost->SetNumResiduals(analytic->num_residuals());
  return cost;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_AUTODIFF_FURTHER_IMU_COST_H_
