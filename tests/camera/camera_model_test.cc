#include "splinecal/camera/camera_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "camera/camera_test_models.h"
#include "testing/project_t.h"

namespace splinecal {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

// Project(UnprojectToBearing(uv)) returns uv to the inversions' accuracy (Newton to 1e-14
// normalised, closed forms to rounding), i.e. ~1e-11 px; 1e-9 px leaves rounding margin at
// wide angles, where a pixel spans more of the bearing.
constexpr double kRoundTripTolerancePx = 1e-9;
// A bearing recovered from a pixel: the projections' inverses lose at most ~1e-13 rad to
// rounding at these angles (a pixel is ~1e-3 rad).
constexpr double kBearingTolerance = 1e-10;

TEST(CameraModelName, KalibrNamesOfTheEightModels) {
  const std::vector<std::string> names = {"pinhole-none",
                                          "pinhole-radtan",
                                          "pinhole-equi",
                                          "pinhole-fov",
                                          "omni-none",
                                          "omni-radtan",
                                          "eucm-none",
                                          "ds-none"};
  for (const std::string& name : names) {
    ProjectionModel p = ProjectionModel::kEucm;
    DistortionModel d = DistortionModel::kFov;
    ASSERT_TRUE(ParseCameraModelName(name, &p, &d)) << name;
    EXPECT_EQ(CameraModelName(p, d), name);
    EXPECT_TRUE(IsSupportedCameraModel(p, d)) << name;
  }
  EXPECT_EQ(SupportedCameraModelNames(),
            "pinhole-none, pinhole-radtan, pinhole-equi, pinhole-fov, omni-none, omni-radtan, "
            "eucm-none, ds-none");
}

TEST(CameraModelName, RefusesEverythingElse) {
  for (const std::string name : {"pinhole",
                                 "pinhole-equidistant",
                                 "omni-equi",
                                 "ds-radtan",
                                 "eucm-fov",
                                 "Pinhole-radtan",
                                 "pinhole-radtan ",
                                 "double-sphere",
                                 ""}) {
    ProjectionModel p = ProjectionModel::kOmni;
    DistortionModel d = DistortionModel::kFov;
    EXPECT_FALSE(ParseCameraModelName(name, &p, &d)) << name;
    EXPECT_EQ(p, ProjectionModel::kOmni);  // untouched
    EXPECT_EQ(d, DistortionModel::kFov);
  }
  EXPECT_FALSE(IsSupportedCameraModel(ProjectionModel::kDoubleSphere, DistortionModel::kRadTan));
  EXPECT_FALSE(IsSupportedCameraModel(ProjectionModel::kOmni, DistortionModel::kEquidistant));
}

TEST(CameraModelName, KalibrSpellingOfTheParts) {
  EXPECT_EQ(ProjectionModelName(ProjectionModel::kPinhole), "pinhole");
  EXPECT_EQ(ProjectionModelName(ProjectionModel::kOmni), "omni");
  EXPECT_EQ(ProjectionModelName(ProjectionModel::kEucm), "eucm");
  EXPECT_EQ(ProjectionModelName(ProjectionModel::kDoubleSphere), "ds");
  EXPECT_EQ(DistortionModelName(DistortionModel::kNone), "none");
  EXPECT_EQ(DistortionModelName(DistortionModel::kRadTan), "radtan");
  EXPECT_EQ(DistortionModelName(DistortionModel::kEquidistant), "equidistant");
  EXPECT_EQ(DistortionModelName(DistortionModel::kFov), "fov");
}

Camera WithModel(ProjectionModel p, DistortionModel d, bool k3 = false) {
  Camera c;
  c.projection = p;
  c.distortion = d;
  c.radtan_k3 = k3;
  return c;
}

TEST(Camera, ActiveIntrinsicsPerModel) {
  using P = ProjectionModel;
  using D = DistortionModel;
  EXPECT_THAT(WithModel(P::kPinhole, D::kNone).ActiveIntrinsics(), ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(WithModel(P::kPinhole, D::kRadTan).ActiveIntrinsics(),
              ElementsAre(0, 1, 2, 3, 6, 7, 8, 9));
  EXPECT_THAT(WithModel(P::kPinhole, D::kRadTan, true).ActiveIntrinsics(),
              ElementsAre(0, 1, 2, 3, 6, 7, 8, 9, 10));
  EXPECT_THAT(WithModel(P::kPinhole, D::kEquidistant).ActiveIntrinsics(),
              ElementsAre(0, 1, 2, 3, 6, 7, 8, 9));
  EXPECT_THAT(WithModel(P::kPinhole, D::kFov).ActiveIntrinsics(), ElementsAre(0, 1, 2, 3, 6));
  EXPECT_THAT(WithModel(P::kOmni, D::kNone).ActiveIntrinsics(), ElementsAre(0, 1, 2, 3, 4));
  EXPECT_THAT(WithModel(P::kOmni, D::kRadTan).ActiveIntrinsics(),
              ElementsAre(0, 1, 2, 3, 4, 6, 7, 8, 9));
  EXPECT_THAT(WithModel(P::kEucm, D::kNone).ActiveIntrinsics(), ElementsAre(0, 1, 2, 3, 4, 5));
  EXPECT_THAT(WithModel(P::kDoubleSphere, D::kNone).ActiveIntrinsics(),
              ElementsAre(0, 1, 2, 3, 4, 5));
}

TEST(Camera, InactiveIntrinsicsHaveZeroJacobianColumns) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const std::vector<int> active = c.camera.ActiveIntrinsics();
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      Eigen::Matrix<double, 2, kNumIntrinsics> J;
      ASSERT_TRUE(c.camera.Project(p, nullptr, nullptr, &J)) << c.label;
      for (int i = 0; i < kNumIntrinsics; ++i) {
        const bool is_active = std::find(active.begin(), active.end(), i) != active.end();
        // radtan's k3 acts whether or not it is estimated.
        const bool acts = is_active || (c.camera.distortion == DistortionModel::kRadTan && i == 10);
        if (!acts) {
          EXPECT_EQ(J.col(i).norm(), 0.0) << c.label << " column " << i;
        }
      }
    }
  }
}

