#include "splinecal/report/fit_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "testing/html_ids.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A fit of 40 IMU samples and 10 poses, enough for every figure of the report.
FitResult SmallFit() {
  FitResult r;
  r.layout.t0_ns = 1'000'000'000;
  r.layout.dt_ns = 100'000'000;
  r.layout.num_control_poses = 6;
  for (int k = 0; k < 40; ++k) {
    FitImuSample s;
    s.t_ns = r.layout.t0_ns + 100'000'000 + k * 5'000'000;
    s.gyro_measured = Eigen::Vector3d(0.1, -0.2, 0.3 + 1e-3 * k);
    s.gyro_fitted = s.gyro_measured + Eigen::Vector3d::Constant(1e-4);
    s.accel_measured = Eigen::Vector3d(0.0, 0.0, 9.81);
    s.accel_fitted = s.accel_measured;
    r.imu_samples.push_back(s);
  }
  for (int k = 0; k < 10; ++k) {
    FitPoseSample p;
    p.t_ns = r.layout.t0_ns + 100'000'000 + k * 20'000'000;
    r.pose_samples.push_back(p);
  }
  r.warnings = {"a warning"};
  return r;
}

FitReportInputs Inputs(const std::string& imu_yaml_path) {
  FitReportInputs inputs;
  inputs.imu_path = "imu0.csv";
  inputs.poses_path = "poses.csv";
  inputs.imu_yaml_path = imu_yaml_path;
  return inputs;
}

TEST(FitReportHtml, IdsAreUniqueAcrossItsInlinedSvgs) {
  const FitReportInputs inputs = Inputs("");
  const std::string html = FitReportHtml(SmallFit(), inputs);
  // Gyroscope 3 panels, accelerometer 3, residuals 4, biases 2: a clip path each.
  EXPECT_EQ(testing::ExpectUniqueHtmlIds(html, "report.html"), 12);
  EXPECT_THAT(html, Not(HasSubstr("<?xml")));
}

TEST(FitReportHtml, ListsTheInputsAndTheNoiseModel) {
  FitReportInputs inputs = Inputs("my_imu.yaml");
  FitResult fit = SmallFit();
  fit.imu_noise.given.gyroscope_noise_density = 1.5e-4;
  fit.imu_noise.measured.gyroscope_noise_density = 6e-4;
  fit.imu_noise.used.gyroscope_noise_density = 1.5e-4;
  fit.imu_noise.num_residuals[0] = 300;
  fit.imu_noise.determined[0] = true;
  const std::string html = FitReportHtml(fit, inputs);
  EXPECT_THAT(html, HasSubstr("<p>IMU: imu0.csv<br>poses: poses.csv</p>"));
  EXPECT_THAT(html,
              HasSubstr("<caption>IMU noise model (--imu-noise estimated), given: my_imu.yaml"));
  // Given, measured, used as the weight.
  EXPECT_THAT(html,
              HasSubstr("<td>gyroscope_noise_density</td><td>0.00015</td><td>0.0006</td>"
                        "<td>0.00015</td>"));
  EXPECT_THAT(html, HasSubstr("measured: enters the standard deviations"));
  inputs.imu_yaml_path.clear();
  EXPECT_THAT(FitReportHtml(fit, inputs), HasSubstr("given: ADIS16448 defaults"));
}

TEST(FitResultYaml, EveryKeyOnce) {
  FitResult r = SmallFit();
  r.extrinsic_estimated = true;
  r.time_offset_estimated = true;
  r.bias_model = BiasModel::kSpline;
  const std::string text = FitResultYaml(r, Inputs(""));
  EXPECT_THAT(testing::DuplicateYamlKeys(text), ::testing::IsEmpty()) << text;
}

}  // namespace
}  // namespace splinecal
