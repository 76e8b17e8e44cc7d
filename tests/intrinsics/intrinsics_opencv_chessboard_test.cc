// splinecal intrinsics on OpenCV's own sample chessboards (the 13 left images, bundled in
// data/opencv_chessboard/cam0: byte-identical to ../shared/data/opencv_chessboard), corners from
// splinecal's detector: the exact least-squares solve against OpenCV's calibrateCamera (k3 fixed at
// 0: the 4-coefficient radtan model of Kalibr and of splinecal's pinhole-radtan) run here on the
// same corners (intrinsics/opencv_reference.h), the default robust solve against the exact one, and
// both near the reference SOURCE.md gives (OpenCV 4.6 on its own detector's corners: fx, fy, cx, cy
// = 533.052, 533.182, 342.459, 233.915).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "intrinsics/opencv_reference.h"
#include "testing/paths.h"

namespace splinecal {
namespace {

TEST(IntrinsicsOpenCvChessboard, ExactLeastSquaresMatchesOpenCvCalibrateCamera) {
  const CalibrationTarget board = MakeCheckerboard(9, 6, 1.0, 1.0);  // square = 1, as OpenCV
  TargetDetector detector(board);
  std::vector<Observation> observations;
  for (int index : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
    char name[64];
    std::snprintf(name, sizeof(name), "opencv_chessboard/cam0/%d000000000.jpg", index);
    const GrayImage image = ReadGrayImage(testing::BundledDataPath(name));
    for (const CornerDetection& corner : detector.Detect(image.view()).corners) {
      observations.push_back({index * 1'000'000'000LL, 0, corner.point_id, corner.uv});
    }
  }
  ASSERT_EQ(observations.size(), 13u * 54u);
  observations = testing::RoundedToFloat(observations);
  IntrinsicsCameraSpec spec;
  spec.camera.distortion = DistortionModel::kRadTan;
  spec.camera.width = 640;
  spec.camera.height = 480;
  IntrinsicsOptions exact;
  exact.huber_px = 0.0;
  exact.outlier_sigmas = 0.0;
  exact.keep_repeated_views = true;
  const IntrinsicsResult result = CalibrateIntrinsics(observations, board, {spec}, exact);
  const IntrinsicsCameraResult& camera = result.cameras[0];
  EXPECT_EQ(camera.views_used, 13);
  EXPECT_EQ(camera.corners_used, 13 * 54);
  const testing::OpenCvCalibration cv = testing::CalibrateWithOpenCv(
      observations, board, DistortionModel::kRadTan, 640, 480, exact.min_corners);
  ASSERT_EQ(cv.corners, 13 * 54);
  const double ours_sq = testing::SumOfSquares(result.residuals);
  // The same problem on the same corners: no larger than OpenCV's sum of squares, up to 1e-9
  // relative (both stop on a relative cost change ~1e-10..1e-15; 1e-9 of 27 px^2 is far below
  // what an intrinsic 0.001 px off the minimum adds).
  EXPECT_LE(ours_sq, cv.sum_sq_px2 * (1.0 + 1e-9));
  const IntrinsicsVector a = camera.camera.intrinsics();
  const IntrinsicsVector b = cv.camera.intrinsics();
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(a(j), b(j), 0.05) << "fu fv pu pv entry " << j;
  // k1 k2 p1 p2: the same minimum, so they agree to the solvers' convergence. 1e-4 is 0.05 px
  // at the image corner for k1 (r^2 ~ 0.6 in normalised units, f ~ 533 px: 1e-4 * 0.6 * 0.8 *
  // 533 = 0.03 px), less for the others.
  for (int j = kDistortionCoeffsIndex; j < kDistortionCoeffsIndex + 4; ++j) {
    EXPECT_NEAR(a(j), b(j), 1e-4) << "distortion entry " << j;
  }
  EXPECT_LT(testing::LargestPixelDifference(camera.camera, cv.camera), 0.05);
  // OpenCV 4.6's own result on these images (SOURCE.md, its detector's corners): within 1 px.
  EXPECT_NEAR(camera.camera.fu, 533.052, 1.0);
  EXPECT_NEAR(camera.camera.fv, 533.182, 1.0);
  EXPECT_NEAR(camera.camera.pu, 342.459, 1.0);
  EXPECT_NEAR(camera.camera.pv, 233.915, 1.0);
  RecordProperty("sum_sq_ours_opencv",
                 std::to_string(ours_sq) + " " + std::to_string(cv.sum_sq_px2));

  // The default (Huber, outlier removal, repeats set aside) on these clean corners stays within
  // 0.1 px of the exact answer everywhere in the image.
  const IntrinsicsResult robust =
      CalibrateIntrinsics(observations, board, {spec}, IntrinsicsOptions());
  EXPECT_LT(testing::LargestPixelDifference(robust.cameras[0].camera, camera.camera), 0.1);
}

}  // namespace
}  // namespace splinecal
