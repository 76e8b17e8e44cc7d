// estimation/view_clusters.h: a view's cluster is its corners' image cell (3 x 3 grid) times the
// quadrant its target tilts towards; the normal's sign (which side of the board faces the camera)
// does not matter. And in CalibrateIntrinsics: on simulated views the covariance over view
// clusters is not taken when the model is exact, and is when the lens has a distortion the model
// lacks.
#include "splinecal/estimation/view_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

Camera ImageOf752x480() {
  Camera camera;
  camera.width = 752;
  camera.height = 480;
  return camera;
}

// Four corners around (u, v), 10 px apart.
std::vector<TargetCornerObservation> CornersAround(double u, double v) {
  std::vector<TargetCornerObservation> corners(4);
  corners[0].uv = {u - 5.0, v - 5.0};
  corners[1].uv = {u + 5.0, v - 5.0};
  corners[2].uv = {u - 5.0, v + 5.0};
  corners[3].uv = {u + 5.0, v + 5.0};
  return corners;
}

// A target 1 m ahead, turned about the camera's x and y axes [rad].
SE3d TiltedTarget(double about_x, double about_y) {
  return SE3d(SO3d::Exp(Eigen::Vector3d(about_x, about_y, 0.0)), Eigen::Vector3d(0.0, 0.0, 1.0));
}

TEST(ViewClusters, EachCellAndTiltDirectionIsItsOwnCluster) {
  const Camera camera = ImageOf752x480();
  std::set<int> clusters;
  for (double u : {100.0, 376.0, 700.0}) {
    for (double v : {60.0, 240.0, 420.0}) {
      for (double about_x : {-0.4, 0.4}) {
        for (double about_y : {-0.4, 0.4}) {
          clusters.insert(ViewCluster(camera, CornersAround(u, v), TiltedTarget(about_x, about_y)));
        }
      }
    }
  }
  EXPECT_EQ(clusters.size(), 36u);
  EXPECT_EQ(*clusters.begin(), 0);
  EXPECT_EQ(*clusters.rbegin(), 35);
}

TEST(ViewClusters, TheBoardsSideAndTheImageEdgeDoNotChangeTheCluster) {
  const Camera camera = ImageOf752x480();
  const SE3d front = TiltedTarget(0.3, -0.2);
  // The same plane seen from its back: the normal flips, the tilt direction does not.
  const SE3d back(front.so3() * SO3d::Exp(Eigen::Vector3d(kPi, 0.0, 0.0)), front.translation());
  EXPECT_EQ(ViewCluster(camera, CornersAround(200.0, 300.0), front),
            ViewCluster(camera, CornersAround(200.0, 300.0), back));
  // A centroid on the last column and row belongs to the last cell.
  EXPECT_EQ(ViewCluster(camera, CornersAround(752.0, 480.0), front) / 4,
            kViewClusterCells * kViewClusterCells - 1);
}

// EuRoC's cam0 with radtan's k3 = `k3` (pinhole-radtan fits k1 k2 p1 p2 only), 200 views from
// 0.5-0.8 m, fitted as pinhole-radtan: where each std comes from.
IntrinsicsCameraResult FitWithK3(double k3) {
  testing::IntrinsicsScene scene;
  scene.cameras = {testing::EurocCam0()};
  scene.cameras[0].distortion_coeffs(4) = k3;
  scene.T_cn_c0 = {SE3d()};
  scene.views = 200;
  scene.min_distance_m = 0.5;
  scene.max_distance_m = 0.8;
  IntrinsicsCameraSpec spec;
  spec.camera.distortion = DistortionModel::kRadTan;
  spec.camera.width = 752;
  spec.camera.height = 480;
  IntrinsicsOptions options;
  options.solver.num_threads = 1;
  return CalibrateIntrinsics(testing::SimulateIntrinsicsViews(scene, 11), scene.target, {spec},
                             options)
      .cameras[0];
}

TEST(ViewClusters, TakenForAModelMisfitNotForAnExactModel) {
  // Exact model: the sandwich over view clusters is noise around the noise model's covariance
  // and stays below its significance bar (measured: every std from the noise model).
  const IntrinsicsCameraResult exact = FitWithK3(0.0);
  EXPECT_EQ(std::count(exact.std_from.begin(), exact.std_from.end(), "view clusters"), 0);
  // k3 = 0.01 bends the image's corners by ~4 px that k1 and k2 absorb differently in each
  // region: the view clusters pull apart (measured: fu, fv, pu, k1, k2 from them, k1's std
  // 4.83e-4 against the exact model's 1.37e-4).
  const IntrinsicsCameraResult misfit = FitWithK3(0.01);
  EXPECT_GE(std::count(misfit.std_from.begin(), misfit.std_from.end(), "view clusters"), 3);
  EXPECT_GT(misfit.intrinsics_std(6), 2.0 * exact.intrinsics_std(6));
}

}  // namespace
}  // namespace splinecal
