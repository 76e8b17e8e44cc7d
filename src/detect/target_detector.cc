#include "splinecal/detect/target_detector.h"

#include "aprilgrid_detector.h"
#include "checkerboard_detector.h"
#include "opencv_view.h"
#include "splinecal/error.h"

namespace splinecal {

DetectEffort ParseDetectEffort(const std::string& name) {
  if (name == "fast") return DetectEffort::kFast;
  if (name == "default") return DetectEffort::kDefault;
  if (name == "thorough") return DetectEffort::kThorough;
  throw Error("detect effort '" + name + "': expected fast, default or thorough");
}

struct TargetDetector::Impl {
  CalibrationTarget target;
  std::unique_ptr<AprilGridDetector> aprilgrid;
};

TargetDetector::TargetDetector(const CalibrationTarget& target, const DetectorOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->target = target;
  if (target.type == "aprilgrid") {
    impl_->aprilgrid = std::make_unique<AprilGridDetector>(target, options);
  } else if (target.type != "checkerboard" || target.grid_cols < 2 || target.grid_rows < 2) {
    throw Error("detect: cannot detect a '" + target.type +
                "' target (detectable: aprilgrid, checkerboard)");
  }
}

TargetDetector::~TargetDetector() = default;

TargetDetection TargetDetector::Detect(const GrayImageView& image) {
  const cv::Mat pixels = BorrowMat(image);
  try {
    if (impl_->aprilgrid) return impl_->aprilgrid->Detect(pixels);
    return DetectCheckerboard(pixels, impl_->target);
  } catch (const cv::Exception& e) {
    // OpenCV's own checks; one error type leaves the library (error.h).
    throw Error("detect: OpenCV failed: " + e.err);
  }
}

TargetDetection DetectTargetCorners(const GrayImageView& image, const CalibrationTarget& target) {
  TargetDetector detector(target);
  return detector.Detect(image);
}

}  // namespace splinecal
