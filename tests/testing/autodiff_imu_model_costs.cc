// The one unit that instantiates ceres::DynamicAutoDiffCostFunction on the IMU-model residual
// twins of testing/autodiff_imu_model_costs.h.
#include "testing/autodiff_imu_model_costs.h"

#include <ceres/dynamic_autodiff_cost_function.h>

#include <memory>

namespace splinecal {
namespace testing {

namespace {

template <typename Functor>
ceres::CostFunction* NewAutoDiffImuModelCost(const ImuModelSegment& segment,
                                             const ceres::CostFunction& analytic) {
  // 8 parameters per pass: the Jets stay small enough to compile and run in the tests.
  auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, 8>(new Functor(segment));
  for (int size : analytic.parameter_block_sizes()) cost->AddParameterBlock(size);
  cost->SetNumResiduals(analytic.num_residuals());
  return cost;
}

}  // namespace

ceres::CostFunction* NewAutoDiffImuModelGyroCost(const ImuModelSegment& segment) {
  const std::unique_ptr<ceres::CostFunction> analytic(NewImuModelGyroCost(segment));
  return NewAutoDiffImuModelCost<ImuModelGyroResidual>(segment, *analytic);
}

ceres::CostFunction* NewAutoDiffImuModelAccelCost(const ImuModelSegment& segment) {
  const std::unique_ptr<ceres::CostFunction> analytic(NewImuModelAccelCost(segment));
  return NewAutoDiffImuModelCost<ImuModelAccelResidual>(segment, *analytic);
}

}  // namespace testing
}  // namespace splinecal
