// The files of `splinecal allan` (docs/allan.md): allan.csv, result.yaml, imu.yaml and allan.svg
// of an AllanResult (allan/allan.h), as text. report/command_outputs.h lists them for the command
// line and the Python module, which write them the same way (io/output_dir.h).
#ifndef SPLINECAL_REPORT_ALLAN_REPORT_H_
#define SPLINECAL_REPORT_ALLAN_REPORT_H_

#include <string>

#include "splinecal/allan/allan.h"

namespace splinecal {

// allan.csv: "#tau_s", one Allan deviation column per axis, then the low and high ends of each
// axis's confidence interval (gyro in rad/s, accel in m/s^2), 17 significant digits; then
// "stride" and "terms": which start indices each averaging time used (the same for every axis).
std::string AllanCsvText(const AllanResult& result);
// result.yaml: Kalibr keys at the top, then gyroscope: {x: {...}, ...}, accelerometer: {...}.
std::string AllanResultYamlText(const AllanResult& result);
// imu.yaml (Kalibr), with the keys of the sensors present.
std::string AllanImuYamlText(const AllanResult& result);
// allan.svg: log-log deviation per axis with error bars and the fitted lines.
std::string AllanSvgText(const AllanResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_ALLAN_REPORT_H_
