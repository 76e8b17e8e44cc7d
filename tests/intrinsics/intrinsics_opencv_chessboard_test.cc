// splinecal intrinsics on OpenCV's own sample chessboards (../shared/data/opencv_chessboard, the
// 13 left images), corners from splinecal's detector, against the reference its SOURCE.md
// gives: OpenCV 4.6's calibrateCamera with k3 fixed at 0 (the 4-coefficient radtan model of
// Kalibr and of splinecal's pinhole-radtan) on the same images: RMS 0.19667 px, fx, fy, cx, cy =
// 533.052, 533.182, 342.459, 233.915.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

TEST(IntrinsicsOpenCvChessboard, RadTanMatchesOpenCvsFourCoefficientResult) {
  SPLINECAL_REQUIRE_SHARED_DATA("opencv_chessboard");
  const CalibrationTarget board = MakeCheckerboard(9, 6, 1.0, 1.0);  // square = 1, as OpenCV
  TargetDetector detector(board);
  std::vector<Observation> observations;
  for (int index : {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14}) {
    char name[32];
    std::snprintf(name, sizeof(name), "opencv_chessboard/left%02d.jpg", index);
    const GrayImage image = ReadGrayImage(testing::SharedDataPath(name));
    for (const CornerDetection& corner : detector.Detect(image.view()).corners) {
      observations.push_back({index * 1'000'000'000LL, 0, corner.point_id, corner.uv});
    }
  }
  ASSERT_EQ(observations.size(), 13u * 54u);
  IntrinsicsCameraSpec spec;
  spec.camera.distortion = DistortionModel::kRadTan;
  spec.camera.width = 640;
  spec.camera.height = 480;
  IntrinsicsOptions options;
  options.min_corners = 12;
  const IntrinsicsResult result = CalibrateIntrinsics(observations, board, {spec}, options);
  const IntrinsicsCameraResult& camera = result.cameras[0];
  EXPECT_EQ(camera.views_used, 13);
  EXPECT_EQ(camera.corners_rejected, 0);
  // The tolerances: 1 px in fx, fy, cx, cy and 0.01 px in RMS.
  EXPECT_NEAR(camera.camera.fu, 533.052, 1.0);
  EXPECT_NEAR(camera.camera.fv, 533.182, 1.0);
  EXPECT_NEAR(camera.camera.pu, 342.459, 1.0);
  EXPECT_NEAR(camera.camera.pv, 233.915, 1.0);
  EXPECT_NEAR(camera.reprojection_rms_px, 0.19667, 0.01);
  RecordProperty("fx_fy_cx_cy_rms",
                 std::to_string(camera.camera.fu) + " " + std::to_string(camera.camera.fv) + " " +
                     std::to_string(camera.camera.pu) + " " + std::to_string(camera.camera.pv) +
                     " " + std::to_string(camera.reprojection_rms_px));
}

}  // namespace
}  // namespace splinecal
