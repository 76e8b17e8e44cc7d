#include "splinecal/calib/calibrate_run.h"

#include <memory>
#include <string>

#include "splinecal/error.h"

namespace splinecal {

CalibrationResult CalibrateWithInitialPoses(const std::vector<ImuSample>& imu,
                                            const std::vector<Observation>& observations,
                                            const Camchain& camchain,
                                            const CalibrationTarget* target,
                                            const std::vector<StampedPose>& initial_poses,
                                            const CalibrateOptions& options) {
  if (target == nullptr && initial_poses.empty()) {
    throw Error(
        "without a target, initial poses are needed (the IMU trajectory, e.g. `splinecal "
        "align` on SLAM poses)");
  }
  std::vector<std::string> guess_warnings;
  std::unique_ptr<CalibrationInitialGuess> guess;
  if (!initial_poses.empty()) {
    guess = std::make_unique<CalibrationInitialGuess>(InitialGuessFromImuPoses(
        imu, initial_poses, observations, camchain, options, &guess_warnings));
  }
  CalibrationResult result = Calibrate(imu, observations, camchain, target, options, guess.get());
  result.warnings.insert(result.warnings.begin(), guess_warnings.begin(), guess_warnings.end());
  return result;
}

}  // namespace splinecal
