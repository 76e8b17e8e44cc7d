// Kalibr's YAML files (docs/conventions.md, "File formats"). Files that begin with OpenCV's
// `%YAML:1.0` line (EuRoC's sensor.yaml, Kalibr's outputs) are accepted.
#ifndef SPLINECAL_IO_KALIBR_YAML_H_
#define SPLINECAL_IO_KALIBR_YAML_H_

#include <string>

#include "splinecal/imu/noise.h"

namespace splinecal {

// Reads the noise keys of a Kalibr imu.yaml: accelerometer_noise_density,
// accelerometer_random_walk, gyroscope_noise_density, gyroscope_random_walk (all required,
// positive and finite) and update_rate (or EuRoC's rate_hz; optional, default 200 Hz).
// Throws Error with the line of the offending key.
ImuNoise ReadImuYaml(const std::string& path);

// The text of a Kalibr imu.yaml for `noise`.
std::string ImuYamlText(const ImuNoise& noise, const std::string& rostopic = "/imu0");

}  // namespace splinecal

#endif  // SPLINECAL_IO_KALIBR_YAML_H_
