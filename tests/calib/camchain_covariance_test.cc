#include "splinecal/io/camchain_yaml_covariance.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/string_printf.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Two pinhole-radtan cameras (EuRoC's published values) with a camera chain, as `splinecal
// intrinsics` writes them (io/camchain_yaml.h, kCamerasOnly).
Camchain TwoCameras() {
  Camchain camchain(2);
  for (int i = 0; i < 2; ++i) {
    Camera& c = camchain[i].camera;
    c.projection = ProjectionModel::kPinhole;
    c.distortion = DistortionModel::kRadTan;
    c.fu = 458.654 - i;
    c.fv = 457.296 - i;
    c.pu = 367.215 + 12 * i;
    c.pv = 248.375 + 7 * i;
    c.distortion_coeffs << -0.2834, 0.0740, 0.00019, 1.8e-05, 0.0;
    c.width = 752;
    c.height = 480;
  }
  camchain[1].T_cn_cnm1 =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.001, -0.002, 0.003)), Eigen::Vector3d(-0.11, 0.0004, -0.0008));
  return camchain;
}

// A positive definite covariance of n parameters with correlations.
Eigen::MatrixXd SomeCovariance(int n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) A(i, j) = 0.1 * std::sin(1.0 + i * 3 + j);
  }
  const Eigen::VectorXd scale = Eigen::VectorXd::LinSpaced(n, 0.5, 1e-4);
  return scale.asDiagonal() * (A * A.transpose()) * scale.asDiagonal();
}

// The camchain text with a splinecal_covariance block under camN from `block` (the map's lines,
// already indented by 4 spaces).
std::string WithBlock(const Camchain& camchain, const std::string& block0,
                      const std::string& block1) {
  const std::string text = CamchainYamlText(camchain, CamchainKeys::kCamerasOnly);
  const size_t cam1 = text.find("cam1:");
  return text.substr(0, cam1) + (block0.empty() ? "" : "  splinecal_covariance:\n" + block0) +
         text.substr(cam1) + (block1.empty() ? "" : "  splinecal_covariance:\n" + block1);
}

