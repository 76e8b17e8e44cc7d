// The analytic Jacobians of Camera::Project and Camera::Unproject against automatic
// differentiation through testing::ProjectT and against central differences, for every model at
// points on the optical axis, 1e-9 rad off it, mid field and at the edge of the field (beyond 90
// degrees for the wide-angle models); and the series branches near singular points against the
// closed forms just outside them.
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "camera/camera_test_models.h"
#include "splinecal/camera/camera_model.h"
#include "testing/numeric_diff.h"
#include "testing/project_t.h"

namespace splinecal {
namespace {

// Automatic and analytic derivatives are both exact up to rounding: entries agree to ~1e-13
// relative; 1e-10 relative to the largest entry leaves margin for the cancellation the header
// comments bound (~1e-11 absolute in the radial models' s'(r)/r near their series thresholds).
constexpr double kAutodiffTolerance = 1e-10;
// Central differences with step h = 1e-5 (absolute; coordinates and intrinsics are O(1e-5) to
// O(500)): truncation h^2/6 |f'''| with |f'''| up to ~1e4 px at the wide-angle edges (~2e-7 px),
// rounding eps |uv| / h ~ 1e-8 px. Against Jacobian entries of O(1..1e3) px per unit, 1e-6
// relative to the largest entry (plus 1e-6 absolute) is well above both and far below any wrong
// term (a missing factor changes entries by O(1) relative).
constexpr double kFiniteDifferenceStep = 1e-5;
constexpr double kFiniteDifferenceTolerance = 1e-6;

double Scale(const Eigen::MatrixXd& J) { return std::max(1.0, J.cwiseAbs().maxCoeff()); }

// |J - J_reference| <= relative_tolerance * Scale(J) entrywise, printing both when not.
void ExpectJacobianNear(const Eigen::MatrixXd& J,
                        const Eigen::MatrixXd& J_reference,
                        double relative_tolerance,
                        const std::string& what) {
  EXPECT_LT((J - J_reference).cwiseAbs().maxCoeff(), relative_tolerance * Scale(J)) << what << "\n"
                                                                                    << J << "\nvs\n"
                                                                                    << J_reference;
}

std::string Where(const testing::TestCamera& c, const Eigen::Vector3d& p) {
  std::ostringstream where;
  where << c.label << " at " << p.transpose();
  return where.str();
}

// The pixel of p (or the ray (x, y, 1) of uv) with the camera's intrinsics replaced: the
// functions the central differences differentiate.
Eigen::Vector2d PixelOf(Camera camera,
                        const Eigen::VectorXd& intrinsics,
                        const Eigen::Vector3d& p) {
  camera.set_intrinsics(intrinsics);
  Eigen::Vector2d uv;
  CHECK(camera.Project(p, &uv));
  return uv;
}

Eigen::Vector3d RayOf(Camera camera, const Eigen::VectorXd& intrinsics, const Eigen::Vector2d& uv) {
  camera.set_intrinsics(intrinsics);
  Eigen::Vector3d ray;
  CHECK(camera.Unproject(uv, &ray));
  return ray;
}

using Jet = ceres::Jet<double, 3 + kNumIntrinsics>;

// uv and its derivatives with respect to (p_c, intrinsics) by ceres::Jet through ProjectT.
bool AutodiffProject(const Camera& camera,
                     const Eigen::Vector3d& p,
                     Eigen::Vector2d* uv,
                     Eigen::Matrix<double, 2, 3>* J_p,
                     Eigen::Matrix<double, 2, kNumIntrinsics>* J_k) {
  Eigen::Matrix<Jet, 3, 1> p_jet;
  for (int i = 0; i < 3; ++i) p_jet(i) = Jet(p(i), i);
  Jet intrinsics[kNumIntrinsics];
  const IntrinsicsVector k = camera.intrinsics();
  for (int i = 0; i < kNumIntrinsics; ++i) intrinsics[i] = Jet(k(i), 3 + i);
  Eigen::Matrix<Jet, 2, 1> uv_jet;
  if (!testing::ProjectT(camera.projection, camera.distortion, intrinsics, p_jet, &uv_jet)) {
    return false;
  }
  for (int r = 0; r < 2; ++r) {
    (*uv)(r) = uv_jet(r).a;
    J_p->row(r) = uv_jet(r).v.head<3>().transpose();
    J_k->row(r) = uv_jet(r).v.tail<kNumIntrinsics>().transpose();
  }
  return true;
}

TEST(CameraJacobians, ProjectMatchesAutodiff) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      Eigen::Vector2d uv, uv_auto;
      Eigen::Matrix<double, 2, 3> J_p, J_p_auto;
      Eigen::Matrix<double, 2, kNumIntrinsics> J_k, J_k_auto;
      ASSERT_TRUE(c.camera.Project(p, &uv, &J_p, &J_k)) << c.label;
      ASSERT_TRUE(AutodiffProject(c.camera, p, &uv_auto, &J_p_auto, &J_k_auto)) << c.label;
      EXPECT_LT((uv - uv_auto).norm(), 1e-12 * uv.norm()) << c.label;
      ExpectJacobianNear(J_p, J_p_auto, kAutodiffTolerance, Where(c, p) + ", d uv / d p");
      ExpectJacobianNear(J_k, J_k_auto, kAutodiffTolerance, Where(c, p) + ", d uv / d intrinsics");
    }
  }
}

