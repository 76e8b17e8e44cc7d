// What `splinecal calibrate` runs once its inputs are read and its cameras chosen
// (calib/camera_selection.h): the initial guess from the IMU poses when some are given, then
// Calibrate(). The command line and the Python module both call it.
#ifndef SPLINECAL_CALIB_CALIBRATE_RUN_H_
#define SPLINECAL_CALIB_CALIBRATE_RUN_H_

#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/poses.h"

namespace splinecal {

// Calibrate(imu, observations, camchain, target, options, guess) where guess is
// InitialGuessFromImuPoses(imu, initial_poses, ...) when initial_poses is not empty (else the
// target's PnP guess); the guess's warnings come first in result.warnings. target may be null
// (landmarks only), which needs initial_poses. Throws splinecal::Error as Calibrate() does.
CalibrationResult CalibrateWithInitialPoses(const std::vector<ImuSample>& imu,
                                            const std::vector<Observation>& observations,
                                            const Camchain& camchain,
                                            const CalibrationTarget* target,
                                            const std::vector<StampedPose>& initial_poses,
                                            const CalibrateOptions& options);

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CALIBRATE_RUN_H_
