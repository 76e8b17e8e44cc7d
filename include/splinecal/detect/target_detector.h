// Calibration target corners in one image: the function at the heart of `splinecal detect`
// (docs/detect.md), image in, corners out, for any program that calls the library.
//
//   aprilgrid     Kalibr's AprilGrid: tag family 36h11 printed with a black border two bits wide.
//                 libapriltag finds and decodes the tags (a family description with the wider
//                 border, built from tag36h11's codes); the 4 corners of tag k get Kalibr's ids
//                 (camera/target.h). Tags with an id outside the grid, a duplicated id, or a
//                 position that its grid neighbours contradict are dropped, so that a corner is
//                 missing rather than wrong. A partly seen grid gives the corners of the tags seen.
//   checkerboard  OpenCV's chessboard finder (the whole board must be seen), ids r cols + c with
//                 corner 0 fixed by the colour of its square, so ids do not depend on how the
//                 board is turned (when cols + rows is odd; an even sum is symmetric under a half
//                 turn and keeps OpenCV's order).
// Both end with sub-pixel refinement: the saddle fit of detect/saddle_point.h for the AprilGrid's
// junctions, OpenCV's cornerSubPix for the checkerboard (detect.md says why each).
#ifndef SPLINECAL_DETECT_TARGET_DETECTOR_H_
#define SPLINECAL_DETECT_TARGET_DETECTOR_H_

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "splinecal/camera/target.h"
#include "splinecal/detect/gray_image.h"

namespace splinecal {

struct CornerDetection {
  int64_t point_id = 0;                          // the target's id (camera/target.h)
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();  // [px], pixel centres at integers
};

struct TargetDetection {
  std::vector<CornerDetection> corners;  // sorted by point_id, each id once
  int tags_found = 0;     // aprilgrid: tags of the grid that were kept
  int tags_rejected = 0;  // aprilgrid: tags dropped (foreign or duplicate id, inconsistent place)
  int corners_rejected = 0;  // corners whose sub-pixel refinement failed
};

// How hard the AprilGrid detector looks for tags: recall against time (docs/detect.md, "Small and
// oblique tags"; the checkerboard detector ignores it). libapriltag decodes a tag from the pixels
// inside it, on an image whose white was grown to cut the tags from their corner squares
// (separate_corner_squares); on tags under ~25 px (or narrower than that when seen obliquely)
// that growth eats the tag's border and the search of the frame as it is misses most tags (14%
// of the corners of 15-20 px tags on the resampled EuRoC frames of
// tests/detect/aprilgrid_recall_test.cc). Two remedies: a tag that the found tags of the grid
// place in the image, kept when the saddle fit finds its corners and its code read there is its
// id's within 4 bits (src/detect/grid_prediction.h); and searching the frame upsampled 2x, with
// the white grown by half a pixel and by one pixel of the frame and the code bits sharpened.
// Together, with a second sub-pixel refinement of refused corners at a smaller blur, they find
// 98% of the corners of 15-20 px tags, with no wrong id.
enum class DetectEffort {
  kFast,      // one search of the frame as it is (quad_decimate below)
  kDefault,   // that search; then, when it found no tag or when tags of the grid that its found
              // tags place wholly inside the image are missing, the predicted tags, and the
              // upsampled searches if tags are still missing (then the predicted tags again)
  kThorough,  // the default's steps, with the upsampled searches in every frame
};

// "fast", "default", "thorough" (the command line's and Python's names); throws splinecal::Error
// naming the accepted ones for anything else.
DetectEffort ParseDetectEffort(const std::string& name);

struct DetectorOptions {
  DetectEffort effort = DetectEffort::kDefault;
  // aprilgrid: libapriltag's quad_decimate in the search of the frame as it is (1 = full
  // resolution; 2 finds Kalibr grids in VGA frames at a third of the time, docs/detect.md).
  double quad_decimate = 2.0;
  // aprilgrid: the scale of the upsampled searches (bilinear); their quads are found at
  // quad_decimate = upsample, i.e. at the frame's own resolution, and decoded in the upsampled
  // pixels. 1 or less: no upsampled search.
  double upsample = 2.0;
  // aprilgrid: a tag is kept only when a tag within this many grid steps was found where its own
  // corners predict it; 0 keeps every decoded tag (not recommended).
  int neighbour_steps = 2;
  // aprilgrid: fewer tags than this in a frame give no corners.
  int min_tags = 1;
  // aprilgrid: grow the white by one pixel before the tag search, which cuts the contacts between
  // each tag and the small squares at its corners (Kalibr's grids). Off finds 21 to 30 of the
  // EuRoC frame's 36 tags instead of 36 (bench/detect_bench.cc).
  bool separate_corner_squares = true;
};

// A detector for one target. Detect() is not thread-safe (libapriltag keeps state); give each
// thread its own detector. Building one costs about 20 ms (the tag family's decode table).
class TargetDetector {
 public:
  // Throws splinecal::Error for a target that is not an aprilgrid or a checkerboard.
  explicit TargetDetector(const CalibrationTarget& target, const DetectorOptions& options = {});
  ~TargetDetector();
  TargetDetector(const TargetDetector&) = delete;
  TargetDetector& operator=(const TargetDetector&) = delete;

  // The corners of the target in `image`; none when the target is not found. Throws
  // splinecal::Error for an empty image or a stride below the width.
  TargetDetection Detect(const GrayImageView& image);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// One-off convenience: builds a detector and runs it once.
TargetDetection DetectTargetCorners(const GrayImageView& image, const CalibrationTarget& target);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_TARGET_DETECTOR_H_
