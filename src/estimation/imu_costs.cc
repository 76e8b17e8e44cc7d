// The one instantiation of the analytic IMU costs (estimation/detail/imu_costs.h declares them extern):
// both bias models, one sample per block and one segment per block.
#include "splinecal/estimation/detail/imu_costs.h"

namespace splinecal {

template class GyroCostFunction<1>;
template class GyroCostFunction<4>;
template class AccelCostFunction<1>;
template class AccelCostFunction<4>;
template class GyroSegmentCostFunction<1>;
template class GyroSegmentCostFunction<4>;
template class AccelSegmentCostFunction<1>;
template class AccelSegmentCostFunction<4>;

}  // namespace splinecal