TEST(CameraJacobians, ProjectMatchesCentralDifferences) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const IntrinsicsVector k = c.camera.intrinsics();
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      Eigen::Matrix<double, 2, 3> J_p;
      Eigen::Matrix<double, 2, kNumIntrinsics> J_k;
      ASSERT_TRUE(c.camera.Project(p, nullptr, &J_p, &J_k)) << c.label;
      const Eigen::MatrixXd J_p_num = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector3d& q) { return PixelOf(c.camera, k, q); },
          p,
          kFiniteDifferenceStep);
      const Eigen::MatrixXd J_k_num = testing::CentralDifferenceJacobian(
          [&](const Eigen::VectorXd& moved) { return PixelOf(c.camera, moved, p); },
          k,
          kFiniteDifferenceStep);
      ExpectJacobianNear(J_p, J_p_num, kFiniteDifferenceTolerance, Where(c, p) + ", d uv / d p");
      ExpectJacobianNear(
          J_k, J_k_num, kFiniteDifferenceTolerance, Where(c, p) + ", d uv / d intrinsics");
    }
  }
}

TEST(CameraJacobians, UnprojectJacobiansMatchCentralDifferences) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const IntrinsicsVector k = c.camera.intrinsics();
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      if (p.z() <= 0.0) continue;  // no ray (x, y, 1) there
      Eigen::Vector2d uv;
      ASSERT_TRUE(c.camera.Project(p, &uv));
      Eigen::Matrix<double, 3, 2> J_uv;
      Eigen::Matrix<double, 3, kNumIntrinsics> J_k;
      ASSERT_TRUE(c.camera.Unproject(uv, nullptr, &J_uv, &J_k)) << c.label;
      // Steps: 1e-3 px on uv; the ray is O(1..10) with third derivatives O(1e-6) per px^3, so
      // central differences are good to ~1e-12 (rounding eps |ray| / h ~ 1e-12 too). The
      // entries are ~1/f ~ 1e-3: the tolerance is relative to the largest, not to 1.
      const Eigen::MatrixXd J_uv_num = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector2d& q) { return RayOf(c.camera, k, q); }, uv, 1e-3);
      EXPECT_LT((J_uv - J_uv_num).cwiseAbs().maxCoeff(), 1e-6 * J_uv.cwiseAbs().maxCoeff())
          << Where(c, p) << "\n"
          << J_uv << "\nvs\n"
          << J_uv_num;
      // 1e-6 on the intrinsics: rounding eps |ray| / h ~ 1e-9 against entries up to O(1).
      const Eigen::MatrixXd J_k_num = testing::CentralDifferenceJacobian(
          [&](const Eigen::VectorXd& moved) { return RayOf(c.camera, moved, uv); }, k, 1e-6);
      ExpectJacobianNear(J_k, J_k_num, 1e-6, Where(c, p) + ", d ray / d intrinsics");
    }
  }
}

// A camera of `model` with coefficients d (the series tests).
Camera RadialCamera(DistortionModel model, const DistortionCoeffs& d) {
  Camera c = testing::EurocCamera();
  c.distortion = model;
  c.distortion_coeffs = d;
  return c;
}

