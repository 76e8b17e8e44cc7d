// Checkerboard detection with OpenCV's chessboard finder (private to src/detect/, behind
// detect/target_detector.h).
#ifndef SPLINECAL_SRC_DETECT_CHECKERBOARD_DETECTOR_H_
#define SPLINECAL_SRC_DETECT_CHECKERBOARD_DETECTOR_H_

#include <opencv2/core.hpp>

#include "splinecal/camera/target.h"
#include "splinecal/detect/target_detector.h"

namespace splinecal {

TargetDetection DetectCheckerboard(const cv::Mat& image, const CalibrationTarget& target);

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_CHECKERBOARD_DETECTOR_H_
