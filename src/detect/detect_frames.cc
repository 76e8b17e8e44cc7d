#include "detect_frames.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <system_error>
#include <thread>

#include "splinecal/error.h"

namespace splinecal {
namespace internal {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// What one frame gave; filled by whichever worker took the frame.
struct FrameOutcome {
  ImageFrame frame;
  bool used = false;    // decoded with its camera's resolution and searched
  std::string problem;  // why not, when not
  TargetDetection detection;
  double seconds = 0;
};

}  // namespace

void ChooseResolution(const std::vector<std::pair<int, int>>& sizes,
                      CameraDetectionSummary* summary) {
  std::map<std::pair<int, int>, int> counts;
  for (const auto& size : sizes) ++counts[size];
  int best = 0;
  for (const auto& [size, count] : counts) {
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

DetectFoldersResult DetectFrames(FrameSource* source,
                                 std::vector<CameraDetectionSummary> cameras,
                                 std::vector<std::string> warnings,
                                 const CalibrationTarget& target,
                                 const DetectFoldersOptions& options) {
  const Clock::time_point start = Clock::now();
  DetectFoldersResult result;
  result.cameras = std::move(cameras);
  result.warnings = std::move(warnings);
  if (target.type == "checkerboard" && (target.grid_cols + target.grid_rows) % 2 == 0) {
    result.warnings.push_back(
        "a checkerboard of " + std::to_string(target.grid_cols) + " x " +
        std::to_string(target.grid_rows) +
        " inner corners looks the same turned by half a turn: its ids can flip between frames "
        "and cameras (a board with one odd and one even count has none of this)");
  }
  // One slot per listed frame, in camera then frame order: the order results are gathered in.
  std::vector<std::vector<FrameOutcome>> outcomes(result.cameras.size());
  int64_t total = 0;
  for (size_t cam = 0; cam < result.cameras.size(); ++cam) {
    outcomes[cam].resize(static_cast<size_t>(result.cameras[cam].images_listed));
    total += result.cameras[cam].images_listed;
  }
  // No more workers than cores: each holds a decode table and a frame's buffers.
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int threads = static_cast<int>(std::max<int64_t>(
      1, std::min<int64_t>({options.threads, cores, std::max<int64_t>(1, total)})));
  // Built before the workers start so that a bad target fails once, on this thread.
  std::vector<std::unique_ptr<TargetDetector>> detectors;
  for (int t = 0; t < threads; ++t) {
    detectors.push_back(std::make_unique<TargetDetector>(target, options.detector));
  }

  std::atomic<int64_t> done{0};
  std::mutex source_mutex;  // one Take at a time
  std::mutex mutex;         // guards progress and the first fatal exception
  bool stop = false;        // under source_mutex
  std::exception_ptr fatal;
  Clock::time_point last_progress = start;
  auto work = [&](TargetDetector* detector) {
    try {
      FrameJob job;
      while (true) {
        {
          std::lock_guard<std::mutex> lock(source_mutex);
          if (stop || !source->Take(&job)) break;
          if (job.cam < 0 || static_cast<size_t>(job.cam) >= outcomes.size() || job.index < 0 ||
              static_cast<size_t>(job.index) >= outcomes[job.cam].size()) {
            throw Error("a frame source gave more frames than it listed");
          }
        }
        const CameraDetectionSummary& camera = result.cameras[job.cam];
        FrameOutcome& outcome = outcomes[job.cam][job.index];
        outcome.frame = job.frame;
        const Clock::time_point frame_start = Clock::now();
        GrayImage image;
        try {
          // A problem of this frame (unreadable, another size, too small to search) skips it.
          image = source->Decode(job);
          if (image.width != camera.width || image.height != camera.height) {
            throw Error(job.frame.path.empty() ? job.frame.origin : job.frame.path, 0,
                        std::to_string(image.width) + " x " + std::to_string(image.height) +
                            " pixels, but cam" + std::to_string(job.cam) + "'s frames are " +
                            std::to_string(camera.width) + " x " + std::to_string(camera.height));
          }
          outcome.detection = detector->Detect(image.view());
          outcome.used = true;
        } catch (const Error& e) {
          outcome.problem = e.what();
        }
        // A failing callback (an overlay that cannot be written) ends the run: below.
        if (outcome.used && options.on_detection) {
          options.on_detection(job.cam, job.frame, image, outcome.detection);
        }
        outcome.seconds = SecondsSince(frame_start);
        const int64_t finished = ++done;
        if (options.progress) {
          std::lock_guard<std::mutex> lock(mutex);
          if (SecondsSince(last_progress) >= 0.2 || finished == total) {
            last_progress = Clock::now();
            options.progress({finished, total, SecondsSince(start)});
          }
        }
      }
    } catch (...) {
      // Out of memory, a damaged bag, a callback's error: stop every worker, rethrow on the
      // caller's thread.
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (!fatal) fatal = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(source_mutex);
      stop = true;
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

  std::vector<std::string> first_problem(result.cameras.size());
  for (size_t cam = 0; cam < outcomes.size(); ++cam) {
    CameraDetectionSummary& summary = result.cameras[cam];
    for (const FrameOutcome& outcome : outcomes[cam]) {
      const ImageFrame& frame = outcome.frame;
      summary.detection_time_s += outcome.seconds;
      if (!outcome.used) {
        // A data.csv row names the frame: say which (a plain folder's origin is the file itself).
        result.warnings.push_back(
            outcome.problem +
            (!frame.path.empty() && frame.origin != frame.path ? " (" + frame.origin + ")" : "") +
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

}  // namespace internal
}  // namespace splinecal