// Value and Jacobians just inside and just outside a series threshold agree to the series'
// truncation (< 1e-15 relative at these thresholds) plus the closed forms' rounding near it.
void ExpectContinuousAcross(const Camera& inside,
                            const Eigen::Vector3d& p_inside,
                            const Camera& outside,
                            const Eigen::Vector3d& p_outside,
                            const char* what) {
  Eigen::Vector2d uv_in, uv_out;
  Eigen::Matrix<double, 2, 3> J_p_in, J_p_out;
  Eigen::Matrix<double, 2, kNumIntrinsics> J_k_in, J_k_out;
  ASSERT_TRUE(inside.Project(p_inside, &uv_in, &J_p_in, &J_k_in));
  ASSERT_TRUE(outside.Project(p_outside, &uv_out, &J_p_out, &J_k_out));
  // The two points (or cameras) differ by ~1e-12 relative; uv and J change by that much.
  EXPECT_LT((uv_in - uv_out).norm(), 1e-9) << what;
  EXPECT_LT((J_p_in - J_p_out).cwiseAbs().maxCoeff(), 1e-6 * Scale(J_p_in)) << what;
  EXPECT_LT((J_k_in - J_k_out).cwiseAbs().maxCoeff(), 1e-6 * Scale(J_k_in)) << what;
}

TEST(CameraJacobians, SeriesBranchesJoinTheClosedForms) {
  DistortionCoeffs equi;
  equi << 0.0035, 0.0007, -0.0021, 0.0002, 0.0;
  DistortionCoeffs fov;
  fov << 0.92, 0.0, 0.0, 0.0, 0.0;
  // r^2 thresholds 1e-10: r = 1e-5 (1 - 1e-9) inside, 1e-5 (1 + 1e-9) outside.
  const Eigen::Vector3d p_in(0.6e-5 * (1 - 1e-9), 0.8e-5 * (1 - 1e-9), 1.0);
  const Eigen::Vector3d p_out(0.6e-5 * (1 + 1e-9), 0.8e-5 * (1 + 1e-9), 1.0);
  ExpectContinuousAcross(RadialCamera(DistortionModel::kEquidistant, equi),
                         p_in,
                         RadialCamera(DistortionModel::kEquidistant, equi),
                         p_out,
                         "equidistant r series");
  ExpectContinuousAcross(RadialCamera(DistortionModel::kFov, fov),
                         p_in,
                         RadialCamera(DistortionModel::kFov, fov),
                         p_out,
                         "fov r series");
  // w^2 threshold 1e-10: w = 1e-5 (1 -+ 1e-9), at a generic point.
  DistortionCoeffs w_in = fov, w_out = fov;
  w_in(0) = 1e-5 * (1 - 1e-9);
  w_out(0) = 1e-5 * (1 + 1e-9);
  const Eigen::Vector3d p(0.3, -0.2, 1.0);
  ExpectContinuousAcross(RadialCamera(DistortionModel::kFov, w_in),
                         p,
                         RadialCamera(DistortionModel::kFov, w_out),
                         p,
                         "fov w series");
}

TEST(CameraJacobians, FovWithTinyWMatchesAutodiffAndCentralDifferences) {
  // The w series branch (w^2 < 1e-10) with its own derivatives, w -> 0 is the pinhole camera.
  DistortionCoeffs d;
  d << 3e-6, 0.0, 0.0, 0.0, 0.0;
  const Camera camera = RadialCamera(DistortionModel::kFov, d);
  const Eigen::Vector3d p(0.3, -0.2, 1.0);
  Eigen::Vector2d uv, uv_auto;
  Eigen::Matrix<double, 2, 3> J_p, J_p_auto;
  Eigen::Matrix<double, 2, kNumIntrinsics> J_k, J_k_auto;
  ASSERT_TRUE(camera.Project(p, &uv, &J_p, &J_k));
  ASSERT_TRUE(AutodiffProject(camera, p, &uv_auto, &J_p_auto, &J_k_auto));
  ExpectJacobianNear(J_p, J_p_auto, kAutodiffTolerance, "fov, tiny w, d uv / d p");
  ExpectJacobianNear(J_k, J_k_auto, kAutodiffTolerance, "fov, tiny w, d uv / d intrinsics");
  // d uv / d w at w = 3e-6: fu x 2 w (1/12 - r^2/3) ~ 1e-4 px/rad; central differences in w
  // with a step of 1e-7 (below w, so both sides stay in the series branch).
  const Eigen::MatrixXd J_num = testing::CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& moved) { return PixelOf(camera, moved, p); },
      camera.intrinsics(),
      1e-7);
  EXPECT_LT((J_k.col(kDistortionCoeffsIndex) - J_num.col(kDistortionCoeffsIndex)).norm(), 1e-6);
}

}  // namespace
}  // namespace splinecal
