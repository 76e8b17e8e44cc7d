// The one instantiation of the analytic IMU costs (estimation/detail/imu_costs.h declares them
// extern): both sensors and bias models, one sample per block and one segment per block.
#include "splinecal/estimation/detail/imu_costs.h"

namespace splinecal {

template class ImuSampleCostFunction<ImuSensor::kGyroscope, 1>;
template class ImuSampleCostFunction<ImuSensor::kGyroscope, 4>;
template class ImuSampleCostFunction<ImuSensor::kAccelerometer, 1>;
template class ImuSampleCostFunction<ImuSensor::kAccelerometer, 4>;
template class ImuSegmentCostFunction<ImuSensor::kGyroscope, 1>;
template class ImuSegmentCostFunction<ImuSensor::kGyroscope, 4>;
template class ImuSegmentCostFunction<ImuSensor::kAccelerometer, 1>;
template class ImuSegmentCostFunction<ImuSensor::kAccelerometer, 4>;

}  // namespace splinecal