TEST(Camera, IntrinsicsVectorRoundTrip) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    Camera copy;
    copy.set_intrinsics(c.camera.intrinsics());
    EXPECT_EQ(copy.intrinsics(), c.camera.intrinsics()) << c.label;
    EXPECT_EQ(copy.projection_params, c.camera.projection_params);
    EXPECT_EQ(copy.distortion_coeffs, c.camera.distortion_coeffs);
  }
}

TEST(Camera, IsValidNamesTheProblem) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    std::string error;
    EXPECT_TRUE(c.camera.IsValid(&error)) << c.label << ": " << error;
  }
  struct Case {
    Camera camera;
    const char* problem;
  };
  std::vector<Case> cases;
  Camera c = testing::EurocDoubleSphere();
  c.projection_params(1) = 1.2;
  cases.push_back({c, "ds alpha"});
  c = testing::EurocDoubleSphere();
  c.projection_params(0) = -1.0;
  cases.push_back({c, "ds xi"});
  c = testing::EurocDoubleSphere();
  c.fu = 0.0;
  cases.push_back({c, "focal lengths"});
  c = testing::EurocDoubleSphere();
  c.distortion = DistortionModel::kRadTan;
  cases.push_back({c, "unsupported camera model ds-radtan"});
  c = WithModel(ProjectionModel::kEucm, DistortionModel::kNone);
  c.projection_params << -0.1, 1.0;
  cases.push_back({c, "eucm alpha"});
  c.projection_params << 0.5, 0.0;
  cases.push_back({c, "eucm beta"});
  c = WithModel(ProjectionModel::kOmni, DistortionModel::kNone);
  c.projection_params << -0.5, 0.0;
  cases.push_back({c, "omni xi"});
  c = WithModel(ProjectionModel::kPinhole, DistortionModel::kFov);
  c.distortion_coeffs(0) = 4.0;
  cases.push_back({c, "fov w"});
  c = WithModel(ProjectionModel::kPinhole, DistortionModel::kNone);
  c.pu = std::nan("");
  cases.push_back({c, "finite"});
  for (const Case& bad : cases) {
    std::string error;
    EXPECT_FALSE(bad.camera.IsValid(&error)) << bad.problem;
    EXPECT_THAT(error, HasSubstr(bad.problem));
  }
}

TEST(Camera, UnprojectToBearingInvertsProject) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(c.camera.Project(p, &uv)) << c.label << " at " << p.transpose();
      Eigen::Vector3d bearing;
      ASSERT_TRUE(c.camera.UnprojectToBearing(uv, &bearing))
          << c.label << " at " << p.transpose() << " -> " << uv.transpose();
      EXPECT_NEAR(bearing.norm(), 1.0, 1e-15);
      EXPECT_LT((bearing - p.normalized()).norm(), kBearingTolerance)
          << c.label << " at " << p.transpose();
      Eigen::Vector2d uv_back;
      ASSERT_TRUE(c.camera.Project(bearing, &uv_back));
      EXPECT_LT((uv_back - uv).norm(), kRoundTripTolerancePx) << c.label;
    }
  }
}

