// intrinsics/corner_outliers.h: a gross error goes, a region the model misfits stays (also where
// the misfit is steep and sparse: the image's corners), a blurred view keeps its corners, and the
// warning names the border.
#include "splinecal/intrinsics/corner_outliers.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>
#include <string>
#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/target.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

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
  out.kept_misfit = 12;
  out.kept_misfit_at_border = 11;
  const std::string warning = CornerOutlierWarning("cam1", "pinhole-radtan", out);
  EXPECT_NE(warning.find("cam1: 12 of 10000 corners"), std::string::npos) << warning;
  EXPECT_NE(warning.find("kept: the model misfits them"), std::string::npos) << warning;
  EXPECT_NE(warning.find("pinhole-radtan likely misfits the border (try pinhole-equi or ds-none"),
            std::string::npos)
      << warning;
  out.kept_misfit_at_border = 3;  // scattered and few: no warning
  EXPECT_TRUE(CornerOutlierWarning("cam1", "pinhole-radtan", out).empty());
  // Removed corners are named once they are more than 1% of the camera's.
  out.removed = 101;
  const std::string removed = CornerOutlierWarning("cam1", "pinhole-radtan", out);
  EXPECT_NE(removed.find("101 of 10000 corners (1.0%) removed as outliers"), std::string::npos)
      << removed;
  EXPECT_EQ(removed.find("likely misfits"), std::string::npos) << removed;
}

// A model's misfit that grows steeply towards the image's corners, as radtan's does on EuRoC
// (docs/intrinsics.md, "Outliers"): 0 within 380 px of the centre, then outward, 8.7 px at the
// image's corner (446 px), too steep and too sparse for a cell median to absorb.
Eigen::Vector2d SteepBorderMisfit(const Eigen::Vector2d& uv) {
  const Eigen::Vector2d from_centre = uv - Eigen::Vector2d(376.0, 240.0);
  const double r = from_centre.norm();
  return r <= 380.0 ? Eigen::Vector2d::Zero()
                    : Eigen::Vector2d(0.002 * (r - 380.0) * (r - 380.0) * from_centre / r);
}

TEST(CornerOutliers, ASteepMisfitAtTheImageCornersStaysAGrossDetectionErrorGoes) {
  const Camera camera = testing::EurocCam0();
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<ViewErrors> views;
  for (int k = 0; k < 60; ++k) {
    // Poses that put the board anywhere in the image, some into its corners.
    const SE3d T_c_t(SO3d::Exp(Eigen::Vector3d(0.4 * unit(rng), 0.4 * unit(rng), unit(rng))),
                     Eigen::Vector3d(0.7 * unit(rng) - 0.3, 0.5 * unit(rng) - 0.3, 0.9));
    ViewErrors view;
    for (const auto& [id, p_t] : target.points) {
      Eigen::Vector2d uv;
      if (!camera.Project(T_c_t * p_t, &uv) || !camera.InImage(uv)) continue;
      const Eigen::Vector2d n(noise(rng), noise(rng));
      view.p_t.push_back(p_t);
      view.uv.push_back(uv + n);
      view.error.push_back(SteepBorderMisfit(uv) - n);  // predicted - observed
    }
    if (view.uv.size() >= 20) views.push_back(std::move(view));
  }
  // A corner detected 6 px off (a neighbouring tag's edge), in the image's middle.
  size_t gross_view = 0, gross_corner = 0;
  double best = 1e9;
  for (size_t v = 0; v < views.size(); ++v) {
    for (size_t i = 0; i < views[v].uv.size(); ++i) {
      const double d = (views[v].uv[i] - Eigen::Vector2d(376.0, 240.0)).norm();
      if (d < best) best = d, gross_view = v, gross_corner = i;
    }
  }
  views[gross_view].uv[gross_corner] += Eigen::Vector2d(6.0, 0.0);
  views[gross_view].error[gross_corner] -= Eigen::Vector2d(6.0, 0.0);
  int misfit = 0;
  for (const ViewErrors& view : views) {
    for (const Eigen::Vector2d& e : view.error) misfit += e.norm() > 3.0 ? 1 : 0;
  }
  ASSERT_GE(misfit, 10);  // the misfit is beyond 5 sigma of the noise at enough corners
  const CornerOutliers out = FindCornerOutliers(views, 752, 480, 5.0);
  EXPECT_TRUE(out.outlier[gross_view][gross_corner]);
  // Every other corner stays: the misfit's corners agree with their neighbours on the target,
  // and 5 sigma of Gaussian noise is crossed by chance in 1 of ~270,000 corners.
  EXPECT_EQ(out.removed, 1);
  EXPECT_GE(out.kept_misfit, misfit / 2);
  EXPECT_EQ(out.kept_misfit_at_border, out.kept_misfit);
  // The model test alone (no target coordinates) removes them: what the local test prevents.
  for (ViewErrors& view : views) view.p_t.clear();
  EXPECT_GE(FindCornerOutliers(views, 752, 480, 5.0).removed, misfit / 2);
}

}  // namespace
}  // namespace splinecal
