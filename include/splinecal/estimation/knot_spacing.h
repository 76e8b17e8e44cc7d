// The knot spacing of the pose spline chosen from the data (`fit`, `calibrate` with
// --knot-spacing 0): the coarsest spacing whose spline can follow the measured rotation.
#ifndef SPLINECAL_ESTIMATION_KNOT_SPACING_H_
#define SPLINECAL_ESTIMATION_KNOT_SPACING_H_

#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"

namespace splinecal {

// The automatic knot spacing (docs/fit.md, "Knot spacing"): the largest of 0.2, 0.1, 0.05,
// 0.04, 0.025, 0.02, 0.01 s, not below 2 IMU periods, for which the centred moving average over
// one knot interval leaves at most max(1% of the gyro signal's variance, the gyro's white-noise
// variance) of the gyro signal unexplained (the white noise's own share removed); the smallest
// candidate if none does. `rule` (may be nullptr) receives the choice in words. imu: at least 2
// samples with increasing times.
double ChooseKnotSpacing(const std::vector<ImuSample>& imu,
                         const ImuNoise& noise,
                         std::string* rule);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_KNOT_SPACING_H_
