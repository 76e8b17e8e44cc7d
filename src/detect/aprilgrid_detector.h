// Kalibr AprilGrid detection with libapriltag (private to src/detect/, behind
// detect/target_detector.h).
#ifndef SPLINECAL_SRC_DETECT_APRILGRID_DETECTOR_H_
#define SPLINECAL_SRC_DETECT_APRILGRID_DETECTOR_H_

#include <opencv2/core.hpp>

#include "splinecal/camera/target.h"
#include "splinecal/detect/target_detector.h"

struct apriltag_detector;
struct apriltag_family;

namespace splinecal {

class AprilGridDetector {
 public:
  AprilGridDetector(const CalibrationTarget& target, const DetectorOptions& options);
  ~AprilGridDetector();
  AprilGridDetector(const AprilGridDetector&) = delete;
  AprilGridDetector& operator=(const AprilGridDetector&) = delete;

  TargetDetection Detect(const cv::Mat& image);

 private:
  CalibrationTarget target_;
  DetectorOptions options_;
  apriltag_family* family_ = nullptr;
  apriltag_detector* detector_ = nullptr;
};

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_APRILGRID_DETECTOR_H_
