// `export --format openvins` carries calibrate's IMU model (src/io/export_openvins.cc derives the
// mapping; docs/export.md). The check is numeric: readings predicted by splinecal's model
// (imu/imu_intrinsic_model.h) are corrected with OpenVINS' equations, written out here from its
// documentation ("IMU Intrinsic Models" of rpng/open_vins, and its loader: Dw = Tw^-1,
// Da = Ta^-1, R_ACCtoIMU = R_IMUtoACC^T, R_GYROtoIMU = R_IMUtoGYRO^T):
//
//   a_I = R_ACCtoIMU Da (a_m - b_a)            w_I = R_GYROtoIMU Dw (w_m - b_g - Tg a_I)
//
// using the matrices read back from the exported kalibr_imu_chain.yaml; a_I and w_I must be the
// specific force and angular velocity the readings were predicted from.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>
#include <string>
#include <vector>

#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/io/calibration_export.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/lie/so3.h"
#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using testing::TempDir;

// A consumer-grade model, every parameter away from nominal (sizes of Rehder et al., ICRA 2016):
// a non-trivial C_gyro_i, so that writing Tg = A (without C_gyro_i) or R_IMUtoGYRO transposed
// would fail the comparison by ~1e-3 relative.
ImuCalibration ConsumerModel(ImuModelKind kind) {
  ImuCalibration model;
  model.model = kind;
  ImuIntrinsicsd& p = model.intrinsics;
  p.M_a << 1.01, 0, 0, 0.008, 0.99, 0, -0.006, 0.004, 1.005;
  p.M_g << 0.99, 0, 0, -0.005, 1.012, 0, 0.007, -0.003, 1.008;
  p.A << 1e-3, 2e-4, -3e-4, -1e-4, -8e-4, 5e-4, 3e-4, -2e-4, 9e-4;
  p.C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.01, -0.02, 0.015)).matrix();
  if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
    p.ry_i = Eigen::Vector3d(0.005, 0, -0.003);
    p.rz_i = Eigen::Vector3d(-0.004, 0.006, 0);
  }
  return model;
}

Eigen::Matrix3d ReadMatrix(const YamlDocument& yaml, const std::string& key) {
  const std::vector<std::vector<double>> rows = yaml.Rows(key);
  EXPECT_EQ(rows.size(), 3u) << key;
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (int r = 0; r < 3 && r < static_cast<int>(rows.size()); ++r) {
    EXPECT_EQ(rows[r].size(), 3u) << key;
    for (int c = 0; c < 3 && c < static_cast<int>(rows[r].size()); ++c) m(r, c) = rows[r][c];
  }
  return m;
}

// The calibration folder calibrate --imu-model writes: camchain-imucam.yaml and imu_models.yaml.
std::string CalibrationFolder(const TempDir& dir, const ImuCalibration& model) {
  dir.Write("camchain-imucam.yaml",
            testing::ReadFileText(testing::BundledDataPath("euroc_april_frames/camchain_euroc.yaml")));
  dir.Write("imu_models.yaml", ImuModelsYamlText({model}));
  return dir.path();
}

class ExportOpenVinsImuModel : public ::testing::TestWithParam<ImuModelKind> {};

