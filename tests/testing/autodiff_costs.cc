// The one unit that instantiates ceres::AutoDiffCostFunction on the residual twins of
// testing/autodiff_costs.h (the header says why they are compiled once).
#include "testing/autodiff_costs.h"

#include <ceres/autodiff_cost_function.h>
#include <glog/logging.h>

namespace splinecal {
namespace testing {

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

ceres::CostFunction* NewAutoDiffPoseCost(const PoseResidualData& data) {
  return new ceres::AutoDiffCostFunction<PoseResidual, 6, 7, 7, 7, 7, 1, 7>(new PoseResidual(data));
}

ReplacementCosts AutoDiffReplacementCosts() {
  ReplacementCosts costs;
  costs.gyro = &NewAutoDiffGyroCost;
  costs.accel = &NewAutoDiffAccelCost;
  costs.pose = &NewAutoDiffPoseCost;
  return costs;
}

}  // namespace testing
}  // namespace splinecal
