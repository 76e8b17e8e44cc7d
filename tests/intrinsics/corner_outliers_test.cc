// intrinsics/corner_outliers.h: a gross error goes, a region the model misfits stays, a blurred
// view keeps its corners, and the warning names the border.
#include "splinecal/intrinsics/corner_outliers.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <vector>

namespace splinecal {
namespace {

// 40 views of 100 corners spread over a 640 x 480 image with Gaussian errors of sigma 0.3 px.
std::vector<ViewErrors> NoisyViews(std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> u(0.0, 640.0), v(0.0, 480.0);
  std::vector<ViewErrors> views(40);
  for (ViewErrors& view : views) {
    for (int i = 0; i < 100; ++i) {
      view.uv.emplace_back(u(*rng), v(*rng));
      view.error.emplace_back(noise(*rng), noise(*rng));
    }
  }
  return views;
}

TEST(CornerOutliers, GrossErrorGoesMisfitRegionAndBlurredViewStay) {
  std::mt19937 rng(3);
  std::vector<ViewErrors> views = NoisyViews(&rng);
  // One view is blurred: errors 4x larger everywhere in it.
  for (Eigen::Vector2d& e : views[7].error) e *= 4.0;
  // The model misfits the top-left cell: every corner there is 3 px off in the same direction
  // (10 sigma: a camera-wide 5-sigma test would remove all of them).
  int misfit = 0;
  for (ViewErrors& view : views) {
    for (size_t i = 0; i < view.uv.size(); ++i) {
      if (view.uv[i].x() < 80.0 && view.uv[i].y() < 60.0) {
        view.error[i] += Eigen::Vector2d(3.0, -2.0);
        ++misfit;
      }
    }
  }
  ASSERT_GE(misfit, 40);  // enough for the cell's median (kMinCellCorners)
  // One gross error (a mislabelled corner) in the image centre.
  views[20].uv[5] = Eigen::Vector2d(320.0, 240.0);
  views[20].error[5] = Eigen::Vector2d(8.0, 0.0);
  const CornerOutliers out = FindCornerOutliers(views, 640, 480, 5.0);
  EXPECT_TRUE(out.outlier[20][5]);
  int removed_misfit = 0;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < views[v].uv.size(); ++i) {
      if (views[v].uv[i].x() < 80.0 && views[v].uv[i].y() < 60.0 && out.outlier[v][i]) {
        ++removed_misfit;
      }
    }
  }
  EXPECT_EQ(removed_misfit, 0);
  int removed_blurred = 0;
  for (bool o : out.outlier[7]) removed_blurred += o ? 1 : 0;
  // 5 sigma of Gaussian noise: an outlier in 1 of ~270,000 corners by chance.
  EXPECT_EQ(removed_blurred, 0);
  EXPECT_EQ(out.removed, 1);
  EXPECT_TRUE(CornerOutlierWarning("cam0", "pinhole-radtan", out).empty());  // 1 of 4000
}

TEST(CornerOutliers, NoRemovalWithZeroSigmasButUnprojectableCornersGo) {
  std::mt19937 rng(4);
  std::vector<ViewErrors> views = NoisyViews(&rng);
  views[0].error[0] = Eigen::Vector2d(100.0, 0.0);
  views[1].error[0] = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  const CornerOutliers out = FindCornerOutliers(views, 640, 480, 0.0);
  EXPECT_FALSE(out.outlier[0][0]);
  EXPECT_TRUE(out.outlier[1][0]);
  EXPECT_EQ(out.removed, 1);
}

TEST(CornerOutliers, WarningNamesTheBorder) {
  CornerOutliers out;
  out.corners = 10000;
  out.removed = 12;
  out.removed_at_border = 11;
  const std::string warning = CornerOutlierWarning("cam1", "pinhole-radtan", out);
  EXPECT_NE(warning.find("cam1: 12 of 10000 corners"), std::string::npos) << warning;
  EXPECT_NE(warning.find("pinhole-radtan likely misfits the border (try pinhole-equi or ds-none"),
            std::string::npos)
      << warning;
  out.removed_at_border = 3;  // scattered and few: no warning
  EXPECT_TRUE(CornerOutlierWarning("cam1", "pinhole-radtan", out).empty());
}

}  // namespace
}  // namespace splinecal
