// The time offset between an IMU and a pose source from the correlation of their rotation rates:
// the initial guess of `fit` (and so of `calibrate`) and its check when the offset is given.
#ifndef SPLINECAL_VIO_TIME_OFFSET_CORRELATION_H_
#define SPLINECAL_VIO_TIME_OFFSET_CORRELATION_H_

#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/poses.h"

namespace splinecal {

// Time offset (t_imu = t_pose + offset) that best aligns the mean body rate of each pose interval
// (Log(R_j^T R_j+1) / (t_j+1 - t_j), frame m) with the mean gyro over the same interval shifted
// by the offset (frame s), searched over centre +- range in steps of one IMU period. At each
// offset the unknown extrinsic rotation and gyro bias are eliminated in closed form (Kabsch on the
// centred rates), so neither biases the alignment. Returns false (and leaves *offset_s) when the
// poses are too sparse (< 5 Hz) or the motion too slow to tell (rate spread < 0.05 rad/s).
// *at_edge (may be nullptr) is set when the best offset is at the edge of the range.
bool EstimateTimeOffsetByCorrelation(const std::vector<ImuSample>& imu,
                                     const std::vector<StampedPose>& poses,
                                     double centre_s,
                                     double range_s,
                                     double* offset_s,
                                     bool* at_edge);

}  // namespace splinecal

#endif  // SPLINECAL_VIO_TIME_OFFSET_CORRELATION_H_
