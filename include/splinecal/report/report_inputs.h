// What a report was made from, listed at the top of report.html (`fit`, `calibrate`): the input
// files and the IMU noise model that weighted the IMU residuals. A report read months later, or
// next to another run's, then says which data and which weights produced it.
#ifndef SPLINECAL_REPORT_REPORT_INPUTS_H_
#define SPLINECAL_REPORT_REPORT_INPUTS_H_

#include <string>
#include <utility>
#include <vector>

#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {

// (label, path) of one input file, e.g. {"IMU", "imu0.csv"}; an empty path is an input not given.
using ReportInput = std::pair<std::string, std::string>;

// "<p>label: path<br>...</p>" for the inputs that were given, escaped; "" when none was.
std::string InputFilesHtml(const std::vector<ReportInput>& inputs);

// Where the noise densities came from: the imu.yaml path, or the defaults when it is empty.
std::string NoiseSourceText(const std::string& imu_yaml_path);

// A table of Kalibr's four densities (with units): as given (captioned with
// NoiseSourceText(imu_yaml_path)), as the residuals show them and as they weighted the solve
// (estimation/imu_noise_estimate.h), and the update rate as given.
std::string ImuNoiseTableHtml(const ImuNoiseEstimate& noise, const std::string& imu_yaml_path);

// The same in result.yaml: `imu_noise: {mode, <density key>: {given, measured, used,
// determined, redundancy}, ...}`.
void WriteImuNoiseYaml(const ImuNoiseEstimate& noise, YamlWriter* yaml);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_REPORT_INPUTS_H_
