// intrinsics/local_corner_fit.h: through a strongly distorting lens the quadratic through a
// corner's neighbours predicts it closely, a displaced corner shows its displacement, and what
// cannot be judged is NaN.
#include "splinecal/intrinsics/local_corner_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/target.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace {

struct ProjectedView {
  std::vector<Eigen::Vector3d> p_t;
  std::vector<Eigen::Vector2d> uv;
};

// EuRoC's 6 x 6 AprilGrid, 0.9 m away, shifted so that it reaches into the image's top-right
// corner, where the distortion bends most; corners outside the image dropped (63 stay).
ProjectedView ViewIntoTheImageCorner() {
  const Camera camera = testing::EurocCam0();
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const SE3d T_c_t(SO3d(), Eigen::Vector3d(0.5, -0.9, 0.9));
  ProjectedView view;
  for (const auto& [id, p_t] : target.points) {
    Eigen::Vector2d uv;
    if (!camera.Project(T_c_t * p_t, &uv) || !camera.InImage(uv)) continue;
    view.p_t.push_back(p_t);
    view.uv.push_back(uv);
  }
  return view;
}

double RadiusFromCentre(const Eigen::Vector2d& uv) {
  return (uv - Eigen::Vector2d(376.0, 240.0)).norm();
}

TEST(LocalFitResiduals, SmallThroughTheDistortionAtTheImageCorner) {
  const ProjectedView view = ViewIntoTheImageCorner();
  ASSERT_GE(view.uv.size(), 60u);  // 63
  const std::vector<Eigen::Vector2d> residuals = LocalFitResiduals(view.p_t, view.uv);
  double farthest = 0.0;
  double largest = 0.0;
  int judged = 0;
  for (size_t i = 0; i < residuals.size(); ++i) {
    if (!residuals[i].allFinite()) continue;
    ++judged;
    farthest = std::max(farthest, RadiusFromCentre(view.uv[i]));
    largest = std::max(largest, residuals[i].norm());
  }
  // The view reaches the image's corner region (the corner is 446 px from the centre).
  EXPECT_GT(farthest, 400.0);
  EXPECT_EQ(judged, static_cast<int>(view.uv.size()));
  // Without noise what is left is the distortion's third-order term over one tag (header):
  // measured 0.067 px. The bound, 0.3 px, is below 1 sigma of EuRoC's corner noise (0.3-0.4 px):
  // the lens alone never brings a corner near the 5-sigma limit.
  EXPECT_LT(largest, 0.3);
}

TEST(LocalFitResiduals, ADisplacedCornerShowsItsDisplacement) {
  ProjectedView view = ViewIntoTheImageCorner();
  const std::vector<Eigen::Vector2d> clean = LocalFitResiduals(view.p_t, view.uv);
  const size_t k = view.uv.size() / 2;  // inside the board: interpolated
  const Eigen::Vector2d displacement(3.0, -2.0);
  view.uv[k] += displacement;
  const std::vector<Eigen::Vector2d> residuals = LocalFitResiduals(view.p_t, view.uv);
  // The corner's own fit leaves it out, so its residual moves by the whole displacement divided
  // by the prediction's noise gain sqrt(1 + h), which is between 1 and 2 inside the board (10
  // neighbours around the corner: h is a few tenths).
  const Eigen::Vector2d moved = residuals[k] - clean[k];
  EXPECT_NEAR(moved.x() / moved.y(), displacement.x() / displacement.y(), 1e-9);
  EXPECT_LE(moved.norm(), displacement.norm());
  EXPECT_GT(moved.norm(), 0.5 * displacement.norm());
  // Its neighbours see it as one of their 10 points: their residuals move, by less.
  for (size_t i = 0; i < residuals.size(); ++i) {
    if (i == k) continue;
    EXPECT_LT((residuals[i] - clean[i]).norm(), displacement.norm()) << i;
  }
}

TEST(LocalFitResiduals, NaNWhereNothingCanBeJudged) {
  ProjectedView view = ViewIntoTheImageCorner();
  // Too few corners for one fit.
  const std::vector<Eigen::Vector3d> few_p(view.p_t.begin(), view.p_t.begin() + 10);
  const std::vector<Eigen::Vector2d> few_uv(view.uv.begin(), view.uv.begin() + 10);
  for (const Eigen::Vector2d& r : LocalFitResiduals(few_p, few_uv)) EXPECT_FALSE(r.allFinite());
  // A point off the plane z = 0: not a planar target where it is.
  view.p_t[0].z() = 0.05;
  EXPECT_FALSE(LocalFitResiduals(view.p_t, view.uv)[0].allFinite());
  // Every corner on one line: the quadratic in the other direction is undetermined.
  std::vector<Eigen::Vector3d> line_p;
  std::vector<Eigen::Vector2d> line_uv;
  for (int i = 0; i < 20; ++i) {
    line_p.emplace_back(0.01 * i, 0.0, 0.0);
    line_uv.emplace_back(100.0 + 5.0 * i, 200.0);
  }
  for (const Eigen::Vector2d& r : LocalFitResiduals(line_p, line_uv)) EXPECT_FALSE(r.allFinite());
}

}  // namespace
}  // namespace splinecal
