// The writers behind ExportCalibration (io/calibration_export.h), one file per format, and what
// they share. Private to the library.
#ifndef SPLINECAL_SRC_IO_EXPORT_FORMATS_H_
#define SPLINECAL_SRC_IO_EXPORT_FORMATS_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/io/calibration_export.h"

namespace splinecal {
namespace internal {

std::vector<OutputFile> ExportOpenVins(const CalibrationExport& calibration);
std::vector<OutputFile> ExportVins(const CalibrationExport& calibration);
std::vector<OutputFile> ExportBasalt(const CalibrationExport& calibration);

// Throws splinecal::Error "FORMAT cannot hold camN's MODEL; it holds: SUPPORTED" unless camera
// `index`'s model name is among `supported`.
void RequireCameraModel(const CalibrationExport& calibration,
                        size_t index,
                        const std::string& format,
                        const std::vector<std::string>& supported);
// Throws splinecal::Error when the calibration has no IMU (a camera-only camchain.yaml).
void RequireImu(const CalibrationExport& calibration, const std::string& format);
// camN's topic: the camchain's rostopic, else Kalibr's /camN/image_raw.
std::string CameraTopic(const CalibrationExport& calibration, size_t index);
// radtan's k3 (OpenCV's fifth coefficient) is 0 and not estimated: the formats with four radtan
// coefficients can hold the camera exactly.
bool RadtanHasNoK3(const CalibrationExport& calibration, size_t index);
// The four Kalibr-ordered distortion coefficients of a radtan or equidistant camera (zeros for
// none).
Eigen::Vector4d FourDistortionCoeffs(const CalibrationExport& calibration, size_t index);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_IO_EXPORT_FORMATS_H_
