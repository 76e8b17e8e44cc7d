// What `splinecal detect` writes (docs/detect.md shows the files): observations.csv and
// result.yaml, one entry per camera, as a list of files for io/output_dir.h (written whole or
// not at all, as every command's), and the one-line summary per camera it prints. The overlays
// (--draw) are images the command stages beside them while it detects.
#ifndef SPLINECAL_REPORT_DETECT_REPORT_H_
#define SPLINECAL_REPORT_DETECT_REPORT_H_

#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/io/output_dir.h"

namespace splinecal {

// result.yaml: the target, the detector's effort (its name, detect/target_detector.h), the
// threads and wall time, then `cameras:` with camN entries holding images (the folder),
// resolution: [w, h], images_listed, images_read, images_with_target, corners, tags_rejected and
// detection_time_s; then the warnings.
std::string DetectResultYamlText(const DetectFoldersResult& result,
                                 const CalibrationTarget& target,
                                 const std::string& target_path,
                                 const std::string& effort);

// observations.csv (io/observations_csv.h) and result.yaml above.
std::vector<OutputFile> DetectOutputFiles(const DetectFoldersResult& result,
                                          const CalibrationTarget& target,
                                          const std::string& target_path,
                                          const std::string& effort);

// "detect: cam0 752 x 480: 1440 of 1440 images read, 1389 with the target, 190208 corners".
std::string DetectSummaryText(const DetectFoldersResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_DETECT_REPORT_H_
