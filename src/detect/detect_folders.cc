#include "splinecal/detect/detect_folders.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <system_error>
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
  bool used = false;    // decoded with its camera's resolution and searched
  std::string problem;  // why not, when not
  TargetDetection detection;
  double seconds = 0;
};

// A camera's resolution is the most common size among its first 5 readable frames, the larger on
// a tie (one odd frame first in the folder does not decide it); found before the workers start, so that each
// frame is checked as soon as it is decoded and no overlay is drawn for a frame then dropped.
void FindResolution(const ImageFolder& folder, CameraDetectionSummary* summary) {
  std::map<std::pair<int, int>, int> sizes;
  int readable = 0;
  for (size_t i = 0; i < folder.frames.size() && readable < 5; ++i) {
    try {
      const GrayImage image = ReadGrayImage(folder.frames[i].path);
      ++sizes[{image.width, image.height}];
      ++readable;
    } catch (const Error&) {
      // The workers read it again and report the problem with the frame.
    }
  }
  int best = 0;
  for (const auto& [size, count] : sizes) {
    // On a tie the larger size: a stray thumbnail is likelier than a stray full frame.
    const bool larger = int64_t{size.first} * size.second >
                        int64_t{summary->width} * summary->height;
    if (count > best || (count == best && larger)) {
      best = count;
      summary->width = size.first;
      summary->height = size.second;
    }
  }
}

}  // namespace

DetectFoldersResult DetectFolders(const std::vector<ImageFolder>& folders,
                                  const CalibrationTarget& target,
                                  const DetectFoldersOptions& options) {
  const Clock::time_point start = Clock::now();
  DetectFoldersResult result;
  for (size_t cam = 0; cam < folders.size(); ++cam) {
    CameraDetectionSummary summary;
    summary.cam_id = static_cast<int>(cam);
    summary.dir = folders[cam].dir;
    summary.images_listed = static_cast<int64_t>(folders[cam].frames.size());
    FindResolution(folders[cam], &summary);
    result.cameras.push_back(summary);
    for (const std::string& warning : folders[cam].warnings) result.warnings.push_back(warning);
  }
  if (target.type == "checkerboard" && (target.grid_cols + target.grid_rows) % 2 == 0) {
    result.warnings.push_back(
        "a checkerboard of " + std::to_string(target.grid_cols) + " x " +
        std::to_string(target.grid_rows) +
        " inner corners looks the same turned by half a turn: its ids can flip between frames "
        "and cameras (a board with one odd and one even count has none of this)");
  }

  // Every (camera, frame) pair, in camera then time order; workers take the next index.
  std::vector<std::pair<int, size_t>> jobs;
  for (size_t cam = 0; cam < folders.size(); ++cam) {
    for (size_t i = 0; i < folders[cam].frames.size(); ++i) jobs.emplace_back(cam, i);
  }
  std::vector<FrameOutcome> outcomes(jobs.size());
  // No more workers than cores: each holds a decode table and a frame's buffers.
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int threads = std::max(
      1, std::min({options.threads, cores, static_cast<int>(std::max<size_t>(1, jobs.size()))}));
  // Built before the workers start so that a bad target fails once, on this thread.
  std::vector<std::unique_ptr<TargetDetector>> detectors;
  for (int t = 0; t < threads; ++t) {
    detectors.push_back(std::make_unique<TargetDetector>(target, options.detector));
  }

  std::atomic<size_t> next{0};
  std::atomic<int64_t> done{0};
  std::mutex mutex;  // guards progress and the first fatal exception
  std::exception_ptr fatal;
  Clock::time_point last_progress = start;
  auto work = [&](TargetDetector* detector) {
    try {
      for (size_t j = next++; j < jobs.size(); j = next++) {
        const auto [cam, index] = jobs[j];
        const ImageFrame& frame = folders[cam].frames[index];
        const CameraDetectionSummary& camera = result.cameras[cam];
        FrameOutcome& outcome = outcomes[j];
        const Clock::time_point frame_start = Clock::now();
        GrayImage image;
        try {
          // A problem of this frame (unreadable, another size, too small to search) skips it.
          image = ReadGrayImage(frame.path);
          if (image.width != camera.width || image.height != camera.height) {
            throw Error(frame.path, 0,
                        std::to_string(image.width) + " x " + std::to_string(image.height) +
                            " pixels, but cam" + std::to_string(cam) + "'s frames are " +
                            std::to_string(camera.width) + " x " + std::to_string(camera.height));
          }
          outcome.detection = detector->Detect(image.view());
          outcome.used = true;
        } catch (const Error& e) {
          outcome.problem = e.what();
        }
        // A failing callback (an overlay that cannot be written) ends the run: below.
        if (outcome.used && options.on_detection) {
          options.on_detection(cam, frame, image, outcome.detection);
        }
        outcome.seconds = SecondsSince(frame_start);
        const int64_t finished = ++done;
        if (options.progress) {
          std::lock_guard<std::mutex> lock(mutex);
          if (SecondsSince(last_progress) >= 0.2 ||
              finished == static_cast<int64_t>(jobs.size())) {
            last_progress = Clock::now();
            options.progress({finished, static_cast<int64_t>(jobs.size()), SecondsSince(start)});
          }
        }
      }
    } catch (...) {
      // Out of memory, a callback's error: stop every worker, rethrow on the caller's thread.
      std::lock_guard<std::mutex> lock(mutex);
      if (!fatal) fatal = std::current_exception();
      next = jobs.size();
    }
  };
  std::vector<std::thread> workers;
  for (int t = 1; t < threads; ++t) {
    try {
      workers.emplace_back(work, detectors[t].get());
    } catch (const std::system_error&) {
      break;  // the system gives no more threads: the ones started do the work
    }
  }
  work(detectors[0].get());
  for (std::thread& worker : workers) worker.join();
  if (fatal) std::rethrow_exception(fatal);

  std::vector<std::string> first_problem(folders.size());
  for (size_t j = 0; j < jobs.size(); ++j) {
    const auto [cam, index] = jobs[j];
    const ImageFrame& frame = folders[cam].frames[index];
    const FrameOutcome& outcome = outcomes[j];
    CameraDetectionSummary& summary = result.cameras[cam];
    summary.detection_time_s += outcome.seconds;
    if (!outcome.used) {
      // A data.csv row names the frame: say which (a plain folder's origin is the file itself).
      result.warnings.push_back(outcome.problem +
                                (frame.origin != frame.path ? " (" + frame.origin + ")" : "") +
                                ", frame skipped");
      if (first_problem[cam].empty()) first_problem[cam] = outcome.problem;
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
  // A camera of which nothing could be read would be a camera without observations: a wrong
  // folder, not a detail to find in result.yaml.
  for (const CameraDetectionSummary& camera : result.cameras) {
    if (camera.images_read == 0) {
      throw Error(camera.dir, 0,
                  "none of cam" + std::to_string(camera.cam_id) + "'s " +
                      std::to_string(camera.images_listed) +
                      " images could be read (first problem: " + first_problem[camera.cam_id] +
                      ")");
    }
  }
  SortObservations(&result.observations);
  result.wall_time_s = SecondsSince(start);
  result.threads = 1 + static_cast<int>(workers.size());
  return result;
}

}  // namespace splinecal
