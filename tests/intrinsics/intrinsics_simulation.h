// Simulated target views for the intrinsics tests: a rig of cameras with known intrinsics and
// T_cn_c0 looks at an AprilGrid from random poses; every corner that projects inside an image
// becomes an observation with Gaussian pixel noise. The target may be bowed, or printed off its
// file's layout in its plane (IntrinsicsScene::shape).
#ifndef SPLINECAL_TESTS_INTRINSICS_INTRINSICS_SIMULATION_H_
#define SPLINECAL_TESTS_INTRINSICS_INTRINSICS_SIMULATION_H_

#include <Eigen/Core>
#include <array>
#include <random>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/lie/se3.h"

namespace splinecal {
namespace testing {

struct IntrinsicsScene {
  std::vector<Camera> cameras;  // the truth
  std::vector<SE3d> T_cn_c0;    // identity first
  CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  int views = 60;
  double sigma_px = 0.3;
  // Target poses: the target's centre on the optical axis of camera 0 at this distance range,
  // shifted sideways by up to `spread` times the distance, tilted by up to max_tilt_deg about
  // a random axis in the target plane.
  double min_distance_m = 0.5;
  double max_distance_m = 1.2;
  double spread = 0.4;
  double max_tilt_deg = 45.0;
  // The target's true geometry (target_deformation.h): out of plane or in plane; as the file
  // says by default.
  TargetDeformationKind shape_kind = TargetDeformationKind::kNone;
  std::array<double, kMaxTargetDeformationSize> shape{};
  // In-plane-per-view: each view's inset d_v (empty: 0; else one per view).
  std::vector<double> view_inset;
};

// The observations of `scene` drawn with `seed`, in (t_ns, cam_id, point_id) order. Views are
// 50 ms apart from t = 1 s; a corner is kept when it projects inside the image with a margin
// of 2 px in every camera that sees it.
inline std::vector<Observation> SimulateIntrinsicsViews(const IntrinsicsScene& scene,
                                                        int seed,
                                                        std::vector<SE3d>* T_c0_t = nullptr) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, scene.sigma_px);
  // The target's centre (tags of 0.088 m, 6 x 6 with 0.3 spacing: 0.6424 m wide).
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& [id, p] : scene.target.points) centre += p;
  centre /= static_cast<double>(scene.target.points.size());
  const TargetShape shape = MakeTargetShape(scene.target, scene.shape_kind);
  std::vector<Observation> observations;
  for (int v = 0; v < scene.views; ++v) {
    const double distance =
        scene.min_distance_m +
        0.5 * (uniform(rng) + 1.0) * (scene.max_distance_m - scene.min_distance_m);
    const Eigen::Vector3d axis(uniform(rng), uniform(rng), 0.0);
    const double tilt = scene.max_tilt_deg * M_PI / 180.0 * std::abs(uniform(rng));
    const Eigen::Vector3d twist(0.0, 0.0, 0.3 * uniform(rng));
    // The target faces the camera (its z axis towards -z of the camera: a flip about x).
    const SO3d R = SO3d::Exp(axis.normalized() * tilt) * SO3d::Exp(Eigen::Vector3d(M_PI, 0, 0)) *
                   SO3d::Exp(twist);
    const Eigen::Vector3d position(
        scene.spread * distance * uniform(rng), scene.spread * distance * uniform(rng), distance);
    const SE3d T = SE3d(R, position - (R * centre));
    if (T_c0_t != nullptr) T_c0_t->push_back(T);
    const int64_t t_ns = 1'000'000'000 + 50'000'000LL * v;
    const double inset = scene.view_inset.empty() ? 0.0 : scene.view_inset[v];
    for (size_t n = 0; n < scene.cameras.size(); ++n) {
      const Camera& camera = scene.cameras[n];
      const SE3d T_cn_t = scene.T_cn_c0[n] * T;
      for (const auto& [id, p_t] : scene.target.points) {
        Eigen::Vector2d uv;
        if (!camera.Project(T_cn_t * shape.Deform(p_t, scene.shape.data(), inset), &uv)) continue;
        if (uv.x() < 2 || uv.y() < 2 || uv.x() > camera.width - 3 || uv.y() > camera.height - 3) {
          continue;
        }
        Observation o;
        o.t_ns = t_ns;
        o.cam_id = static_cast<int>(n);
        o.point_id = id;
        o.uv = uv + Eigen::Vector2d(noise(rng), noise(rng));
        observations.push_back(o);
      }
    }
  }
  return observations;
}

// EuRoC's cam0 as Kalibr published it (pinhole-radtan).
inline Camera EurocCam0() {
  Camera camera;
  camera.distortion = DistortionModel::kRadTan;
  camera.fu = 458.654;
  camera.fv = 457.296;
  camera.pu = 367.215;
  camera.pv = 248.375;
  camera.distortion_coeffs.head<4>() << -0.28340811, 0.07395907, 0.00019359, 1.76187114e-05;
  camera.width = 752;
  camera.height = 480;
  return camera;
}

// EuRoC's cam0 alone before the file's AprilGrid, 40 views (the scene of the target-shape tests).
inline IntrinsicsScene EurocCam0Scene() {
  IntrinsicsScene scene;
  scene.cameras = {EurocCam0()};
  scene.T_cn_c0 = {SE3d()};
  scene.views = 40;
  return scene;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_INTRINSICS_INTRINSICS_SIMULATION_H_
