// splinecal intrinsics on the real EuRoC calibration recording (../shared/data/euroc_imu_april:
// 358k AprilGrid corners of two cameras; published calibrations in its REFERENCE.md):
//   * pinhole-radtan against OpenCV's calibrateCamera (k3 fixed: the same 4-coefficient model)
//     on exactly the corners splinecal used, within 1 px in fx, fy, cx, cy;
//   * the stereo baseline within 1 mm of the published 110.074 mm (Kalibr's camchain).
#include <gtest/gtest.h>

#include <map>
#include <opencv2/calib3d.hpp>
#include <string>
#include <vector>

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "testing/shared_data.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

struct EurocRun {
  CalibrationTarget target;
  IntrinsicsResult result;
};

EurocRun RunEuroc(int max_views, const std::string& model = "pinhole-radtan") {
  EurocRun run;
  run.target = ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  const std::vector<Observation> observations =
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv"));
  IntrinsicsCameraSpec spec;
  EXPECT_TRUE(ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion));
  spec.camera.width = 752;
  spec.camera.height = 480;
  IntrinsicsOptions options;
  options.max_views_per_camera = max_views;
  options.solver.num_threads = 2;
  run.result = CalibrateIntrinsics(observations, run.target, {spec, spec}, options);
  return run;
}

TEST(IntrinsicsEuroc, RadTanAgreesWithOpenCvCalibrateCameraOnTheSameCorners) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  // 100 views per camera: OpenCV's calibrateCamera solves a dense system over every view's pose.
  const EurocRun run = RunEuroc(100);
  for (int n = 0; n < 2; ++n) {
    SCOPED_TRACE("cam" + std::to_string(n));
    std::map<int64_t, std::pair<std::vector<cv::Point3f>, std::vector<cv::Point2f>>> views;
    for (const ReprojectionSample& s : run.result.residuals) {
      if (s.cam_id != n) continue;
      const Eigen::Vector3d& p = *run.target.Find(s.point_id);
      views[s.t_ns].first.emplace_back(p.x(), p.y(), p.z());
      views[s.t_ns].second.emplace_back(s.uv.x(), s.uv.y());
    }
    std::vector<std::vector<cv::Point3f>> object_points;
    std::vector<std::vector<cv::Point2f>> image_points;
    for (auto& [t, view] : views) {
      object_points.push_back(view.first);
      image_points.push_back(view.second);
    }
    ASSERT_EQ(static_cast<int>(object_points.size()), run.result.cameras[n].views_used);
    cv::Mat K, distortion;
    std::vector<cv::Mat> rvecs, tvecs;
    const double rms = cv::calibrateCamera(object_points,
                                           image_points,
                                           cv::Size(752, 480),
                                           K,
                                           distortion,
                                           rvecs,
                                           tvecs,
                                           // LU for OpenCV's steps, as in opencv_reference.h.
                                           cv::CALIB_FIX_K3 | cv::CALIB_USE_LU);
    const Camera& ours = run.result.cameras[n].camera;
    RecordProperty("cam" + std::to_string(n) + "_opencv_fx_fy_cx_cy_rms",
                   std::to_string(K.at<double>(0, 0)) + " " + std::to_string(K.at<double>(1, 1)) +
                       " " + std::to_string(K.at<double>(0, 2)) + " " +
                       std::to_string(K.at<double>(1, 2)) + " " + std::to_string(rms));
    RecordProperty("cam" + std::to_string(n) + "_ours_fx_fy_cx_cy_rms",
                   std::to_string(ours.fu) + " " + std::to_string(ours.fv) + " " +
                       std::to_string(ours.pu) + " " + std::to_string(ours.pv) + " " +
                       std::to_string(run.result.cameras[n].reprojection_rms_px));
    EXPECT_NEAR(ours.fu, K.at<double>(0, 0), 1.0);
    EXPECT_NEAR(ours.fv, K.at<double>(1, 1), 1.0);
    EXPECT_NEAR(ours.pu, K.at<double>(0, 2), 1.0);
    EXPECT_NEAR(ours.pv, K.at<double>(1, 2), 1.0);
    // Same corners and model; the rig shares each timestamp's target pose between the two
    // cameras where OpenCV fits each camera alone, so the minima are close, not identical.
    EXPECT_NEAR(run.result.cameras[n].reprojection_rms_px, rms, 0.01);
  }
}

// basalt's double sphere of this rig (REFERENCE.md B): fx, fy, cx, cy, xi, alpha per camera.
constexpr double kBasaltDs[2][6] = {
    {349.7560023, 348.7245423, 365.8944076, 249.3299557, -0.2409573942, 0.5669968992},
    {361.6713884, 360.5856494, 379.4081839, 255.9772969, -0.2130083538, 0.5767008625}};

// One test for the two checks on every view (the stereo baseline of radtan, the double sphere
// against basalt's and against radtan): they share radtan's calibration of the whole recording,
// computed once (ctest runs each TEST as its own process).
TEST(IntrinsicsEuroc, StereoBaselineAndDoubleSphereAgainstThePublishedCalibrations) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  const EurocRun radtan = RunEuroc(0);
  {
    SCOPED_TRACE("stereo baseline within one millimetre of the published one");
    const double baseline_mm = 1e3 * radtan.result.cameras[1].T_cn_cnm1.translation().norm();
    RecordProperty("baseline_mm", std::to_string(baseline_mm));
    EXPECT_NEAR(baseline_mm, 110.074, 1.0);
    // Its std is what the two halves of a recording would disagree by: far below 1 mm.
    EXPECT_LT(1e3 * radtan.result.cameras[1].T_cn_cnm1_std.head<3>().norm(), 1.0);
  }
  const EurocRun ds = RunEuroc(0, "ds-none");
  for (int n = 0; n < 2; ++n) {
    SCOPED_TRACE("double sphere against basalt's published calibration, cam" +
                 std::to_string(n));
    const Camera& c = ds.result.cameras[n].camera;
    const double* b = kBasaltDs[n];
    RecordProperty("cam" + std::to_string(n) + "_ds_fx_fy_cx_cy_xi_alpha_rms",
                   std::to_string(c.fu) + " " + std::to_string(c.fv) + " " +
                       std::to_string(c.pu) + " " + std::to_string(c.pv) + " " +
                       std::to_string(c.projection_params(0)) + " " +
                       std::to_string(c.projection_params(1)) + " " +
                       std::to_string(ds.result.cameras[n].reprojection_rms_px));
    // The principal point within 8 px (this recording covers less of the image than basalt's).
    EXPECT_NEAR(c.pu, b[2], 8.0);
    EXPECT_NEAR(c.pv, b[3], 8.0);
    // The focal length near the optical axis, f / (1 + xi) (the double sphere's projection of
    // a small angle), within 2% of basalt's. fx and xi themselves trade along a valley this
    // recording does not resolve: fx lands 7% below basalt's, xi 0.05 lower (docs/intrinsics.md,
    // "fx 7% below basalt's").
    EXPECT_NEAR(c.fu / (1.0 + c.projection_params(0)), b[0] / (1.0 + b[4]),
                0.02 * b[0] / (1.0 + b[4]));
    EXPECT_NEAR(c.fv / (1.0 + c.projection_params(0)), b[1] / (1.0 + b[4]),
                0.02 * b[1] / (1.0 + b[4]));
    // The wide-angle model explains the corners at least as well as radtan.
    EXPECT_LE(ds.result.cameras[n].reprojection_rms_px,
              radtan.result.cameras[n].reprojection_rms_px);
  }
}

}  // namespace
}  // namespace splinecal