TEST(Camera, UnprojectGivesTheRayWithinNinetyDegrees) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    for (const Eigen::Vector3d& p : testing::TestPoints(c)) {
      Eigen::Vector2d uv;
      ASSERT_TRUE(c.camera.Project(p, &uv));
      Eigen::Vector3d ray(7.0, 7.0, 7.0);
      if (p.z() <= 0.0) {
        EXPECT_FALSE(c.camera.Unproject(uv, &ray)) << c.label << " at " << p.transpose();
        EXPECT_EQ(ray, Eigen::Vector3d(7.0, 7.0, 7.0));  // untouched
        continue;
      }
      ASSERT_TRUE(c.camera.Unproject(uv, &ray)) << c.label << " at " << p.transpose();
      EXPECT_EQ(ray.z(), 1.0);
      EXPECT_LT((ray - p / p.z()).norm(), kBearingTolerance * ray.squaredNorm()) << c.label;
    }
  }
}

TEST(Camera, WideAngleModelsSeeBeyondNinetyDegrees) {
  // The wide-angle cameras of the test set project a point 100 degrees off the axis into their
  // image (a 200 degree field of view along its diagonal) and unproject it back.
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    if (c.max_angle_deg < 100.0) continue;
    const Eigen::Vector3d p = testing::PointAt(100.0 * kDegToRad, 0.8, 1.5);
    Eigen::Vector2d uv;
    ASSERT_TRUE(c.camera.Project(p, &uv)) << c.label;
    EXPECT_TRUE(c.camera.InImage(uv)) << c.label << ": " << uv.transpose();
    EXPECT_TRUE(c.camera.IsDistortionMonotonic(p)) << c.label;
    Eigen::Vector3d bearing;
    ASSERT_TRUE(c.camera.UnprojectToBearing(uv, &bearing));
    EXPECT_LT((bearing - p.normalized()).norm(), kBearingTolerance) << c.label;
  }
}

// The border of each projection's valid region (camera/projection.h), as a polar angle [deg].
double RegionBorderDeg(const Camera& camera) {
  const Eigen::Vector2d& m = camera.projection_params;
  auto w_of = [](double alpha) { return alpha <= 0.5 ? alpha / (1 - alpha) : (1 - alpha) / alpha; };
  switch (camera.projection) {
    case ProjectionModel::kPinhole:
      return 90.0;
    case ProjectionModel::kOmni:
      return 90.0 + std::asin(m(0) <= 1.0 ? m(0) : 1.0 / m(0)) * kRadToDeg;
    case ProjectionModel::kEucm: {
      // z = -w sqrt(beta sin^2 + cos^2): tan(theta - 90 deg) = w sqrt(beta) / sqrt(1 - w^2).
      const double w = w_of(m(0));
      return 90.0 + std::atan(w * std::sqrt(m(1)) / std::sqrt(1.0 - w * w)) * kRadToDeg;
    }
    case ProjectionModel::kDoubleSphere: {
      const double w1 = w_of(m(1));
      const double w2 = (w1 + m(0)) / std::sqrt(2.0 * w1 * m(0) + m(0) * m(0) + 1.0);
      return 90.0 + std::asin(w2) * kRadToDeg;
    }
  }
  return 90.0;
}

TEST(Camera, RefusesPointsOutsideTheValidRegion) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const double border = RegionBorderDeg(c.camera);
    for (double phi : {0.0, 1.1, 2.9, 4.4}) {
      Eigen::Vector2d uv(7.0, 7.0);
      Eigen::Matrix<double, 2, 3> J_p = Eigen::Matrix<double, 2, 3>::Constant(7.0);
      EXPECT_FALSE(
          c.camera.Project(testing::PointAt((border + 0.01) * kDegToRad, phi, 1.0), &uv, &J_p))
          << c.label << " border " << border;
      EXPECT_FALSE(c.camera.Project(Eigen::Vector3d(0.0, 0.0, -1.0), &uv)) << c.label;
      EXPECT_EQ(uv, Eigen::Vector2d(7.0, 7.0));  // untouched
      EXPECT_EQ(J_p, (Eigen::Matrix<double, 2, 3>::Constant(7.0)));
      // Just inside the border the projection is defined (wide-angle models only: a pinhole
      // camera's z > kMinDepth border is tested below).
      if (c.camera.projection != ProjectionModel::kPinhole) {
        EXPECT_TRUE(c.camera.Project(testing::PointAt((border - 0.01) * kDegToRad, phi, 1.0), &uv))
            << c.label << " border " << border;
      }
    }
    EXPECT_FALSE(c.camera.Project(Eigen::Vector3d::Zero(), nullptr)) << c.label;
  }
  const Camera pinhole = testing::EurocCamera();
  EXPECT_FALSE(pinhole.Project(Eigen::Vector3d(0.1, 0.2, Camera::kMinDepth), nullptr));
  EXPECT_TRUE(pinhole.Project(Eigen::Vector3d(0.1, 0.2, 2.0 * Camera::kMinDepth), nullptr));
}