TEST_P(ExportOpenVinsImuModel, OpenVinsCorrectionOfTheModelsReadingsGivesTheTrueMotion) {
  const ImuCalibration model = ConsumerModel(GetParam());
  TempDir folder;
  const CalibrationExport calibration = ReadCalibrationForExport(CalibrationFolder(folder, model));
  ASSERT_EQ(calibration.imu_model.model, model.model);
  const std::vector<OutputFile> files = ExportCalibration(calibration, ExportFormat::kOpenVins);
  const std::string& text = OutputFileContents(files, "kalibr_imu_chain.yaml");
  TempDir out;
  const YamlDocument yaml(out.Write("kalibr_imu_chain.yaml", text));
  EXPECT_EQ(yaml.String("imu0/model"), "kalibr");
  const Eigen::Matrix3d Tw = ReadMatrix(yaml, "imu0/Tw");
  const Eigen::Matrix3d Ta = ReadMatrix(yaml, "imu0/Ta");
  const Eigen::Matrix3d R_IMUtoACC = ReadMatrix(yaml, "imu0/R_IMUtoACC");
  const Eigen::Matrix3d R_IMUtoGYRO = ReadMatrix(yaml, "imu0/R_IMUtoGYRO");
  const Eigen::Matrix3d Tg = ReadMatrix(yaml, "imu0/Tg");
  // OpenVINS' "kalibr" model holds lower-triangular Dw, Da (its D'_6): Tw, Ta must be too.
  EXPECT_EQ(Tw(0, 1), 0.0);
  EXPECT_EQ(Tw(0, 2), 0.0);
  EXPECT_EQ(Tw(1, 2), 0.0);
  EXPECT_EQ(Ta(0, 1), 0.0);
  EXPECT_EQ(Ta(0, 2), 0.0);
  EXPECT_EQ(Ta(1, 2), 0.0);
  const Eigen::Matrix3d Dw = Tw.inverse();
  const Eigen::Matrix3d Da = Ta.inverse();
  const bool size_effect = GetParam() == ImuModelKind::kScaleMisalignmentSizeEffect;
  EXPECT_EQ(text.find("ry_i, rz_i have no OpenVINS counterpart") != std::string::npos,
            size_effect);

  std::mt19937 rng(7);
  std::uniform_real_distribution<double> rate(-3.0, 3.0);      // rad/s, a lively hand-held rig
  std::uniform_real_distribution<double> force(-15.0, 15.0);   // m/s^2, gravity and motion
  const Eigen::Vector3d b_g(0.003, -0.002, 0.001);
  const Eigen::Vector3d b_a(0.05, -0.08, 0.02);
  for (int k = 0; k < 50; ++k) {
    BodyMotion<double> motion;
    motion.w_b = Eigen::Vector3d(rate(rng), rate(rng), rate(rng));
    motion.f_b = Eigen::Vector3d(force(rng), force(rng), force(rng));
    // OpenVINS has no lever arms: with the size effect its model is the scale-misalignment part
    // of Kalibr's (the arms are left out and the file says so, checked above).
    Eigen::Vector3d gyro, accel;
    PredictImuReadings(ImuModelKind::kScaleMisalignment, model.intrinsics, motion, b_g, b_a,
                       &gyro, &accel);
    const Eigen::Vector3d a_I = R_IMUtoACC.transpose() * Da * (accel - b_a);
    const Eigen::Vector3d w_I = R_IMUtoGYRO.transpose() * Dw * (gyro - b_g - Tg * a_I);
    // The exported numbers are printed to round trip, so the only error is the inversion's
    // rounding: ~1e-15 relative to |f| ~ 15 m/s^2 and |w| ~ 3 rad/s; 1e-12 leaves room for it
    // and nothing else (a Tg without C_gyro_i moves w_I by |A| |f| 0.02 ~ 3e-4 rad/s).
    EXPECT_LT((a_I - motion.f_b).norm(), 1e-12) << "sample " << k;
    EXPECT_LT((w_I - motion.w_b).norm(), 1e-12) << "sample " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(Models,
                         ExportOpenVinsImuModel,
                         ::testing::Values(ImuModelKind::kScaleMisalignment,
                                           ImuModelKind::kScaleMisalignmentSizeEffect));

TEST(ExportOpenVinsImuModel, WithoutAModelFileTheIntrinsicsAreNominal) {
  TempDir folder;
  folder.Write("camchain-imucam.yaml",
               testing::ReadFileText(testing::BundledDataPath("euroc_april_frames/camchain_euroc.yaml")));
  const CalibrationExport calibration = ReadCalibrationForExport(folder.path());
  EXPECT_EQ(calibration.imu_model.model, ImuModelKind::kCalibrated);
  const std::vector<OutputFile> files = ExportCalibration(calibration, ExportFormat::kOpenVins);
  TempDir out;
  const YamlDocument yaml(
      out.Write("kalibr_imu_chain.yaml", OutputFileContents(files, "kalibr_imu_chain.yaml")));
  EXPECT_EQ(ReadMatrix(yaml, "imu0/Tw"), Eigen::Matrix3d::Identity());
  EXPECT_EQ(ReadMatrix(yaml, "imu0/Ta"), Eigen::Matrix3d::Identity());
  EXPECT_EQ(ReadMatrix(yaml, "imu0/R_IMUtoGYRO"), Eigen::Matrix3d::Identity());
  EXPECT_EQ(ReadMatrix(yaml, "imu0/Tg"), Eigen::Matrix3d::Zero());
}

}  // namespace
}  // namespace splinecal
