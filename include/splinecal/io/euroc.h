// EuRoC file formats (docs/conventions.md, "File formats"): imu0/data.csv and
// state_groundtruth_estimate0/data.csv. Readers validate what every command relies on and throw
// splinecal::Error naming file, line and problem; writers print doubles with 17 significant
// digits and int64 nanosecond timestamps.
#ifndef SPLINECAL_IO_EUROC_H_
#define SPLINECAL_IO_EUROC_H_

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "splinecal/imu/ground_truth.h"
#include "splinecal/imu/imu_sample.h"

namespace splinecal {

struct ImuReadOptions {
  // Readings are multiplied by these on input (e.g. 9.81 for an accelerometer in g, pi/180 for a
  // gyro in deg/s).
  double gyro_scale = 1.0;
  double accel_scale = 1.0;
  // Refuse an accelerometer whose median magnitude is near 1 (the data is in g, not m/s^2).
  bool check_accel_units = true;
  // Refuse a gap between samples longer than this many median sample periods.
  double max_gap_periods = 10.0;
  // Added to the error when the file is YAML (TextFileReader::set_yaml_hint): where a YAML file
  // belongs instead, e.g. Kalibr's imu.yaml to --imu-yaml.
  std::string yaml_hint;
};

// Reads EuRoC imu0/data.csv: t_ns, gyro xyz [rad/s], accel xyz [m/s^2]. Throws on: missing file,
// wrong column count, non-numeric or non-finite values, timestamps not strictly increasing,
// gaps, fewer than 2 samples, an accelerometer in units of g.
std::vector<ImuSample> ReadEurocImu(const std::string& path, const ImuReadOptions& options = {});
void WriteEurocImu(const std::vector<ImuSample>& samples, std::ostream* out);

// Reads the 17-column ground truth (t_ns, p, q wxyz, v, gyro bias, accel bias). Throws on the
// same problems as ReadEurocImu and on a quaternion whose norm is not about 1.
std::vector<GroundTruthState> ReadEurocGroundTruth(const std::string& path);
void WriteEurocGroundTruth(const std::vector<GroundTruthState>& states, std::ostream* out);

}  // namespace splinecal

#endif  // SPLINECAL_IO_EUROC_H_
