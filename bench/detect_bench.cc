// Benchmarks of `splinecal detect` (docs/performance.md and docs/detect.md):
//   - BM_AprilGridFrame: the AprilGrid detector on the bundled EuRoC frame (752 x 480, 36 tags),
//     image already decoded; BM_AprilGridFrameWithDecode adds reading the PNG.
//   - BM_AprilGridSmallTags/effort/scale_percent: the same frame scaled down (area average) to
//     35..100 %, tags of 14..40 px, at each --effort (0 fast, 1 default, 2 thorough); counter:
//     corners found of 144.
//   - BM_CheckerboardFrame: the checkerboard detector on OpenCV's left01.jpg (640 x 480, 9 x 6).
//   - BM_DetectFolder*/threads: the whole command's work (list, decode, detect, gather) on a
//     folder of 96 frames, 1 and 2 threads, the default effort: frames/s against the targets
//     (AprilGrid 110 frames/s, checkerboard 50 frames/s on 2 cores), and the CPU time per frame
//     of all threads; BM_DetectFolderSmallTags on resampled copies with tags of 12-25 px.
//   - BM_DetectorChoice/...: why libapriltag and not OpenCV's ArUco (docs/detect.md): each one
//     on the EuRoC frame, with and without the 2 x 2 white growth that separates Kalibr's tags
//     from their corner squares; counters: tags found of 36, and the homography RMS [px] of the
//     found corners after the same saddle refinement, undistorted with the published cam0 model.
//
// Run: scripts/bench.sh detect_bench, or build-bench/bench/detect_bench
#include <benchmark/benchmark.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sys/resource.h>

#include "splinecal/detect/detect_folders.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/detect/saddle_point.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/image_folder.h"
#include "splinecal/io/target_yaml.h"
#include "detect/warped_views.h"