TEST(ReadCamchainCovariances, RoundTripOfIntrinsicsAndChain) {
  const Camchain camchain = TwoCameras();
  CameraCovariance c0;
  c0.intrinsics = {0, 1, 2, 3, 6, 7, 8, 9};
  c0.matrix = SomeCovariance(8);
  c0.block_seconds = 2.0;
  CameraCovariance c1 = c0;
  c1.has_T_cn_cnm1 = true;
  c1.matrix = SomeCovariance(14);
  testing::TempDir dir;
  const std::string path = dir.Write(
      "camchain.yaml",
      WithBlock(camchain, CameraCovarianceYamlText(camchain[0].camera, c0, 4),
                CameraCovarianceYamlText(camchain[1].camera, c1, 4)));
  // Kalibr's reader of the same file ignores the block.
  const Camchain read = ReadCamchainYaml(path);
  ASSERT_EQ(read.size(), 2u);
  const std::vector<std::optional<CameraCovariance>> covariances =
      ReadCamchainCovariances(path, read);
  ASSERT_EQ(covariances.size(), 2u);
  ASSERT_TRUE(covariances[0] && covariances[1]);
  EXPECT_EQ(covariances[0]->intrinsics, c0.intrinsics);
  EXPECT_FALSE(covariances[0]->has_T_cn_cnm1);
  // 17 digits read back exactly; the reader symmetrises, which rounds in the last bit.
  EXPECT_LT((covariances[0]->matrix - c0.matrix).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_EQ(covariances[0]->block_seconds, 2.0);
  EXPECT_TRUE(covariances[1]->has_T_cn_cnm1);
  EXPECT_LT((covariances[1]->matrix - c1.matrix).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_THAT(CovarianceParameterNames(read[1].camera, true),
              ::testing::ElementsAre("fu", "fv", "pu", "pv", "k1", "k2", "p1", "p2",
                                     "T_cn_cnm1_rho_x", "T_cn_cnm1_rho_y", "T_cn_cnm1_rho_z",
                                     "T_cn_cnm1_phi_x", "T_cn_cnm1_phi_y", "T_cn_cnm1_phi_z"));
}

TEST(ReadCamchainCovariances, AcceptsTheSchemasSynonymsAndNoBlock) {
  // The agreed schema's example names fx fy cx cy, k1 k2 r1 r2 (Kalibr's radtan names).
  const Camchain camchain = TwoCameras();
  std::string block = "    parameters: [fx, fy, cx, cy, k1, k2, r1, r2]\n    matrix:\n";
  const Eigen::MatrixXd S = SomeCovariance(8);
  for (int r = 0; r < 8; ++r) {
    block += "      - [";
    for (int c = 0; c < 8; ++c) block += (c ? ", " : "") + StringPrintf("%.17g", S(r, c));
    block += "]\n";
  }
  testing::TempDir dir;
  const std::string path = dir.Write("camchain.yaml", WithBlock(camchain, block, ""));
  const auto covariances = ReadCamchainCovariances(path, ReadCamchainYaml(path));
  ASSERT_TRUE(covariances[0].has_value());
  EXPECT_FALSE(covariances[1].has_value());
  EXPECT_TRUE(std::isnan(covariances[0]->block_seconds));
  EXPECT_NEAR(covariances[0]->matrix(7, 7), S(7, 7), 1e-16);
}

// The message of the Error reading `text`'s covariances ("" when none).
std::string ErrorOf(const std::string& text) {
  testing::TempDir dir;
  const std::string path = dir.Write("camchain.yaml", text);
  try {
    ReadCamchainCovariances(path, ReadCamchainYaml(path));
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReadCamchainCovariances, RefusesMalformedBlocksNamingFileAndCamera) {
  const Camchain camchain = TwoCameras();
  CameraCovariance good;
  good.intrinsics = {0, 1, 2, 3, 6, 7, 8, 9};
  good.matrix = SomeCovariance(8);
  const std::string text = CameraCovarianceYamlText(camchain[0].camera, good, 4);
  // Names of another model (ds) for the pinhole-radtan camera.
  std::string names = text;
  names.replace(names.find("fu, fv"), 6, "xi, fv");
  EXPECT_THAT(ErrorOf(WithBlock(camchain, names, "")),
              AllOf(HasSubstr("camchain.yaml:"), HasSubstr("cam0/splinecal_covariance/parameters"),
                    HasSubstr("'xi', expected 'fu'")));
  // Too few names.
  EXPECT_THAT(ErrorOf(WithBlock(camchain, "", [&] {
                std::string t = CameraCovarianceYamlText(camchain[1].camera, good, 4);
                t.replace(t.find(", p2]"), 5, "]");
                return t;
              }())),
              AllOf(HasSubstr("cam1/splinecal_covariance/parameters"), HasSubstr("7 names")));
  // Not symmetric.
  CameraCovariance asymmetric = good;
  asymmetric.matrix(0, 1) *= 1.5;
  EXPECT_THAT(ErrorOf(WithBlock(camchain, CameraCovarianceYamlText(camchain[0].camera, asymmetric, 4), "")),
              AllOf(HasSubstr("cam0/splinecal_covariance/matrix"), HasSubstr("not symmetric")));
  // Symmetric but not positive definite: a correlation of 1.5.
  CameraCovariance indefinite = good;
  indefinite.matrix(0, 1) = indefinite.matrix(1, 0) =
      1.5 * std::sqrt(good.matrix(0, 0) * good.matrix(1, 1));
  EXPECT_THAT(ErrorOf(WithBlock(camchain, CameraCovarianceYamlText(camchain[0].camera, indefinite, 4), "")),
              AllOf(HasSubstr("cam0/splinecal_covariance/matrix"),
                    HasSubstr("not positive definite")));
  // A negative variance.
  CameraCovariance negative = good;
  negative.matrix(2, 2) = -1.0;
  EXPECT_THAT(ErrorOf(WithBlock(camchain, CameraCovarianceYamlText(camchain[0].camera, negative, 4), "")),
              HasSubstr("the variance of pu is -1, not positive"));
  // T_cn_cnm1 rows for cam0.
  CameraCovariance chain = good;
  chain.has_T_cn_cnm1 = true;
  chain.matrix = SomeCovariance(14);
  EXPECT_THAT(ErrorOf(WithBlock(camchain, CameraCovarianceYamlText(camchain[0].camera, chain, 4), "")),
              HasSubstr("T_cn_cnm1 rows for cam0"));
  // A matrix of the wrong size.
  std::string small = CameraCovarianceYamlText(camchain[0].camera, good, 4);
  small = small.substr(0, small.rfind("      - ["));
  EXPECT_THAT(ErrorOf(WithBlock(camchain, small, "")), HasSubstr("expected 8x8"));
}

}  // namespace
}  // namespace splinecal
