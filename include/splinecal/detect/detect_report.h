// What `splinecal detect` writes besides observations.csv: result.yaml, one entry per camera
// (docs/detect.md shows one), and the one-line summary per camera it prints.
#ifndef SPLINECAL_DETECT_DETECT_REPORT_H_
#define SPLINECAL_DETECT_DETECT_REPORT_H_

#include <string>

#include "splinecal/camera/target.h"
#include "splinecal/detect/detect_folders.h"

namespace splinecal {

// result.yaml: the target, the threads and wall time, then `cameras:` with camN entries holding
// images (the folder), resolution: [w, h], images_listed, images_read, images_with_target,
// corners, tags_rejected and detection_time_s; then the warnings.
std::string DetectResultYamlText(const DetectFoldersResult& result,
                                 const CalibrationTarget& target,
                                 const std::string& target_path);

// "detect: cam0 752 x 480: 1440 of 1440 images read, 1389 with the target, 190208 corners".
std::string DetectSummaryText(const DetectFoldersResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_DETECT_REPORT_H_