namespace splinecal {
namespace {

const std::string kBundled = std::string(SPLINECAL_SOURCE_DIR) + "/data/euroc_april_frames";
const std::string kEurocFrame = kBundled + "/cam0/data/1403709395937837056.png";
const std::string kChessboard = std::string(SPLINECAL_SOURCE_DIR) +
                                "/../shared/data/opencv_chessboard/left01.jpg";

CalibrationTarget EurocGrid() { return ReadTargetYaml(kBundled + "/aprilgrid.yaml"); }

void BM_AprilGridFrame(benchmark::State& state) {
  const GrayImage image = ReadGrayImage(kEurocFrame);
  TargetDetector detector(EurocGrid());
  size_t corners = 0;
  for (auto _ : state) corners = detector.Detect(image.view()).corners.size();
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["frames_per_s"] = benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_AprilGridFrame)->Unit(benchmark::kMillisecond);

void BM_AprilGridFrameWithDecode(benchmark::State& state) {
  TargetDetector detector(EurocGrid());
  for (auto _ : state) {
    const GrayImage image = ReadGrayImage(kEurocFrame);
    benchmark::DoNotOptimize(detector.Detect(image.view()).corners.size());
  }
}
BENCHMARK(BM_AprilGridFrameWithDecode)->Unit(benchmark::kMillisecond);

void BM_AprilGridSmallTags(benchmark::State& state) {
  const GrayImage frame = ReadGrayImage(kEurocFrame);
  const double scale = state.range(1) / 100.0;
  const cv::Mat pixels(frame.height, frame.width, CV_8UC1,
                       const_cast<uint8_t*>(frame.pixels.data()));
  cv::Mat scaled;
  cv::resize(pixels, scaled, cv::Size(), scale, scale, cv::INTER_AREA);
  const GrayImageView view{scaled.cols, scaled.rows, static_cast<std::ptrdiff_t>(scaled.step),
                           scaled.data};
  DetectorOptions options;
  options.effort = static_cast<DetectEffort>(state.range(0));
  TargetDetector detector(EurocGrid(), options);
  size_t corners = 0;
  for (auto _ : state) corners = detector.Detect(view).corners.size();
  state.counters["corners"] = static_cast<double>(corners);
  state.counters["frames_per_s"] =
      benchmark::Counter(1.0, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_AprilGridSmallTags)
    ->ArgNames({"effort", "scale_percent"})
    ->ArgsProduct({{0, 1, 2}, {35, 42, 50, 100}})
    ->Unit(benchmark::kMillisecond);

void BM_CheckerboardFrame(benchmark::State& state) {
  if (!std::filesystem::exists(kChessboard)) {
    state.SkipWithError("../shared/data/opencv_chessboard is absent");
    return;
  }
  const GrayImage image = ReadGrayImage(kChessboard);
  TargetDetector detector(MakeCheckerboard(9, 6, 0.025, 0.025));
  size_t corners = 0;
  for (auto _ : state) corners = detector.Detect(image.view()).corners.size();
  state.counters["corners"] = static_cast<double>(corners);
}
BENCHMARK(BM_CheckerboardFrame)->Unit(benchmark::kMillisecond);

// A plain folder of 96 copies of `source` (the decode is part of the work, as in a recording).
std::string FolderOfCopies(const std::string& source, const std::string& name) {
  const std::string dir = (std::filesystem::temp_directory_path() / name).string();
  std::filesystem::create_directories(dir);
  const std::string ext = std::filesystem::path(source).extension().string();
  for (int i = 0; i < 96; ++i) {
    std::filesystem::copy_file(source, dir + "/" + std::to_string(1000 + i) + ext,
                               std::filesystem::copy_options::overwrite_existing);
  }
  return dir;
}

// CPU time of every thread of this process [s] (Google Benchmark's CPU time is the main
// thread's only; the folder benchmarks run workers).
double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
         1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

// The command's work on `dir`'s frames at the default effort; counters: frames/s (real time),
// CPU ms per frame over all threads (what a shared machine cannot inflate much), corners per
// frame.
void DetectFolderBench(benchmark::State& state, const std::string& dir,
                       const CalibrationTarget& target) {
  const std::vector<ImageFolder> folders = {ListImageFolder(dir)};
  const double frames = static_cast<double>(folders[0].frames.size());
  DetectFoldersOptions options;
  options.threads = static_cast<int>(state.range(0));
  size_t corners = 0;
  const double cpu_start = ProcessCpuSeconds();
  for (auto _ : state) corners = DetectFolders(folders, target, options).observations.size();
  const double cpu = ProcessCpuSeconds() - cpu_start;
  state.counters["frames_per_s"] =
      benchmark::Counter(frames, benchmark::Counter::kIsIterationInvariantRate);
  state.counters["cpu_ms_per_frame"] = 1e3 * cpu / (frames * state.iterations());
  state.counters["corners_per_frame"] = corners / frames;
}

void DetectFolderBench(benchmark::State& state, const std::string& source,
                       const CalibrationTarget& target, const std::string& name) {
  if (!std::filesystem::exists(source)) {
    state.SkipWithError((source + " is absent").c_str());
    return;
  }
  DetectFolderBench(state, FolderOfCopies(source, name), target);
}

void BM_DetectFolderAprilGrid(benchmark::State& state) {
  DetectFolderBench(state, kEurocFrame, EurocGrid(), "splinecal_bench_aprilgrid");
}
BENCHMARK(BM_DetectFolderAprilGrid)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

// 96 resampled copies of the EuRoC frame with small, oblique tags, the kind of views of
// tests/detect/aprilgrid_recall_test.cc (detect/warped_views.h): scales 0.42, 0.5 and 0.6 against
// tilts of 0 to 60 degrees, turned in the image, every third blurred (0.8 px) or noisy (3 grey
// levels), each pasted at the centre of a 640 x 480 grey frame (a folder's frames share one size).
// Tags of about 12 to 25 px on their shortest side, where the default effort's extra steps run.
std::string FolderOfSmallTags() {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "splinecal_bench_small_tags").string();
  std::filesystem::create_directories(dir);
  const GrayImage frame = ReadGrayImage(kEurocFrame);
  std::vector<Eigen::Vector2d> region;
  for (const CornerDetection& c : TargetDetector(EurocGrid()).Detect(frame.view()).corners) {
    region.push_back(c.uv);
  }
  const std::vector<std::pair<double, double>> tilts = {{0, 0},   {35, 0},  {50, 90},
                                                        {60, 0}, {60, 90}, {45, 45}};
  uint32_t seed = 1;
  for (int i = 0; i < 96; ++i, ++seed) {
    testing::ViewSpec spec;
    spec.scale = std::vector<double>{0.42, 0.5, 0.6}[(i / 6) % 3];
    spec.tilt_deg = tilts[i % 6].first;
    spec.tilt_axis_deg = tilts[i % 6].second;
    spec.roll_deg = 37.0 * seed;
    spec.seed = seed;
    if (seed % 3 == 1) spec.blur_px = 0.8;
    if (seed % 3 == 2) spec.noise = 3.0;
    const testing::WarpedView view = testing::MakeWarpedView(frame.view(), region, spec);
    cv::Mat canvas(480, 640, CV_8UC1, cv::Scalar(128));
    const int w = std::min(view.image.width, 640), h = std::min(view.image.height, 480);
    const cv::Mat pixels(view.image.height, view.image.width, CV_8UC1,
                         const_cast<uint8_t*>(view.image.pixels.data()));
    pixels(cv::Rect((view.image.width - w) / 2, (view.image.height - h) / 2, w, h))
        .copyTo(canvas(cv::Rect((640 - w) / 2, (480 - h) / 2, w, h)));
    cv::imwrite(dir + "/" + std::to_string(1000 + i) + ".png", canvas);
  }
  return dir;
}

void BM_DetectFolderSmallTags(benchmark::State& state) {
  if (!std::filesystem::exists(kEurocFrame)) {
    state.SkipWithError("the bundled EuRoC frame is absent");
    return;
  }
  static const std::string dir = FolderOfSmallTags();
  DetectFolderBench(state, dir, EurocGrid());
}
BENCHMARK(BM_DetectFolderSmallTags)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

void BM_DetectFolderCheckerboard(benchmark::State& state) {
  DetectFolderBench(state, kChessboard, MakeCheckerboard(9, 6, 0.025, 0.025),
                    "splinecal_bench_checkerboard");
}
BENCHMARK(BM_DetectFolderCheckerboard)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

// ---- The detector choice: OpenCV's ArUco against libapriltag on the real frame. ----

// Kalibr's corner ids of a tag whose corners are given in the target's tag-local order (0, 0),
// (1, 0), (1, 1), (0, 1).
int64_t CornerId(int tag, int k) {
  const int local_x[4] = {0, 1, 1, 0}, local_y[4] = {0, 0, 1, 1};
  return (2 * (tag / 6) + local_y[k]) * 12 + 2 * (tag % 6) + local_x[k];
}

// Refines the corners with the production saddle fit and measures the homography RMS after
// undistortion with the published cam0 model; -1 with fewer than 8 corners.
double HomographyRms(const GrayImage& image, std::map<int64_t, Eigen::Vector2d> corners) {
  std::vector<Eigen::Vector2d> points;
  for (const auto& [id, uv] : corners) points.push_back(uv);
  SaddleOptions saddle;
  const std::vector<bool> ok = RefineSaddlePoints(image.view(), saddle, &points);
  const CalibrationTarget grid = EurocGrid();
  const Camera camera = ReadCamchainYaml(kBundled + "/camchain_euroc.yaml")[0].camera;
  std::vector<cv::Point2d> plane, ideal;
  size_t i = 0;
  for (const auto& [id, uv] : corners) {
    Eigen::Vector3d ray;
    if (ok[i] && camera.Unproject(points[i], &ray)) {
      plane.emplace_back(grid.points.at(id).x(), grid.points.at(id).y());
      ideal.emplace_back(camera.fu * ray.x() + camera.pu, camera.fv * ray.y() + camera.pv);
    }
    ++i;
  }
  if (plane.size() < 8) return -1;
  const cv::Mat H = cv::findHomography(plane, ideal, 0);
  std::vector<cv::Point2d> projected;
  cv::perspectiveTransform(plane, projected, H);
  double sum = 0;
  for (size_t j = 0; j < plane.size(); ++j) sum += std::pow(cv::norm(projected[j] - ideal[j]), 2);
  return std::sqrt(sum / plane.size());
}

// ArUco's DICT_APRILTAG_36h11 with Kalibr's 2-bit border. Its corners are the marker image's
// top-left, top-right, bottom-right, bottom-left; on the EuRoC frame the order that puts them on
// the grid is (1, 0, 3, 2) of the target's tag-local order (found by trying all eight).
void BM_DetectorChoiceAruco(benchmark::State& state) {
  const bool grow_white = state.range(0) != 0;
  const GrayImage image = ReadGrayImage(kEurocFrame);
  const cv::Mat pixels(image.height, image.width, CV_8UC1, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat input = pixels;
  if (grow_white) cv::dilate(pixels, input, cv::Mat::ones(2, 2, CV_8U));
  const cv::Ptr<cv::aruco::Dictionary> dictionary =
      cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
  const cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  parameters->markerBorderBits = 2;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  for (auto _ : state) cv::aruco::detectMarkers(input, dictionary, corners, ids, parameters);
  std::map<int64_t, Eigen::Vector2d> found;
  const int order[4] = {1, 0, 3, 2};
  int tags = 0;
  for (size_t t = 0; t < ids.size(); ++t) {
    if (ids[t] < 0 || ids[t] >= 36) continue;
    ++tags;
    for (int k = 0; k < 4; ++k) {
      found[CornerId(ids[t], k)] = Eigen::Vector2d(corners[t][order[k]].x, corners[t][order[k]].y);
    }
  }
  state.counters["tags_of_36"] = tags;
  state.counters["homography_rms_px"] = HomographyRms(image, found);
}
BENCHMARK(BM_DetectorChoiceAruco)->ArgName("grow_white")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// libapriltag as splinecal uses it (TargetDetector), and without the white growth for
// comparison (neighbour check and refinement as in production).
void BM_DetectorChoiceLibapriltag(benchmark::State& state) {
  const GrayImage image = ReadGrayImage(kEurocFrame);
  DetectorOptions options;
  options.separate_corner_squares = state.range(0) != 0;
  TargetDetector detector(EurocGrid(), options);
  TargetDetection detection;
  for (auto _ : state) detection = detector.Detect(image.view());
  std::map<int64_t, Eigen::Vector2d> found;
  for (const CornerDetection& c : detection.corners) found[c.point_id] = c.uv;
  state.counters["tags_of_36"] = detection.tags_found;
  state.counters["homography_rms_px"] = HomographyRms(image, found);
}
BENCHMARK(BM_DetectorChoiceLibapriltag)->ArgName("grow_white")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
