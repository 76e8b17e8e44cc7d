#include "splinecal/estimation/imu_autodiff_costs.h"

#include <ceres/autodiff_cost_function.h>
#include <glog/logging.h>

namespace splinecal {

ceres::CostFunction* NewAutoDiffGyroCost(int bias_blocks,
                                         const ImuResidualSegment& segment,
                                         const ImuResidualSample& sample) {
  CHECK(bias_blocks == 1 || bias_blocks == 4) << "bias_blocks must be 1 or 4";
  if (bias_blocks == 1) {
    return new ceres::AutoDiffCostFunction<GyroResidual<1>, 3, 7, 7, 7, 7, 3>(
        new GyroResidual<1>(segment, sample));
  }
  return new ceres::AutoDiffCostFunction<GyroResidual<4>, 3, 7, 7, 7, 7, 3, 3, 3, 3>(
      new GyroResidual<4>(segment, sample));
}

ceres::CostFunction* NewAutoDiffAccelCost(int bias_blocks,
                                          const ImuResidualSegment& segment,
                                          const ImuResidualSample& sample) {
  CHECK(bias_blocks == 1 || bias_blocks == 4) << "bias_blocks must be 1 or 4";
  if (bias_blocks == 1) {
    return new ceres::AutoDiffCostFunction<AccelResidual<1>, 3, 7, 7, 7, 7, 3, 3>(
        new AccelResidual<1>(segment, sample));
  }
  return new ceres::AutoDiffCostFunction<AccelResidual<4>, 3, 7, 7, 7, 7, 3, 3, 3, 3, 3>(
      new AccelResidual<4>(segment, sample));
}

}  // namespace splinecal
