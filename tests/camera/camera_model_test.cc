#include "splinecal/camera/camera_model.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "calib/camera_test_scene.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

// Analytic vs Ridders-extrapolated Jacobians: Ridders reaches ~1e-10 relative on these smooth
// maps; pixels are O(100..1000) and their derivatives O(1..1e3), so 1e-6 absolute leaves a
// margin of 100x over the numeric error while catching any wrong term.
constexpr double kJacobianTolerance = 1e-6;
// Project(Unproject(uv)) returns uv to the unprojection's Newton tolerance (1e-14 normalised,
// i.e. ~1e-11 px) plus rounding.
constexpr double kRoundTripTolerancePx = 1e-9;

PinholeCamera EurocRadTan() { return testing::EurocCamera(); }

PinholeCamera TumViEquidistant() {
  PinholeCamera c;
  c.fu = 190.97847715128717;
  c.fv = 190.9733070521226;
  c.pu = 254.93170605935475;
  c.pv = 256.8974428996504;
  c.distortion = DistortionModel::kEquidistant;
  c.distortion_coeffs << 0.0034823894022493434, 0.0007150348452162257, -0.0020532361418706202,
      0.00020293673591811182;
  c.width = 512;
  c.height = 512;
  return c;
}

PinholeCamera Undistorted() {
  PinholeCamera c = EurocRadTan();
  c.distortion = DistortionModel::kNone;
  c.distortion_coeffs.setZero();
  return c;
}

std::vector<PinholeCamera> AllCameras() {
  return {Undistorted(), EurocRadTan(), TumViEquidistant()};
}

// Points from the optical axis (exactly, and 1e-9 off it) to wide angles.
std::vector<Eigen::Vector3d> TestPoints(const PinholeCamera& camera) {
  std::vector<Eigen::Vector3d> points = {
      {0.0, 0.0, 2.0}, {1e-9, -2e-9, 1.0}, {0.1, -0.05, 1.5}, {-0.4, 0.3, 1.2}, {0.3, 0.25, 0.8}};
  if (camera.distortion == DistortionModel::kEquidistant) {
    points.push_back({1.5, -1.0, 0.7});  // ~68 degrees off the axis
  }
  return points;
}

TEST(PinholeCamera, ProjectPointJacobianMatchesNumeric) {
  for (const PinholeCamera& camera : AllCameras()) {
    for (const Eigen::Vector3d& p : TestPoints(camera)) {
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, 3> J;
      ASSERT_TRUE(camera.Project(p, &uv, &J, nullptr));
      testutil::RiddersOptions options;
      options.initial_step = 1e-3;
      const Eigen::MatrixXd J_num = testutil::RiddersJacobian(
          [&](const Eigen::Vector3d& q) -> Eigen::Vector2d {
            Eigen::Vector2d out;
            CHECK(camera.Project(q, &out));
            return out;
          },
          p,
          options);
      EXPECT_LT((J - J_num).cwiseAbs().maxCoeff(), kJacobianTolerance)
          << DistortionModelName(camera.distortion) << " at " << p.transpose() << "\n"
          << J << "\nvs\n"
          << J_num;
    }
  }
}

TEST(PinholeCamera, ProjectIntrinsicsJacobianMatchesNumeric) {
  for (const PinholeCamera& camera : AllCameras()) {
    for (const Eigen::Vector3d& p : TestPoints(camera)) {
      Eigen::Matrix<double, 2, kNumIntrinsics> J;
      ASSERT_TRUE(camera.Project(p, nullptr, nullptr, &J));
      testutil::RiddersOptions options;
      options.initial_step = 1e-3;
      const Eigen::MatrixXd J_num = testutil::RiddersJacobian(
          [&](const Eigen::VectorXd& intrinsics) -> Eigen::Vector2d {
            PinholeCamera c = camera;
            c.set_intrinsics(intrinsics);
            Eigen::Vector2d out;
            CHECK(c.Project(p, &out));
            return out;
          },
          camera.intrinsics(),
          options);
      EXPECT_LT((J - J_num).cwiseAbs().maxCoeff(), kJacobianTolerance)
          << DistortionModelName(camera.distortion) << " at " << p.transpose() << "\n"
          << J << "\nvs\n"
          << J_num;
    }
  }
}

TEST(PinholeCamera, JetProjectionMatchesAnalyticJacobians) {
  using Jet = ceres::Jet<double, 11>;  // 3 point + 8 intrinsics
  for (const PinholeCamera& camera : AllCameras()) {
    for (const Eigen::Vector3d& p : TestPoints(camera)) {
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, 3> J_p;
      Eigen::Matrix<double, 2, kNumIntrinsics> J_k;
      ASSERT_TRUE(camera.Project(p, &uv, &J_p, &J_k));
      Eigen::Matrix<Jet, 3, 1> p_jet;
      for (int i = 0; i < 3; ++i) p_jet(i) = Jet(p(i), i);
      Jet intrinsics[kNumIntrinsics];
      const IntrinsicsVector k = camera.intrinsics();
      for (int i = 0; i < kNumIntrinsics; ++i) intrinsics[i] = Jet(k(i), 3 + i);
      Eigen::Matrix<Jet, 2, 1> uv_jet;
      ASSERT_TRUE(PinholeCamera::ProjectT(camera.distortion, intrinsics, p_jet, &uv_jet));
      for (int r = 0; r < 2; ++r) {
        EXPECT_NEAR(uv_jet(r).a, uv(r), 1e-12 * std::abs(uv(r)) + 1e-12);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(uv_jet(r).v(c), J_p(r, c), 1e-9);
        for (int c = 0; c < kNumIntrinsics; ++c) EXPECT_NEAR(uv_jet(r).v(3 + c), J_k(r, c), 1e-9);
      }
    }
  }
}

