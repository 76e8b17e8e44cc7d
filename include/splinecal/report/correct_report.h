// What `splinecal correct` (and Python's splinecal.correct) computes and writes: the raw readings
// with an IMU model inverted (imu/correct_imu.h), as mav0/imu0/data.csv, and result.yaml naming
// the model, the biases subtracted, the output frame and the size effect's derivative window.
#ifndef SPLINECAL_REPORT_CORRECT_REPORT_H_
#define SPLINECAL_REPORT_CORRECT_REPORT_H_

#include <string>
#include <vector>

#include "splinecal/imu/correct_imu.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/output_dir.h"

namespace splinecal {

// Where the inputs came from, for result.yaml.
struct CorrectSources {
  std::string imu_path;
  std::string intrinsics_path;
  int imu_index = 0;
};

struct CorrectRun {
  std::vector<ImuSample> corrected;
  std::vector<OutputFile> files;  // mav0/imu0/data.csv, result.yaml
};

// CorrectImuReadings and the files of the command. Throws Error as CorrectImuReadings does.
CorrectRun RunCorrection(const ImuCalibration& imu,
                         const std::vector<ImuSample>& raw,
                         const ImuCorrectionOptions& options,
                         const CorrectSources& sources);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_CORRECT_REPORT_H_
