// A small camera-on-spline scene shared by the reprojection and rolling-shutter tests: a random
// spline T_w_s around 1 m above a planar target, a camera looking down (R_s_c ~ Rx(pi)), a
// distorted pinhole camera (EuRoC's cam0 values) and Ceres parameter blocks for everything.
#ifndef SPLINECAL_TESTS_CALIB_CAMERA_TEST_SCENE_H_
#define SPLINECAL_TESTS_CALIB_CAMERA_TEST_SCENE_H_

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/target.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

inline Camera EurocCamera() {
  Camera c;
  c.fu = 458.654;
  c.fv = 457.296;
  c.pu = 367.215;
  c.pv = 248.375;
  c.distortion = DistortionModel::kRadTan;
  c.distortion_coeffs << -0.28340811, 0.07395907, 0.00019359, 1.76187114e-05, 0.0;
  c.width = 752;
  c.height = 480;
  return c;
}

struct CameraTestScene {
  Camera camera = EurocCamera();
  std::vector<std::array<double, 7>> poses;  // control-pose blocks T_w_s
  TrajectoryModel model = TrajectoryModel::kSE3;  // their interpolation
  std::array<double, 7> T_c_s{};
  double shift = 0.004;      // [s]
  double line_delay = 3e-5;  // [s/row]
  std::array<double, 7> T_w_t{};
  CalibrationTarget target = MakeAprilGrid(4, 4, 0.04, 0.3);
  double dt_s = 0.1;
  int64_t t0_ns = 0;

  // num_poses control poses at knot spacing dt, random rotations of ~0.15 rad and positions
  // within 0.1 m of (0, 0, 1); seeded.
  explicit CameraTestScene(unsigned seed = 7, int num_poses = 12) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (int i = 0; i < num_poses; ++i) {
      const Eigen::Vector3d phi(0.15 * normal(rng), 0.15 * normal(rng), 0.3 * normal(rng));
      const Eigen::Vector3d p(0.08 * normal(rng), 0.08 * normal(rng), 1.0 + 0.05 * normal(rng));
      std::array<double, 7> block;
      PoseToBlock(SE3d(SO3d::Exp(phi), p), block.data());
      poses.push_back(block);
    }
    // Camera looking down: R_s_c = Rx(pi) times a small rotation; a lever arm of a few cm.
    const SO3d R_c_s =
        SO3d::Exp(Eigen::Vector3d(0.02, -0.03, 0.01)) * SO3d::Exp(Eigen::Vector3d(kPi, 0.0, 0.0));
    PoseToBlock(SE3d(R_c_s, Eigen::Vector3d(0.05, -0.02, 0.01)), T_c_s.data());
    // Target centred below the spline, slightly rotated.
    PoseToBlock(
        SE3d(SO3d::Exp(Eigen::Vector3d(0.05, -0.02, 0.4)), Eigen::Vector3d(-0.1, -0.1, 0.0)),
        T_w_t.data());
  }

  SE3Splined Spline() const {
    std::vector<SE3d> control;
    for (const auto& block : poses) control.push_back(PoseFromBlock(block.data()));
    return SE3Splined(control, t0_ns, static_cast<int64_t>(std::llround(dt_s * 1e9)), model);
  }
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_CAMERA_TEST_SCENE_H_
