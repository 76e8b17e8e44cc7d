#include "splinecal/detect/detect_folders.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What one frame gave; filled by whichever worker took the frame.
struct FrameOutcome {
  bool read = false;
  int width = 0;
  int height = 0;
  std::string problem;
  TargetDetection detection;
  double seconds = 0;
};

}  // namespace

DetectFoldersResult DetectFolders(const std::vector<ImageFolder>& folders,
                                  const CalibrationTarget& target,
                                  const DetectFoldersOptions& options) {
  const Clock::time_point start = Clock::now();
  // Every (camera, frame) pair, in camera then time order; workers take the next index.
  std::vector<std::pair<int, size_t>> jobs;
  for (size_t cam = 0; cam < folders.size(); ++cam) {
    for (size_t i = 0; i < folders[cam].frames.size(); ++i) jobs.emplace_back(cam, i);
  }
  std::vector<FrameOutcome> outcomes(jobs.size());
  // Built before the workers start so that a bad target fails once, on this thread.
  const int threads = std::max(1, std::min<int>(options.threads, std::max<size_t>(1, jobs.size())));
  std::vector<std::unique_ptr<TargetDetector>> detectors;
  for (int t = 0; t < threads; ++t) {
    detectors.push_back(std::make_unique<TargetDetector>(target, options.detector));
  }

  std::atomic<size_t> next{0};
  std::atomic<int64_t> done{0};
  std::mutex progress_mutex;
  Clock::time_point last_progress = start;
  auto work = [&](TargetDetector* detector) {
    for (size_t j = next++; j < jobs.size(); j = next++) {
      const auto [cam, index] = jobs[j];
      const ImageFrame& frame = folders[cam].frames[index];
      FrameOutcome& outcome = outcomes[j];
      const Clock::time_point frame_start = Clock::now();
      try {
        const GrayImage image = ReadGrayImage(frame.path);
        outcome.read = true;
        outcome.width = image.width;
        outcome.height = image.height;
        outcome.detection = detector->Detect(image.view());
        if (options.on_detection && !outcome.detection.corners.empty()) {
          options.on_detection(cam, frame, image, outcome.detection);
        }
      } catch (const Error& e) {
        outcome.problem = e.what();
      }
      outcome.seconds = SecondsSince(frame_start);
      const int64_t finished = ++done;
      if (options.progress) {
        std::lock_guard<std::mutex> lock(progress_mutex);
        if (std::chrono::duration<double>(Clock::now() - last_progress).count() >= 0.2 ||
            finished == static_cast<int64_t>(jobs.size())) {
          last_progress = Clock::now();
          options.progress({finished, static_cast<int64_t>(jobs.size()), SecondsSince(start)});
        }
      }
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) workers.emplace_back(work, detectors[t].get());
  work(detectors[0].get());
  for (std::thread& worker : workers) worker.join();

  DetectFoldersResult result;
  for (size_t cam = 0; cam < folders.size(); ++cam) {
    CameraDetectionSummary summary;
    summary.cam_id = static_cast<int>(cam);
    summary.dir = folders[cam].dir;
    summary.images_listed = static_cast<int64_t>(folders[cam].frames.size());
    result.cameras.push_back(summary);
    for (const std::string& warning : folders[cam].warnings) result.warnings.push_back(warning);
  }
  for (size_t j = 0; j < jobs.size(); ++j) {
    const auto [cam, index] = jobs[j];
    const ImageFrame& frame = folders[cam].frames[index];
    FrameOutcome& outcome = outcomes[j];
    CameraDetectionSummary& summary = result.cameras[cam];
    summary.detection_time_s += outcome.seconds;
    if (!outcome.read) {
      // A data.csv row names the frame: say which (a plain folder's origin is the file itself).
      result.warnings.push_back(outcome.problem +
                                (frame.origin != frame.path ? " (" + frame.origin + ")" : "") +
                                ", frame skipped");
      continue;
    }
    if (summary.width == 0) {
      summary.width = outcome.width;
      summary.height = outcome.height;
    } else if (outcome.width != summary.width || outcome.height != summary.height) {
      result.warnings.push_back(frame.path + ": " + std::to_string(outcome.width) + " x " +
                                std::to_string(outcome.height) + " pixels, but cam" +
                                std::to_string(cam) + "'s frames are " +
                                std::to_string(summary.width) + " x " +
                                std::to_string(summary.height) + ", frame skipped");
      continue;
    }
    ++summary.images_read;
    summary.tags_rejected += outcome.detection.tags_rejected;
    if (outcome.detection.corners.empty()) continue;
    ++summary.images_with_target;
    summary.corners += static_cast<int64_t>(outcome.detection.corners.size());
    for (const CornerDetection& corner : outcome.detection.corners) {
      result.observations.push_back({frame.t_ns, static_cast<int>(cam), corner.point_id,
                                     corner.uv});
    }
  }
  int64_t read = 0;
  for (const CameraDetectionSummary& summary : result.cameras) read += summary.images_read;
  if (read == 0) {
    throw Error("detect: no image could be read" +
                (result.warnings.empty() ? std::string() : " (first problem: " +
                                                               result.warnings.front() + ")"));
  }
  SortObservations(&result.observations);
  result.wall_time_s = SecondsSince(start);
  return result;
}

}  // namespace splinecal
