// `splinecal detect`'s work, as a library function: the target's corners in every frame of one
// or more camera folders (io/image_folder.h), in parallel over frames, as the observations that
// `calibrate` reads (camera/observations.h). docs/detect.md.
#ifndef SPLINECAL_DETECT_DETECT_FOLDERS_H_
#define SPLINECAL_DETECT_DETECT_FOLDERS_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"
#include "splinecal/detect/gray_image.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/image_folder.h"

namespace splinecal {

struct CameraDetectionSummary {
  int cam_id = 0;
  std::string dir;
  int width = 0;  // the camera's resolution (the most common of its first 5 readable frames)
  int height = 0;
  int64_t images_listed = 0;       // frames the folder names
  int64_t images_read = 0;         // frames decoded with the camera's resolution and searched
  int64_t images_with_target = 0;  // frames that gave at least one corner
  int64_t corners = 0;
  int64_t tags_rejected = 0;     // aprilgrid: decoded tags dropped (wrong id or place)
  double detection_time_s = 0;  // CPU time spent in this camera's frames (decode + detect)
};

struct DetectFoldersResult {
  std::vector<Observation> observations;  // sorted by (t_ns, cam_id, point_id)
  std::vector<CameraDetectionSummary> cameras;
  // One line per frame that could not be used ("path: problem"), and the folders' own warnings
  // (io/image_folder.h), in frame order.
  std::vector<std::string> warnings;
  double wall_time_s = 0;
  int threads = 1;  // workers that ran: min(options.threads, cores, frames)
};

struct DetectProgress {
  int64_t frames_done = 0;
  int64_t frames_total = 0;
  double elapsed_s = 0;
};

struct DetectFoldersOptions {
  int threads = 1;
  DetectorOptions detector;
  // Called from the worker that finished a frame, at most every 0.2 s and once at the end (never
  // concurrently).
  std::function<void(const DetectProgress&)> progress;
  // Called for every frame that was searched, with or without corners, from the worker that
  // searched it (concurrently: the callee synchronises what it shares). For overlays and for
  // Python's per-frame results.
  std::function<void(int cam_id, const ImageFrame& frame, const GrayImage& image,
                     const TargetDetection& detection)>
      on_detection;
};

// Runs the detector over the frames of `folders` (folder i is camera i) on min(threads, cores)
// workers. A camera's resolution is the most common size among its first 5 readable frames. A frame that cannot be
// decoded, has another size, or that the detector refuses (too small) becomes a warning and is
// skipped. Throws splinecal::Error naming the folder when no frame of some camera can be read;
// rethrows, after stopping every worker, what an on_detection callback throws and any other
// exception (out of memory). A camera without any frame with the target is reported in its
// summary (the caller decides). A checkerboard that is symmetric under a half turn is a warning.
DetectFoldersResult DetectFolders(const std::vector<ImageFolder>& folders,
                                  const CalibrationTarget& target,
                                  const DetectFoldersOptions& options);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_DETECT_FOLDERS_H_
