// Recall of the AprilGrid detector on small and oblique tags, on real pixels: resampled copies of
// the two EuRoC frames (bundled in data/euroc_april_frames; tests/detect/warped_views.h) scaled to
// 0.35..1 and turned by up to 60 degrees, some blurred or noisy. Truth in a copy: the frame's own
// detected corners mapped through the homography that made the copy.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "detect/render_aprilgrid.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/target_yaml.h"
#include "testing/paths.h"
#include "warped_views.h"

namespace splinecal {
namespace {

constexpr char kFrames[] = "euroc_april_frames";

// A found corner farther than this from its truth is off: the truth is the frame's corner (about
// 0.1 px from the grid's homography) scaled down, and the medians of the refined corners' errors
// are 0.01..0.04 px on tags of 15 px and more (docs/detect.md). Its id is wrong when another
// corner of the grid is nearer than its own.
constexpr double kOffPx = 1.0;

// Bins of a tag's shortest side in the copy [px]; a corner counts in its tag's bin.
const std::vector<double> kBinEdges = {0, 10, 15, 20, 25, 30, 40, 1e9};

struct BinCount {
  int truth = 0;
  int found = 0;
  int off = 0;    // found farther than kOffPx from the truth, right id
  int wrong = 0;  // found nearer to another corner of the grid
  std::vector<double> errors;
};

struct RecallTable {
  std::vector<BinCount> bins = std::vector<BinCount>(kBinEdges.size() - 1);
  double seconds = 0;
  int views = 0;

