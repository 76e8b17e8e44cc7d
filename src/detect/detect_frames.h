// The engine under DetectFolders (detect/detect_folders.h) and DetectBag (detect/detect_bag.h):
// the target's corners in a stream of camera frames, searched by parallel workers that take the
// next frame from a FrameSource and decode it themselves. Internal to src/detect/.
#ifndef SPLINECAL_SRC_DETECT_DETECT_FRAMES_H_
#define SPLINECAL_SRC_DETECT_DETECT_FRAMES_H_

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/detect/gray_image.h"

namespace splinecal {
namespace internal {

// One frame as a worker takes it: which camera, its place among that camera's frames (the order
// results are gathered in, whatever order the workers finish), and what decoding needs.
struct FrameJob {
  int cam = 0;
  int64_t index = 0;
  ImageFrame frame;
  std::string bytes;  // the encoded frame when it is not a file (a bag message)
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  // The next frame, false at the end. Called by one worker at a time (under a lock): cheap work
  // only (a file name, a bag message copied out). Throws for a problem that ends the run (a
  // damaged bag, a stamp out of order).
  virtual bool Take(FrameJob* job) = 0;
  // The frame's pixels. Called by the workers concurrently. Throws splinecal::Error for a frame
  // that cannot be decoded (the frame is skipped with a warning).
  virtual GrayImage Decode(const FrameJob& job) const = 0;
};

// A camera's resolution from the sizes of its first readable frames (at most 5): the most common,
// the larger on a tie (a stray thumbnail is likelier than a stray full frame).
void ChooseResolution(const std::vector<std::pair<int, int>>& sizes,
                      CameraDetectionSummary* summary);

// Searches every frame `source` gives for the target on min(options.threads, cores) workers.
// `cameras` hold each camera's dir, images_listed (the frames the source will give) and
// resolution; `warnings` the listing's own. Completes the result as DetectFolders documents.
DetectFoldersResult DetectFrames(FrameSource* source,
                                 std::vector<CameraDetectionSummary> cameras,
                                 std::vector<std::string> warnings,
                                 const CalibrationTarget& target,
                                 const DetectFoldersOptions& options);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_DETECT_FRAMES_H_
