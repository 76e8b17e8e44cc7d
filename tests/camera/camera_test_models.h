// One camera per supported model (and the wide-angle cases) with the directions each is tested
// at: on the optical axis, 1e-9 rad off it, mid field and the edge of its field (beyond 90
// degrees for the wide-angle models). Shared by the camera model tests.
#ifndef SPLINECAL_TESTS_CAMERA_CAMERA_TEST_MODELS_H_
#define SPLINECAL_TESTS_CAMERA_CAMERA_TEST_MODELS_H_

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "calib/camera_test_scene.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

struct TestCamera {
  std::string label;  // model name plus the case
  Camera camera;
  double max_angle_deg;  // the edge of the field the tests use (from the optical axis)
};

inline Camera MakeCamera(ProjectionModel projection,
                         DistortionModel distortion,
                         const IntrinsicsVector& intrinsics,
                         int width,
                         int height) {
  Camera c;
  c.projection = projection;
  c.distortion = distortion;
  c.set_intrinsics(intrinsics);
  c.width = width;
  c.height = height;
  return c;
}

// TUM-VI's published equidistant calibration of its 195 degree cam0 (512 x 512).
inline Camera TumViEquidistant() {
  IntrinsicsVector k;
  k << 190.97847715128717, 190.9733070521226, 254.93170605935475, 256.8974428996504, 0.0, 0.0,
      0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202, 0.00020293673591811182,
      0.0;
  return MakeCamera(ProjectionModel::kPinhole, DistortionModel::kEquidistant, k, 512, 512);
}

// basalt's published double-sphere calibration of EuRoC cam0.
inline Camera EurocDoubleSphere() {
  IntrinsicsVector k;
  k << 349.7560023, 348.7245423, 365.8944076, 249.3299557, -0.2409573942, 0.5669968992, 0.0, 0.0,
      0.0, 0.0, 0.0;
  return MakeCamera(ProjectionModel::kDoubleSphere, DistortionModel::kNone, k, 752, 480);
}

inline std::vector<TestCamera> AllTestCameras() {
  std::vector<TestCamera> cameras;
  Camera euroc = EurocCamera();
  Camera none = euroc;
  none.distortion = DistortionModel::kNone;
  none.distortion_coeffs.setZero();
  cameras.push_back({"pinhole-none", none, 50.0});
  cameras.push_back({"pinhole-radtan (EuRoC cam0)", euroc, 50.0});
  Camera k3 = euroc;
  k3.distortion_coeffs(4) = -0.0125;
  k3.radtan_k3 = true;
  cameras.push_back({"pinhole-radtan with k3", k3, 50.0});
  cameras.push_back({"pinhole-equi (TUM-VI)", TumViEquidistant(), 80.0});
  IntrinsicsVector k;
  k << 270.2, 269.8, 320.4, 239.6, 0.0, 0.0, 0.92, 0.0, 0.0, 0.0, 0.0;
  cameras.push_back({"pinhole-fov",
                     MakeCamera(ProjectionModel::kPinhole, DistortionModel::kFov, k, 640, 480),
                     80.0});
  k << 420.0, 419.5, 256.3, 255.8, 1.8, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  cameras.push_back({"omni-none (wide, xi > 1)",
                     MakeCamera(ProjectionModel::kOmni, DistortionModel::kNone, k, 512, 512),
                     115.0});
  k << 820.0, 818.5, 366.8, 248.9, 0.8, 0.0, -0.05, 0.01, 2.0e-4, -1.0e-4, 0.0;
  cameras.push_back({"omni-radtan",
                     MakeCamera(ProjectionModel::kOmni, DistortionModel::kRadTan, k, 752, 480),
                     60.0});
  k << 460.1, 459.2, 366.3, 249.1, 0.59, 1.1, 0.0, 0.0, 0.0, 0.0, 0.0;
  cameras.push_back(
      {"eucm-none", MakeCamera(ProjectionModel::kEucm, DistortionModel::kNone, k, 752, 480), 60.0});
  k << 158.5, 158.4, 255.9, 256.2, 0.63, 1.04, 0.0, 0.0, 0.0, 0.0, 0.0;
  cameras.push_back({"eucm-none (wide)",
                     MakeCamera(ProjectionModel::kEucm, DistortionModel::kNone, k, 512, 512),
                     120.0});
  cameras.push_back({"ds-none (EuRoC cam0)", EurocDoubleSphere(), 60.0});
  k << 125.3, 125.2, 256.1, 255.4, -0.18, 0.59, 0.0, 0.0, 0.0, 0.0, 0.0;
  cameras.push_back(
      {"ds-none (wide, a 190 degree image circle)",
       MakeCamera(ProjectionModel::kDoubleSphere, DistortionModel::kNone, k, 512, 512),
       120.0});
  return cameras;
}

// The point at polar angle theta from the optical axis, azimuth phi [rad], distance d [m].
inline Eigen::Vector3d PointAt(double theta, double phi, double d) {
  return d * Eigen::Vector3d(
                 std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
}

// On the axis exactly, 1e-9 rad off it, and 0.3, 0.7 and 1.0 of the way to max_angle_deg at
// several azimuths and distances.
inline std::vector<Eigen::Vector3d> TestPoints(const TestCamera& c) {
  const double max = c.max_angle_deg * kDegToRad;
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d(0.0, 0.0, 1.7), PointAt(1e-9, 0.4, 1.0)};
  const double phis[] = {0.3, 1.9, 3.6, 5.2};
  const double distances[] = {0.6, 2.5};
  int i = 0;
  for (double fraction : {0.3, 0.7, 1.0}) {
    for (double phi : phis) points.push_back(PointAt(fraction * max, phi, distances[i++ % 2]));
  }
  return points;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CAMERA_CAMERA_TEST_MODELS_H_
