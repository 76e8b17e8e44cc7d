// Exact least squares: with no loss (huber_px = 0), no outlier removal (outlier_sigmas = 0),
// repeated views kept and one camera, splinecal intrinsics solves the problem OpenCV's
// calibrateCamera solves (every corner's squared pixel error, each view its own pose). On the
// same corners its sum of squares must be no larger than OpenCV's and every intrinsic within
// 0.05 px (docs/intrinsics.md, "Exact least squares"). Data: every 8th frame of each camera of
// the EuRoC calibration recording (../shared/data/euroc_imu_april, 177 views each). Slow: OpenCV's
// calibrateCamera solves its dense system over every view's pose at each iteration (4 to 6 CPU-s
// per camera in Release with the steps by LU, opencv_reference.h; 43 to 48 by OpenCV's default
// SVD, docs/reliability.md "Test time before / after").
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "intrinsics/opencv_reference.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "testing/shared_data.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

IntrinsicsOptions ExactOptions() {
  IntrinsicsOptions options;
  options.huber_px = 0.0;
  options.outlier_sigmas = 0.0;
  options.keep_repeated_views = true;
  options.solver.num_threads = 2;
  return options;
}

void ExpectExactAgainstOpenCv(const std::string& model, int cam_id) {
  const CalibrationTarget target =
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  const std::vector<Observation> observations = testing::RoundedToFloat(testing::EveryNthFrame(
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv")), cam_id, 8));
  IntrinsicsCameraSpec spec;
  ASSERT_TRUE(ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion));
  spec.camera.width = 752;
  spec.camera.height = 480;
  const IntrinsicsOptions options = ExactOptions();
  const IntrinsicsResult result = CalibrateIntrinsics(observations, target, {spec}, options);
  const testing::OpenCvCalibration cv = testing::CalibrateWithOpenCv(
      observations, target, spec.camera.distortion, 752, 480, options.min_corners);
  const IntrinsicsCameraResult& ours = result.cameras[0];
  // The same corners on both sides: every view and every corner used.
  ASSERT_EQ(ours.views_used, cv.views);
  ASSERT_EQ(ours.corners_used, cv.corners);
  const double ours_sq = testing::SumOfSquares(result.residuals);
  ::testing::Test::RecordProperty("sum_sq_ours_opencv",
                                  std::to_string(ours_sq) + " " + std::to_string(cv.sum_sq_px2));
  // No larger than OpenCV's, up to 1e-9 relative: both stop where a step changes the cost by
  // less than their tolerances (Ceres' function tolerance 1e-10 relative); 1e-9 of ~6,000 px^2
  // is 6e-6 px^2, what an intrinsic 1e-4 px off the minimum would add.
  EXPECT_LE(ours_sq, cv.sum_sq_px2 * (1.0 + 1e-9));
  const IntrinsicsVector a = ours.camera.intrinsics();
  const IntrinsicsVector b = cv.camera.intrinsics();
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(a(j), b(j), 0.05) << "fu fv pu pv entry " << j;
  // The distortion, in pixels: the two calibrations map no ray of the image 0.05 px apart.
  EXPECT_LT(testing::LargestPixelDifference(ours.camera, cv.camera), 0.05);
}

TEST(IntrinsicsExactLeastSquares, RadTanCam0NoWorseThanOpenCvCalibrateCamera) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  ExpectExactAgainstOpenCv("pinhole-radtan", 0);
}

TEST(IntrinsicsExactLeastSquares, RadTanCam1NoWorseThanOpenCvCalibrateCamera) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  ExpectExactAgainstOpenCv("pinhole-radtan", 1);
}

// cam0's pinhole-equi has no OpenCV reference: cv::fisheye::calibrate (4.6) stops on its corners
// with "Assertion failed: fabs(norm_u1) > 0 in function 'InitExtrinsics'" (its homography start
// of one of the 177 views degenerates), so only cam1's is compared.
TEST(IntrinsicsExactLeastSquares, EquidistantCam1NoWorseThanOpenCvFisheyeCalibrate) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  ExpectExactAgainstOpenCv("pinhole-equi", 1);
}

}  // namespace
}  // namespace splinecal