TEST(PinholeCamera, UnprojectInvertsProject) {
  for (const PinholeCamera& camera : AllCameras()) {
    for (const Eigen::Vector3d& p : TestPoints(camera)) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(camera.Project(p, &uv));
      Eigen::Vector3d ray;
      ASSERT_TRUE(camera.Unproject(uv, &ray)) << DistortionModelName(camera.distortion);
      EXPECT_EQ(ray.z(), 1.0);
      EXPECT_LT((ray - p / p.z()).norm(), 1e-10) << DistortionModelName(camera.distortion);
      Eigen::Vector2d uv_back;
      ASSERT_TRUE(camera.Project(ray, &uv_back));
      EXPECT_LT((uv_back - uv).norm(), kRoundTripTolerancePx);
    }
  }
}

TEST(PinholeCamera, UnprojectJacobiansMatchNumeric) {
  for (const PinholeCamera& camera : AllCameras()) {
    for (const Eigen::Vector3d& p : TestPoints(camera)) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(camera.Project(p, &uv));
      Eigen::Matrix<double, 3, 2> J_uv;
      Eigen::Matrix<double, 3, kNumIntrinsics> J_k;
      ASSERT_TRUE(camera.Unproject(uv, nullptr, &J_uv, &J_k));
      testutil::RiddersOptions options;
      options.initial_step = 1e-2;
      const Eigen::MatrixXd J_uv_num = testutil::RiddersJacobian(
          [&](const Eigen::Vector2d& q) -> Eigen::Vector3d {
            Eigen::Vector3d ray;
            CHECK(camera.Unproject(q, &ray));
            return ray;
          },
          uv,
          options);
      // Normalised coordinates per pixel are ~1/f ~ 2e-3: scale the tolerance accordingly.
      EXPECT_LT((J_uv - J_uv_num).cwiseAbs().maxCoeff(), 1e-9)
          << DistortionModelName(camera.distortion) << "\n"
          << J_uv << "\nvs\n"
          << J_uv_num;
      options.initial_step = 1e-4;
      const Eigen::MatrixXd J_k_num = testutil::RiddersJacobian(
          [&](const Eigen::VectorXd& intrinsics) -> Eigen::Vector3d {
            PinholeCamera c = camera;
            c.set_intrinsics(intrinsics);
            Eigen::Vector3d ray;
            CHECK(c.Unproject(uv, &ray));
            return ray;
          },
          camera.intrinsics(),
          options);
      EXPECT_LT((J_k - J_k_num).cwiseAbs().maxCoeff(), 1e-8)
          << DistortionModelName(camera.distortion) << "\n"
          << J_k << "\nvs\n"
          << J_k_num;
    }
  }
}

TEST(PinholeCamera, RefusesPointsBehindTheCamera) {
  const PinholeCamera camera = EurocRadTan();
  Eigen::Vector2d uv(7.0, 7.0);
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0.1, 0.2, -1.0), &uv));
  EXPECT_FALSE(camera.Project(Eigen::Vector3d(0.1, 0.2, 0.0), &uv));
  EXPECT_EQ(uv, Eigen::Vector2d(7.0, 7.0));  // untouched
}

TEST(PinholeCamera, DistortionFoldsBackFarOutside) {
  // r (1 + k1 r^2) with k1 = -0.5 turns at r = sqrt(2/3) ~ 0.816 (EuRoC's cam0 never folds:
  // 1 + 3 k1 r^2 + 5 k2 r^4 has no real root for its k1, k2).
  PinholeCamera camera = EurocRadTan();
  camera.distortion_coeffs << -0.5, 0.0, 0.0, 0.0;
  EXPECT_TRUE(camera.IsDistortionMonotonic(0.3, 0.2));
  EXPECT_TRUE(camera.IsDistortionMonotonic(0.8, 0.0));
  EXPECT_FALSE(camera.IsDistortionMonotonic(0.83, 0.0));
  EXPECT_FALSE(camera.IsDistortionMonotonic(1.0, 0.5));
}

TEST(PinholeCamera, InImageUsesPixelCentres) {
  const PinholeCamera camera = EurocRadTan();
  EXPECT_TRUE(camera.InImage(Eigen::Vector2d(0.0, 0.0)));
  EXPECT_TRUE(camera.InImage(Eigen::Vector2d(751.0, 479.0)));
  EXPECT_FALSE(camera.InImage(Eigen::Vector2d(751.5, 10.0)));
  EXPECT_FALSE(camera.InImage(Eigen::Vector2d(10.0, -0.1)));
}

TEST(DistortionModelName, KalibrSpelling) {
  EXPECT_EQ(DistortionModelName(DistortionModel::kNone), "none");
  EXPECT_EQ(DistortionModelName(DistortionModel::kRadTan), "radtan");
  EXPECT_EQ(DistortionModelName(DistortionModel::kEquidistant), "equidistant");
}

}  // namespace
}  // namespace splinecal
