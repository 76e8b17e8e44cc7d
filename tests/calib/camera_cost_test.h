// The fixture of the camera cost tests (tests/estimation/reprojection_cost_test.cc,
// target_scale_cost_test.cc): the camera-on-spline scene (camera_test_scene.h) and reprojection
// settings over its control poses, 0.7 px pixel noise.
#ifndef SPLINECAL_TESTS_CALIB_CAMERA_COST_TEST_H_
#define SPLINECAL_TESTS_CALIB_CAMERA_COST_TEST_H_

#include <gtest/gtest.h>

#include <cmath>

#include "calib/camera_test_scene.h"
#include "splinecal/estimation/reprojection_cost.h"

namespace splinecal {
namespace testing {

class CameraCostTest : public ::testing::Test {
 protected:
  CameraCostTest() {
    settings_.camera = &scene_.camera;
    settings_.layout.dt_ns = std::llround(scene_.dt_s * 1e9);
    settings_.layout.num_control_poses = static_cast<int>(scene_.poses.size());
    settings_.sigma_px = 0.7;
  }

  CameraTestScene scene_;
  ReprojectionOptions settings_;
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_CAMERA_COST_TEST_H_
