// The lens model that places missed AprilGrid tags (src/detect/division_model.h): its inverse, and
// its fit to tags seen through a known division model and through a pinhole.
#include "../../src/detect/division_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/calib3d.hpp>

namespace splinecal {
namespace {

constexpr double kHalfDiagonalSq = 0.25 * (640.0 * 640.0 + 480.0 * 480.0);

TEST(DivisionModel, DistortUndoesUndistortInsideThePole) {
  for (double kappa : {-1.5, -0.3, 0.0, 0.2}) {
    DivisionModel model;
    model.centre = cv::Point2d(319.5, 239.5);
    model.lambda = kappa / kHalfDiagonalSq;
    // The pole of kappa = -1.5 lies 0.82 half diagonals (327 px) from the centre.
    for (const cv::Point2d& p : {cv::Point2d(40, 120), cv::Point2d(600, 400), cv::Point2d(320, 240),
                                 cv::Point2d(100, 450)}) {
      cv::Point2d u, back;
      ASSERT_TRUE(model.Undistort(p, &u)) << kappa;
      ASSERT_TRUE(model.Distort(u, &back)) << kappa;
      EXPECT_NEAR(back.x, p.x, 1e-9) << kappa;
      EXPECT_NEAR(back.y, p.y, 1e-9) << kappa;
    }
  }
  DivisionModel barrel;
  barrel.centre = cv::Point2d(319.5, 239.5);
  barrel.lambda = -1.5 / kHalfDiagonalSq;
  cv::Point2d u;
  EXPECT_FALSE(barrel.Undistort(cv::Point2d(0, 0), &u));  // 400 px out: beyond the pole
}

// The tags of a 6 x 6 grid seen by a homography, then through a division model of kappa (or none):
// the fit finds kappa, and with no distortion keeps lambda at 0.
std::vector<GridTag> TagsThrough(const CalibrationTarget& target, const DivisionModel& lens) {
  cv::Matx33d H(120.0, 25.0, 90.0, -15.0, 110.0, 60.0, 0.02, 0.05, 1.0);  // a tilted view
  const double pitch = 1.0 + target.tag_spacing_ratio;
  std::vector<GridTag> tags;
  for (int id = 0; id < target.grid_cols * target.grid_rows; ++id) {
    GridTag tag;
    tag.id = id;
    for (int k = 0; k < 4; ++k) {
      const cv::Point2d q = TagCorner(target, id, k, pitch);
      const cv::Vec3d m = H * cv::Vec3d(q.x, q.y, 1.0);
      if (!lens.Distort(cv::Point2d(m[0] / m[2], m[1] / m[2]), &tag.corners[k])) ADD_FAILURE();
    }
    tags.push_back(tag);
  }
  return tags;
}

TEST(DivisionModel, FitFindsTheLensOfTheTagsAndNoneForAPinhole) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  for (double kappa : {-1.2, -0.4, 0.0}) {
    DivisionModel truth;
    truth.centre = cv::Point2d(319.5, 239.5);
    truth.lambda = kappa / kHalfDiagonalSq;
    const DivisionModel fitted = FitDivisionModel(target, TagsThrough(target, truth), {640, 480});
    EXPECT_NEAR(fitted.lambda * kHalfDiagonalSq, kappa, 1e-3) << kappa;
  }
}

TEST(DivisionModel, TooFewTagsKeepTheHomography) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  DivisionModel truth;
  truth.centre = cv::Point2d(319.5, 239.5);
  truth.lambda = -1.0 / kHalfDiagonalSq;
  std::vector<GridTag> tags = TagsThrough(target, truth);
  tags.resize(kMinTagsForDivisionModel - 1);
  EXPECT_EQ(FitDivisionModel(target, tags, {640, 480}).lambda, 0.0);
}

}  // namespace
}  // namespace splinecal
