// Recall of the AprilGrid detector through a fisheye: EuRoC's 6 x 6 grid of 8.8 cm tags rendered
// (tests/detect/render_aprilgrid.h) through a 512 x 512 double-sphere lens of about 190 degrees,
// like TUM-VI's cameras, at 0.3-0.8 m, from the image's centre to 65 degrees off the optical axis,
// facing the lens' axis or turned 40 degrees. Near the image's edge the lens bends the grid's rows
// by pixels over one tag: the tags the tag search misses there are placed through the frame's
// division model (src/detect/division_model.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "detect/render_aprilgrid.h"
#include "detect/rendered_recording.h"
#include "splinecal/detect/target_detector.h"

namespace splinecal {
namespace {

struct ViewCount {
  int truth = 0;
  int found = 0;
};

TEST(FisheyeRecall, TagsBentByTheLensArePlacedThroughItsDivisionModel) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const Camera camera = testing::TumViLikeFisheye();
  const testing::AprilGridTexture texture(target, 4);
  const testing::PlanarViewRenderer renderer(camera, texture);
  Eigen::Vector3d grid_centre = Eigen::Vector3d::Zero();
  for (const auto& [id, p] : target.points) grid_centre += p / 144.0;
  TargetDetector detector(target);
  std::vector<double> errors;
  int truth_corners = 0, wrong_ids = 0;
  ViewCount close_and_bent;  // 0.3 m, 30 degrees off the axis, facing the axis
  uint32_t seed = 0;
  for (double depth : {0.3, 0.5, 0.8}) {
    for (double off_axis_deg : {0.0, 30.0, 50.0, 65.0}) {
      for (double tilt_deg : {0.0, 40.0}) {
        const double off = off_axis_deg * M_PI / 180.0;
        const Eigen::Vector3d direction =
            Eigen::Vector3d(std::sin(off), 0.3 * std::sin(off), std::cos(off)).normalized();
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(tilt_deg * M_PI / 180.0, Eigen::Vector3d(0.6, 0.8, 0.0))
                .toRotationMatrix() *
            Eigen::AngleAxisd(0.4 * seed, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
            Eigen::Vector3d(1, -1, -1).asDiagonal();  // the printed side faces the camera
        const Eigen::Vector3d t = depth * direction - R * grid_centre;
        std::vector<Observation> corners;
        for (const auto& [id, p] : target.points) {
          Observation o;
          o.point_id = id;
          if ((R * p + t).z() > 0.05 && camera.Project(R * p + t, &o.uv) && camera.InImage(o.uv)) {
            corners.push_back(o);
          }
        }
        if (corners.size() < 20) continue;
        const GrayImage image = renderer.Render(corners, target, 0.5, 2.0, seed++);
        std::map<int64_t, Eigen::Vector2d> found;
        for (const CornerDetection& c : detector.Detect(image.view()).corners) {
          found[c.point_id] = c.uv;
        }
        int found_here = 0;
        for (const Observation& o : corners) {
          ++truth_corners;
          const auto it = found.find(o.point_id);
          if (it == found.end()) continue;
          ++found_here;
          const double error = (it->second - o.uv).norm();
          errors.push_back(error);
          for (const Observation& other : corners) {
            wrong_ids += other.point_id != o.point_id && (it->second - other.uv).norm() < error;
          }
        }
        if (depth == 0.3 && off_axis_deg == 30.0 && tilt_deg == 0.0) {
          close_and_bent = {static_cast<int>(corners.size()), found_here};
        }
      }
    }
  }
  ASSERT_FALSE(errors.empty());
  std::sort(errors.begin(), errors.end());
  const int off = static_cast<int>(
      errors.end() - std::upper_bound(errors.begin(), errors.end(), 1.0));
  std::printf("fisheye: %zu of %d corners, median error %.4f px, %d more than 1 px off (max %.2f), "
              "%d wrong ids; 0.3 m, 30 deg off the axis: %d of %d\n",
              errors.size(), truth_corners, errors[errors.size() / 2], off, errors.back(),
              wrong_ids, close_and_bent.found, close_and_bent.truth);
  // Measured: 2,501 of 3,273 corners (76.4%), median 0.013 px, 4 more than 1 px off (max 2.26,
  // on tags pressed to a few pixels across at 50 degrees off the axis), no wrong id; the close
  // view 135 of 144. With the homography alone (the detector before the division model): 2,274
  // (69.5%), 9 more than 1 px off, one wrong id, and 103 of 144, the outer ring of tags lost.
  // The bounds sit between the two.
  EXPECT_GE(errors.size(), 0.72 * truth_corners);
  EXPECT_GE(close_and_bent.found, 130);
  EXPECT_EQ(wrong_ids, 0);
  EXPECT_LE(off, 0.005 * errors.size());
  EXPECT_LE(errors[errors.size() / 2], 0.05);
}

}  // namespace
}  // namespace splinecal