  int Bin(double side) const {
    int b = 0;
    while (b + 2 < static_cast<int>(kBinEdges.size()) && side >= kBinEdges[b + 1]) ++b;
    return b;
  }
  // Corners of tags at least `min_side` px wide: found / truth, and those off.
  double Recall(double min_side, int* off) const {
    int truth = 0, found = 0;
    *off = 0;
    for (size_t b = 0; b < bins.size(); ++b) {
      if (kBinEdges[b] < min_side) continue;
      truth += bins[b].truth;
      found += bins[b].found;
      *off += bins[b].off;
    }
    return truth > 0 ? static_cast<double>(found) / truth : 0.0;
  }
  int WrongIds() const {
    int wrong = 0;
    for (const BinCount& bin : bins) wrong += bin.wrong;
    return wrong;
  }
  std::string Text() const {
    std::string text =
        "| shortest tag side [px] | corners | found | recall | more than 1 px off | wrong ids | "
        "median error [px] |\n|---|---|---|---|---|---|---|\n";
    for (size_t b = 0; b < bins.size(); ++b) {
      const BinCount& bin = bins[b];
      if (bin.truth == 0) continue;
      std::vector<double> e = bin.errors;
      double median = 0;
      if (!e.empty()) {
        std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
        median = e[e.size() / 2];
      }
      char line[200];
      const std::string range = kBinEdges[b + 1] > 1e8
                                    ? ">= " + std::to_string(static_cast<int>(kBinEdges[b]))
                                    : std::to_string(static_cast<int>(kBinEdges[b])) + " - " +
                                          std::to_string(static_cast<int>(kBinEdges[b + 1]));
      std::snprintf(line, sizeof(line), "| %s | %d | %d | %.1f%% | %d | %d | %.3f |\n",
                    range.c_str(), bin.truth, bin.found, 100.0 * bin.found / bin.truth, bin.off,
                    bin.wrong, median);
      text += line;
    }
    char line[120];
    std::snprintf(line, sizeof(line), "%d copies, %.1f ms per copy\n", views,
                  1e3 * seconds / std::max(1, views));
    return text + line;
  }
};

// The copies: scales 0.35..1 against tilts 0..60 degrees about axes of every direction, turned
// in the image, with a lens blur of 0.8 px or noise of 3 grey levels on every other copy.
std::vector<testing::ViewSpec> Specs() {
  const std::vector<double> scales = {0.35, 0.42, 0.5, 0.6, 0.75, 1.0};
  const std::vector<std::pair<double, double>> tilts = {{0, 0}, {35, 0}, {50, 90}, {60, 0},
                                                        {60, 90}, {45, 45}};
  std::vector<testing::ViewSpec> specs;
  uint32_t seed = 1;
  for (double scale : scales) {
    for (const auto& [tilt, axis] : tilts) {
      testing::ViewSpec spec;
      spec.scale = scale;
      spec.tilt_deg = tilt;
      spec.tilt_axis_deg = axis;
      spec.roll_deg = 37.0 * seed;  // every direction of the grid in the image
      spec.seed = seed;
      if (seed % 3 == 1) spec.blur_px = 0.8;
      if (seed % 3 == 2) spec.noise = 3.0;
      ++seed;
      specs.push_back(spec);
    }
  }
  return specs;
}

RecallTable MeasureRecall(const DetectorOptions& options) {
  const CalibrationTarget target =
      ReadTargetYaml(testing::BundledDataPath(std::string(kFrames) + "/aprilgrid.yaml"));
  TargetDetector detector(target, options);
  RecallTable table;
  for (int cam = 0; cam < 2; ++cam) {
    const GrayImage frame = ReadGrayImage(testing::BundledDataPath(
        std::string(kFrames) + "/cam" + std::to_string(cam) + "/data/1403709395937837056.png"));
    std::map<int64_t, Eigen::Vector2d> truth_frame;
    std::vector<Eigen::Vector2d> region;
    for (const CornerDetection& c : TargetDetector(target).Detect(frame.view()).corners) {
      truth_frame[c.point_id] = c.uv;
      region.push_back(c.uv);
    }
    EXPECT_EQ(truth_frame.size(), 144u);
    for (const testing::ViewSpec& spec : Specs()) {
      const testing::WarpedView view = testing::MakeWarpedView(frame.view(), region, spec);
      const auto start = std::chrono::steady_clock::now();
      const TargetDetection detection = detector.Detect(view.image.view());
      table.seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++table.views;
      std::map<int64_t, Eigen::Vector2d> found;
      for (const CornerDetection& c : detection.corners) found[c.point_id] = c.uv;
      // Each corner's bin: the shortest side of the tag(s) it belongs to in the copy. A corner
      // id r (2 cols) + c belongs to tag (r / 2) cols + c / 2.
      for (const auto& [id, uv] : truth_frame) {
        const int cols = 2 * target.grid_cols;
        const int r = static_cast<int>(id / cols), c = static_cast<int>(id % cols);
        const int r0 = r - r % 2, c0 = c - c % 2;  // the tag's corner 0
        const int64_t k[4] = {r0 * cols + c0, r0 * cols + c0 + 1, (r0 + 1) * cols + c0 + 1,
                              (r0 + 1) * cols + c0};
        double side = 1e9;
        bool complete = true;
        for (int i = 0; i < 4; ++i) {
          if (!truth_frame.count(k[i]) || !truth_frame.count(k[(i + 1) % 4])) {
            complete = false;
            continue;
          }
          side = std::min(side, (testing::Apply(view.H, truth_frame.at(k[i])) -
                                 testing::Apply(view.H, truth_frame.at(k[(i + 1) % 4])))
                                    .norm());
        }
        if (!complete) continue;
        BinCount& bin = table.bins[table.Bin(side)];
        ++bin.truth;
        const auto it = found.find(id);
        if (it == found.end()) continue;
        const Eigen::Vector2d truth = testing::Apply(view.H, uv);
        const double error = (it->second - truth).norm();
        bool nearer_other = false;
        for (const auto& [other, other_uv] : truth_frame) {
          nearer_other |= other != id &&
                          (it->second - testing::Apply(view.H, other_uv)).norm() < error;
        }
        if (nearer_other) {
          ++bin.wrong;
        } else if (error > kOffPx) {
          ++bin.off;
        } else {
          ++bin.found;
          bin.errors.push_back(error);
        }
      }
      // A corner whose id is not a corner of the grid at all is wrong too.
      for (const auto& [id, uv] : found) {
        if (!truth_frame.count(id)) ++table.bins.back().wrong;
      }
    }
  }
  return table;
}

TEST(AprilGridRecall, SmallAndObliqueTagsOfRealFramesAreFoundWithTheRightIds) {
  DetectorOptions fast;
  fast.effort = DetectEffort::kFast;
  const RecallTable before = MeasureRecall(fast);
  std::printf("effort fast:\n%s", before.Text().c_str());
  const RecallTable table = MeasureRecall(DetectorOptions{});
  std::printf("effort default:\n%s", table.Text().c_str());
  int off = 0;
  // Measured: 100% of the corners of tags of 20 px and more (fast: 87.6%), 99.4% of those of
  // 15 px and more (fast: 52.1%), 70.6% of 10-15 px ones, no wrong id at any size; none more
  // than 1 px off from 10 px (before the saddle blur was capped by the small square: 28 of the
  // 10-15 px bin's corners). The bounds (docs/detect.md, "Small and oblique tags"): 97% from
  // 15 px, 0 wrong ids, none more than 1 px off from 15 px and at most 3 from 10 px; 20 px and
  // up keeps the margin it had before the grid prediction (97%).
  const double recall_20 = table.Recall(20.0, &off);
  EXPECT_GE(recall_20, 0.97);
  EXPECT_EQ(off, 0);
  int off_15 = 0;
  const double recall_15 = table.Recall(15.0, &off_15);
  EXPECT_GE(recall_15, 0.97);
  EXPECT_EQ(off_15, 0);
  int off_10 = 0;
  table.Recall(10.0, &off_10);
  EXPECT_LE(off_10, 3);
  EXPECT_EQ(table.WrongIds(), 0);
  EXPECT_GT(recall_15, before.Recall(15.0, &off) + 0.3);
  RecordProperty("recall_20px", std::to_string(recall_20));
  RecordProperty("recall_15px", std::to_string(recall_15));
}

// Rendered grids (tests/detect/render_aprilgrid.h), where the corners are exact: tags of 20 px
// seen head-on and turned by up to 50 degrees (down to 13 px across), a lens blur of 0.5 px and
// noise of 2 grey levels, in a 640 x 480 pinhole camera.
TEST(AprilGridRecall, TwentyPixelTagsOfRenderedGridsGiveExactCorners) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  Camera camera;
  camera.fu = camera.fv = 460.0;
  camera.pu = 319.5;
  camera.pv = 239.5;
  camera.width = 640;
  camera.height = 480;
  const testing::AprilGridTexture texture(target, 4);
  const testing::PlanarViewRenderer renderer(camera, texture);
  // The distance at which a tag is 20 px wide head-on: f tagSize / 20.
  const double depth = camera.fu * target.tag_size_m / 20.0;
  Eigen::Vector3d grid_centre = Eigen::Vector3d::Zero();
  for (const auto& [id, p] : target.points) grid_centre += p / 144.0;
  TargetDetector detector(target);
  std::vector<double> errors;
  int truth_corners = 0, wrong_ids = 0;
  uint32_t seed = 0;
  for (const auto& [tilt_deg, axis_deg] : std::vector<std::pair<double, double>>{
           {0, 0}, {30, 0}, {30, 90}, {45, 45}, {50, 0}, {50, 135}}) {
    const double axis = axis_deg * M_PI / 180.0;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(tilt_deg * M_PI / 180.0,
                          Eigen::Vector3d(std::cos(axis), std::sin(axis), 0.0))
            .toRotationMatrix() *
        Eigen::AngleAxisd(0.4 * seed, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
        Eigen::Vector3d(1, -1, -1).asDiagonal();  // the printed side (target z) faces the camera
    // The grid's centre on the optical axis at `depth`, offset a little across the image.
    const Eigen::Vector3d t = Eigen::Vector3d(0.1 * std::sin(seed), 0.05, depth) - R * grid_centre;
    std::vector<Observation> corners;
    for (const auto& [id, p] : target.points) {
      Observation o;
      o.point_id = id;
      if (camera.Project(R * p + t, &o.uv)) corners.push_back(o);
    }
    ASSERT_EQ(corners.size(), 144u);
    const GrayImage image = renderer.Render(corners, target, 0.5, 2.0, seed++);
    std::map<int64_t, Eigen::Vector2d> found;
    for (const CornerDetection& c : detector.Detect(image.view()).corners) found[c.point_id] = c.uv;
    for (const Observation& o : corners) {
      ++truth_corners;
      if (!found.count(o.point_id)) continue;
      const double error = (found.at(o.point_id) - o.uv).norm();
      errors.push_back(error);
      for (const Observation& other : corners) {
        wrong_ids += other.point_id != o.point_id && (found.at(o.point_id) - other.uv).norm() < error;
      }
    }
  }
  ASSERT_FALSE(errors.empty());
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  const double p95 = errors[errors.size() * 95 / 100];
  std::printf("rendered 20 px tags: %zu of %d corners, median error %.4f px, 95%% %.4f px, max "
              "%.4f px\n", errors.size(), truth_corners, median, p95, errors.back());
  // Measured: 794 of 864 corners (92%; the tags turned by 45 and 50 degrees are 13-15 px
  // across), median 0.014 px, 95th percentile 0.090 px, max 0.33 px. Before the saddle blur was
  // capped by the small square (grid_prediction.cc): 779, 0.034, 0.52 and 1.23 px, a tail on
  // the small, strongly turned tags. The accuracy bound, 0.1 px, is on the median
  // (docs/detect.md, "Small and oblique tags", rendered grids); the tail is held at about twice
  // what was measured.
  EXPECT_LE(median, 0.1);
  EXPECT_LT(p95, 0.2);
  EXPECT_LT(errors.back(), 0.6);
  EXPECT_EQ(wrong_ids, 0);
  EXPECT_GE(errors.size(), 0.7 * truth_corners);
}

}  // namespace
}  // namespace splinecal
