// The autodiff twin of the pose residual (estimation/pose_cost.h), in a unit of its own: a Jet of
// 29 parameters is slow to compile, and only the tests and the benchmark use it.
#include <ceres/autodiff_cost_function.h>

#include "splinecal/estimation/pose_cost.h"

namespace splinecal {

ceres::CostFunction* NewAutoDiffPoseCost(const PoseResidualData& data) {
  return new ceres::AutoDiffCostFunction<PoseResidual, 6, 7, 7, 7, 7, 1, 7>(new PoseResidual(data));
}

}  // namespace splinecal
