// Pixels of the pinhole models against an outside implementation: OpenCV's cv::projectPoints
// (radial-tangential with 4 coefficients and with k3, OpenCV's order k1 k2 p1 p2 k3) and
// cv::fisheye::projectPoints (Kannala-Brandt, Kalibr's equidistant), on EuRoC cam0's published
// intrinsics and on a wide-angle lens.
//
// Tolerance. Both sides evaluate the same polynomials in double precision, in different orders:
// they differ by a few ulps of the pixel (|uv| ~ 1e3 px, ulp ~ 1e-13 px), and OpenCV's fisheye
// code takes the distortion factor as 1 for r < 1e-8 where splinecal uses its series
// 1 + (k1 - 1/3) r^2 (a difference < 1e-16 relative). kOpenCvTolerancePx = 1e-9 px is 1e4 times
// that and 1e3 times below the smallest effect of swapping p1 and p2 at the tested off-axis
// points, which SwappedTangentialCoefficientsMoveThePixels checks.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "camera/camera_test_models.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/io/camchain_yaml.h"
#include "testing/paths.h"

namespace splinecal {
namespace {

constexpr double kOpenCvTolerancePx = 1e-9;
// Swapping p1 and p2 must move every tested off-axis pixel by at least this (1000x the
// tolerance), so that a swapped pair in splinecal cannot pass the comparison.
constexpr double kMinSwapEffectPx = 1e3 * kOpenCvTolerancePx;

// Points at polar angles up to max_angle_deg, several azimuths, 1.3 m away; the axis first.
std::vector<Eigen::Vector3d> ReferencePoints(double max_angle_deg) {
  std::vector<Eigen::Vector3d> points = {Eigen::Vector3d(0.0, 0.0, 1.3)};
  for (double fraction : {0.1, 0.35, 0.7, 1.0}) {
    for (double phi_deg : {10.0, 75.0, 140.0, 200.0, 290.0}) {
      points.push_back(
          testing::PointAt(fraction * max_angle_deg * kDegToRad, phi_deg * kDegToRad, 1.3));
    }
  }
  return points;
}

cv::Mat CameraMatrix(const Camera& camera) {
  return (cv::Mat_<double>(3, 3) << camera.fu,
          0.0,
          camera.pu,
          0.0,
          camera.fv,
          camera.pv,
          0.0,
          0.0,
          1.0);
}

std::vector<cv::Point3d> ToCv(const std::vector<Eigen::Vector3d>& points) {
  std::vector<cv::Point3d> out;
  for (const Eigen::Vector3d& p : points) out.emplace_back(p.x(), p.y(), p.z());
  return out;
}

// cv::projectPoints with the camera's first `count` radtan coefficients (4 or 5).
std::vector<Eigen::Vector2d> OpenCvRadTan(const Camera& camera,
                                          int count,
                                          const std::vector<Eigen::Vector3d>& points) {
  cv::Mat distortion(1, count, CV_64F);
  for (int i = 0; i < count; ++i) distortion.at<double>(0, i) = camera.distortion_coeffs(i);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(ToCv(points),
                    cv::Vec3d(0, 0, 0),
                    cv::Vec3d(0, 0, 0),
                    CameraMatrix(camera),
                    distortion,
                    pixels);
  std::vector<Eigen::Vector2d> out;
  for (const cv::Point2d& p : pixels) out.emplace_back(p.x, p.y);
  return out;
}

std::vector<Eigen::Vector2d> OpenCvFisheye(const Camera& camera,
                                           const std::vector<Eigen::Vector3d>& points) {
  const cv::Vec4d distortion(camera.distortion_coeffs(0),
                             camera.distortion_coeffs(1),
                             camera.distortion_coeffs(2),
                             camera.distortion_coeffs(3));
  std::vector<cv::Point2d> pixels;
  cv::fisheye::projectPoints(ToCv(points),
                             pixels,
                             cv::Vec3d(0, 0, 0),
                             cv::Vec3d(0, 0, 0),
                             CameraMatrix(camera),
                             distortion);
  std::vector<Eigen::Vector2d> out;
  for (const cv::Point2d& p : pixels) out.emplace_back(p.x, p.y);
  return out;
}

void ExpectMatchesOpenCv(const Camera& camera,
                         const std::vector<Eigen::Vector3d>& points,
                         const std::vector<Eigen::Vector2d>& reference,
                         const std::string& label) {
  ASSERT_EQ(points.size(), reference.size());
  for (size_t i = 0; i < points.size(); ++i) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(camera.Project(points[i], &uv)) << label;
    EXPECT_LT((uv - reference[i]).norm(), kOpenCvTolerancePx)
        << label << " at " << points[i].transpose() << ": " << uv.transpose() << " vs OpenCV "
        << reference[i].transpose();
  }
}

// The dataset's camchain, bundled in data/euroc_april_frames/ (byte-identical to
// ../shared/data/euroc_imu_april/camchain_euroc.yaml), so that these checks run in every checkout.
Camera EurocCam0() {
  const std::string path = testing::BundledDataPath("euroc_april_frames/camchain_euroc.yaml");
  return ReadCamchainYaml(path)[0].camera;
}

// A wide-angle radtan lens (~100 degree field) with OpenCV's 5th coefficient.
Camera WideRadTan() {
  Camera c;
  c.distortion = DistortionModel::kRadTan;
  c.fu = 600.0;
  c.fv = 598.5;
  c.pu = 641.2;
  c.pv = 479.3;
  c.distortion_coeffs << -0.32, 0.11, 1.2e-3, -6.0e-4, -0.018;
  c.radtan_k3 = true;
  c.width = 1280;
  c.height = 960;
  return c;
}

TEST(CameraOpenCvReference, RadTanFourCoefficientsOnEurocCam0) {
  const Camera camera = EurocCam0();
  ASSERT_EQ(camera.distortion, DistortionModel::kRadTan);
  ASSERT_EQ(camera.distortion_coeffs(4), 0.0);
  const std::vector<Eigen::Vector3d> points = ReferencePoints(50.0);
  ExpectMatchesOpenCv(camera, points, OpenCvRadTan(camera, 4, points), "EuRoC cam0 radtan");
}

TEST(CameraOpenCvReference, RadTanWithK3) {
  Camera camera = EurocCam0();
  camera.distortion_coeffs(4) = -0.0125;  // an OpenCV-style 5-coefficient calibration
  camera.radtan_k3 = true;
  const std::vector<Eigen::Vector3d> points = ReferencePoints(50.0);
  ExpectMatchesOpenCv(camera, points, OpenCvRadTan(camera, 5, points), "EuRoC cam0 with k3");
  const Camera wide = WideRadTan();
  const std::vector<Eigen::Vector3d> wide_points = ReferencePoints(50.0);
  ExpectMatchesOpenCv(wide, wide_points, OpenCvRadTan(wide, 5, wide_points), "wide with k3");
  Camera wide4 = wide;
  wide4.distortion_coeffs(4) = 0.0;
  ExpectMatchesOpenCv(wide4, wide_points, OpenCvRadTan(wide4, 4, wide_points), "wide, 4");
}

TEST(CameraOpenCvReference, EquidistantMatchesOpenCvFisheye) {
  // EuRoC cam0's focal lengths and principal point with Kannala-Brandt coefficients of a
  // similar lens (the dataset publishes radtan only).
  Camera euroc = EurocCam0();
  euroc.distortion = DistortionModel::kEquidistant;
  euroc.distortion_coeffs << -0.0045, 0.0196, -0.0218, 0.0076, 0.0;
  const std::vector<Eigen::Vector3d> points = ReferencePoints(50.0);
  ExpectMatchesOpenCv(euroc, points, OpenCvFisheye(euroc, points), "EuRoC cam0 equidistant");
  // TUM-VI's 195 degree fisheye, to 85 degrees (a pinhole-equi camera stops at 90).
  const Camera tumvi = testing::TumViEquidistant();
  const std::vector<Eigen::Vector3d> wide_points = ReferencePoints(85.0);
  ExpectMatchesOpenCv(tumvi, wide_points, OpenCvFisheye(tumvi, wide_points), "TUM-VI equi");
}

TEST(CameraOpenCvReference, SwappedTangentialCoefficientsMoveThePixels) {
  // The premise of the radtan comparisons: had splinecal swapped p1 and p2, its pixels would
  // differ from OpenCV's by more than kMinSwapEffectPx at every off-axis point tested.
  for (const Camera& camera : {EurocCam0(), WideRadTan()}) {
    Camera swapped = camera;
    std::swap(swapped.distortion_coeffs(2), swapped.distortion_coeffs(3));
    const std::vector<Eigen::Vector3d> points = ReferencePoints(50.0);
    const std::vector<Eigen::Vector2d> reference = OpenCvRadTan(camera, 5, points);
    const std::vector<Eigen::Vector2d> moved = OpenCvRadTan(swapped, 5, points);
    for (size_t i = 1; i < points.size(); ++i) {  // 0 is the axis, where p1, p2 do nothing
      EXPECT_GT((moved[i] - reference[i]).norm(), kMinSwapEffectPx) << points[i].transpose();
      Eigen::Vector2d uv;
      ASSERT_TRUE(swapped.Project(points[i], &uv));
      EXPECT_GT((uv - reference[i]).norm(), kMinSwapEffectPx);  // the comparison would fail
    }
  }
}

}  // namespace
}  // namespace splinecal