TEST(Camera, ProjectTAgreesOnTheValidRegion) {
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const IntrinsicsVector k = c.camera.intrinsics();
    const double border = RegionBorderDeg(c.camera);
    for (double theta : {0.5 * border, border - 0.01, border + 0.01, 179.0}) {
      const Eigen::Vector3d p = testing::PointAt(theta * kDegToRad, 0.7, 1.0);
      Eigen::Vector2d uv, uv_t;
      const bool analytic = c.camera.Project(p, &uv);
      const bool templated =
          testing::ProjectT(c.camera.projection, c.camera.distortion, k.data(), p, &uv_t);
      EXPECT_EQ(analytic, templated) << c.label << " at " << theta << " deg";
      if (analytic && templated) {
        EXPECT_LT((uv - uv_t).norm(), 1e-9) << c.label;
      }
    }
  }
}

TEST(Camera, DistortionFoldsBackFarOutside) {
  // r (1 + k1 r^2) with k1 = -0.5 turns at r = sqrt(2/3) ~ 0.816 (EuRoC's cam0 never folds:
  // 1 + 3 k1 r^2 + 5 k2 r^4 has no real root for its k1, k2).
  Camera camera = testing::EurocCamera();
  camera.distortion_coeffs << -0.5, 0.0, 0.0, 0.0, 0.0;
  EXPECT_TRUE(camera.IsDistortionMonotonic(0.3, 0.2));
  EXPECT_TRUE(camera.IsDistortionMonotonic(0.8, 0.0));
  EXPECT_FALSE(camera.IsDistortionMonotonic(0.83, 0.0));
  EXPECT_FALSE(camera.IsDistortionMonotonic(1.0, 0.5));
  // The 3-D form agrees on the same rays, at any distance along them.
  EXPECT_TRUE(camera.IsDistortionMonotonic(Eigen::Vector3d(2.4, 0.0, 3.0)));
  EXPECT_FALSE(camera.IsDistortionMonotonic(Eigen::Vector3d(2.49, 0.0, 3.0)));
  // A folded pixel does not unproject: its preimage on the folded branch is refused.
  Eigen::Vector2d uv;
  ASSERT_TRUE(camera.Project(Eigen::Vector3d(0.9, 0.0, 1.0), &uv));
  Eigen::Vector3d ray;
  if (camera.Unproject(uv, &ray)) {
    EXPECT_LT(ray.x(), 0.8165);  // the unfolded preimage only
  }
}

TEST(Camera, OmniFoldsAtItsRegionBorder) {
  // Mei's model with xi > 1 is invertible up to z = -|p| / xi: det -> 0 at the border.
  const testing::TestCamera omni = testing::AllTestCameras()[5];
  ASSERT_EQ(omni.camera.projection, ProjectionModel::kOmni);
  const double border = RegionBorderDeg(omni.camera);
  EXPECT_TRUE(
      omni.camera.IsDistortionMonotonic(testing::PointAt((border - 1.0) * kDegToRad, 0.3, 1.0)));
  EXPECT_FALSE(
      omni.camera.IsDistortionMonotonic(testing::PointAt((border + 1.0) * kDegToRad, 0.3, 1.0)));
}

TEST(Camera, InImageUsesPixelCentres) {
  const Camera camera = testing::EurocCamera();
  EXPECT_TRUE(camera.InImage(Eigen::Vector2d(0.0, 0.0)));
  EXPECT_TRUE(camera.InImage(Eigen::Vector2d(751.0, 479.0)));
  EXPECT_FALSE(camera.InImage(Eigen::Vector2d(751.5, 10.0)));
  EXPECT_FALSE(camera.InImage(Eigen::Vector2d(10.0, -0.1)));
}

TEST(Camera, PixelsWithoutPreimageDoNotUnproject) {
  // The double sphere's lift needs (2 alpha - 1) r^2 <= 1: far outside the image there is none.
  const Camera ds = testing::EurocDoubleSphere();
  Eigen::Vector3d bearing;
  EXPECT_FALSE(ds.UnprojectToBearing(Eigen::Vector2d(ds.pu + 5.0 * ds.fu, ds.pv), &bearing));
  EXPECT_FALSE(ds.UnprojectToBearing(Eigen::Vector2d(std::nan(""), 1.0), &bearing));
  // TUM-VI's equidistant camera is a pinhole one: beyond 90 degrees there is no ray.
  const Camera equi = testing::TumViEquidistant();
  EXPECT_FALSE(
      equi.UnprojectToBearing(Eigen::Vector2d(equi.pu + 1.7 * equi.fu, equi.pv), &bearing));
}

}  // namespace
}  // namespace splinecal
