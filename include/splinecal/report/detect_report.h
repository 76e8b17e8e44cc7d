// What `splinecal detect` writes besides observations.csv: result.yaml, one entry per camera
// (docs/detect.md shows one), and the one-line summary per camera it prints.
#ifndef SPLINECAL_REPORT_DETECT_REPORT_H_
#define SPLINECAL_REPORT_DETECT_REPORT_H_

#include <functional>
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

// The files `splinecal detect --out` writes, as the command line and Python's detect(images=...,
// out=...) both write them: observations.csv (io/observations_csv.h) and result.yaml. Throws
// splinecal::Error naming `target_path` when no frame showed the target (nothing is written:
// a wrong target file, not an empty result), and CheckTargetLayout's error
// (camera/target_layout_check.h) when the corners contradict the target's columns or spacing.
std::vector<OutputFile> DetectOutputFiles(const DetectFoldersResult& result,
                                          const CalibrationTarget& target,
                                          const std::string& target_path,
                                 const std::string& effort);

// A DetectFoldersOptions::on_detection callback for `--draw`: stages
// overlays/camN/<t_ns>.png in `output` for every frame with corners (workers call it
// concurrently; it serialises its use of `output`, which must outlive the run).
std::function<void(int, const ImageFrame&, const GrayImage&, const TargetDetection&)>
OverlayWriter(OutputDir* output);

// "detect: cam0 752 x 480: 1440 of 1440 images read, 1389 with the target, 190208 corners".
std::string DetectSummaryText(const DetectFoldersResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_DETECT_REPORT_H_
