#include "splinecal/io/camchain_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "camera/camera_test_models.h"
#include "splinecal/error.h"
#include "testing/paths.h"
#include "testing/refusals.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

// EuRoC's cam0 sensor.yaml values in Kalibr's camchain-imucam layout, with OpenCV's first line,
// CRLF line ends and a comment.
constexpr char kKalibrCamchain[] =
    "%YAML:1.0\r\n"
    "# written by kalibr\r\n"
    "cam0:\r\n"
    "  T_cam_imu:\r\n"
    "  - [0.0148655429818, 0.999557249008, -0.0257744366974, 0.0652229868707]\r\n"
    "  - [-0.999880929698, 0.0149672133247, 0.00375618835797, -0.0207063833366]\r\n"
    "  - [0.00414029679422, 0.0257155299480, 0.999660727178, -0.0080546014540]\r\n"
    "  - [0.0, 0.0, 0.0, 1.0]\r\n"
    "  cam_overlaps: []\r\n"
    "  camera_model: pinhole\r\n"
    "  distortion_coeffs: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]\r\n"
    "  distortion_model: radtan\r\n"
    "  intrinsics: [458.654, 457.296, 367.215, 248.375]\r\n"
    "  resolution: [752, 480]\r\n"
    "  rostopic: /cam0/image_raw\r\n"
    "  timeshift_cam_imu: 0.0012\r\n"
    "  line_delay: 2.5e-5\r\n";

TEST(ReadCamchainYaml, ReadsKalibrCamchainImucam) {
  testing::TempDir dir;
  const Camchain camchain = ReadCamchainYaml(dir.Write("camchain.yaml", kKalibrCamchain));
  ASSERT_EQ(camchain.size(), 1u);
  const CameraCalibration& c = camchain[0];
  EXPECT_EQ(c.camera.fu, 458.654);
  EXPECT_EQ(c.camera.pv, 248.375);
  EXPECT_EQ(c.camera.distortion, DistortionModel::kRadTan);
  EXPECT_EQ(c.camera.distortion_coeffs(3), 1.76187114e-05);
  EXPECT_EQ(c.camera.width, 752);
  EXPECT_EQ(c.camera.height, 480);
  EXPECT_EQ(c.time_offset_s, 0.0012);
  EXPECT_EQ(c.line_delay_s, 2.5e-5);
  EXPECT_EQ(c.rostopic, "/cam0/image_raw");
  EXPECT_NEAR(c.T_cam_imu.translation().x(), 0.0652229868707, 1e-15);
  EXPECT_NEAR(c.T_cam_imu.rotationMatrix()(1, 0), -0.999880929698, 1e-9);
}

TEST(ReadCamchainYaml, DefaultsWithoutImuKeys) {
  testing::TempDir dir;
  const Camchain camchain = ReadCamchainYaml(dir.Write(
      "camchain.yaml",
      "cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
      "  distortion_model: none\n  distortion_coeffs: []\n  resolution: [640, 480]\n"
      "cam1:\n  camera_model: pinhole\n  intrinsics: [300, 300, 320, 240]\n"
      "  distortion_model: equidistant\n  distortion_coeffs: [0.01, 0.002, -0.001, 0.0003]\n"
      "  resolution: [640, 480]\n"));
  ASSERT_EQ(camchain.size(), 2u);
  EXPECT_EQ(camchain[0].camera.distortion, DistortionModel::kNone);
  EXPECT_EQ(camchain[0].T_cam_imu.matrix(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(camchain[0].time_offset_s, 0.0);
  EXPECT_EQ(camchain[0].line_delay_s, 0.0);
  EXPECT_EQ(camchain[1].camera.distortion, DistortionModel::kEquidistant);
  EXPECT_EQ(camchain[1].camera.distortion_coeffs(2), -0.001);
}

TEST(CamchainYamlText, RoundTripsExactly) {
  testing::TempDir dir;
  Camchain camchain = ReadCamchainYaml(dir.Write("in.yaml", kKalibrCamchain));
  camchain[0].T_cam_imu = camchain[0].T_cam_imu *
                          SE3d::Exp((Vector6d() << 0.01, -0.02, 0.03, 0.1, 0.2, -0.3).finished());
  camchain[0].time_offset_s = -1.0 / 3.0;
  camchain[0].line_delay_s = 1.0 / 30000.0;
  const std::string text = CamchainYamlText(camchain);
  const Camchain back = ReadCamchainYaml(dir.Write("out.yaml", text));
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].camera.intrinsics(), camchain[0].camera.intrinsics());
  EXPECT_EQ(back[0].camera.width, 752);
  EXPECT_EQ(back[0].time_offset_s, camchain[0].time_offset_s);
  EXPECT_EQ(back[0].line_delay_s, camchain[0].line_delay_s);
  EXPECT_LT((back[0].T_cam_imu.matrix() - camchain[0].T_cam_imu.matrix()).cwiseAbs().maxCoeff(),
            1e-15);
  EXPECT_EQ(back[0].rostopic, "/cam0/image_raw");
  EXPECT_THAT(text, HasSubstr("camera_model: \"pinhole\""));
  EXPECT_THAT(text, HasSubstr("distortion_model: \"radtan\""));
}

// T_cn_cnm1 as written for camera `cam` of `text`.
Eigen::Matrix4d WrittenTcnCnm1(const std::string& text, const std::string& cam) {
  const YAML::Node rows = testing::LoadStrictYaml(text)[cam]["T_cn_cnm1"];
  Eigen::Matrix4d T = Eigen::Matrix4d::Zero();
  EXPECT_EQ(rows.size(), 4u) << cam << "\n" << text;
  for (size_t r = 0; r < rows.size() && r < 4; ++r) {
    for (int c = 0; c < 4; ++c) T(r, c) = rows[r][c].as<double>();
  }
  return T;
}

TEST(CamchainYamlText, SeveralCamerasGetTheTcnCnm1TheirTCamImuImply) {
  testing::TempDir dir;
  Camchain camchain = ReadCamchainYaml(dir.Write("in.yaml", kKalibrCamchain));
  CameraCalibration cam1 = camchain[0];
  cam1.T_cam_imu = SE3d::Exp((Vector6d() << -0.11, 0.002, 0.001, 0.01, -0.02, 0.005).finished()) *
                   camchain[0].T_cam_imu;
  cam1.rostopic = "/cam1/image_raw";
  CameraCalibration cam2 = cam1;
  cam2.T_cam_imu =
      SE3d::Exp((Vector6d() << 0.0, -0.1, 0.0, 0.3, 0.0, 0.0).finished()) * cam1.T_cam_imu;
  camchain.push_back(cam1);
  camchain.push_back(cam2);
  const std::string text = CamchainYamlText(camchain);
  EXPECT_FALSE(testing::LoadStrictYaml(text)["cam0"]["T_cn_cnm1"]);  // Kalibr writes none for cam0
  for (size_t n = 1; n < camchain.size(); ++n) {
    const Eigen::Matrix4d expected =
        (camchain[n].T_cam_imu * camchain[n - 1].T_cam_imu.inverse()).matrix();
    const Eigen::Matrix4d written = WrittenTcnCnm1(text, "cam" + std::to_string(n));
    // 17 significant digits: the text holds the double's value.
    EXPECT_LT((written - expected).cwiseAbs().maxCoeff(), 1e-15) << n;
  }
  // It reads back (the key is known, not a typo). Reading re-orthonormalises the rotations,
  // which moves entries by a few ulps (up to ~7e-16 here): the round trip holds to 1e-14.
  const Camchain back = ReadCamchainYaml(dir.Write("out.yaml", text));
  ASSERT_EQ(back.size(), 3u);
  const std::string again = CamchainYamlText(back);
  for (const std::string cam : {"cam1", "cam2"}) {
    EXPECT_LT((WrittenTcnCnm1(again, cam) - WrittenTcnCnm1(text, cam)).cwiseAbs().maxCoeff(),
              1e-14);
  }
}

TEST(CamchainYamlText, EurocStereoKeepsItsPublishedTcnCnm1) {
  // The dataset's camchain as bundled (byte-identical to ../shared/data/euroc_imu_april/).
  const std::string path = testing::BundledDataPath("euroc_april_frames/camchain_euroc.yaml");
  const Camchain camchain = ReadCamchainYaml(path);
  ASSERT_EQ(camchain.size(), 2u);
  const std::string published = testing::ReadFileText(path);
  const std::string written = CamchainYamlText(camchain);
  // The file derived its T_cn_cnm1 from its two T_cam_imu and printed 12 digits: they agree to
  // that rounding (the translations are ~0.1 m, so 1e-9 absolute is ~1e-8 relative).
  EXPECT_LT(
      (WrittenTcnCnm1(written, "cam1") - WrittenTcnCnm1(published, "cam1")).cwiseAbs().maxCoeff(),
      1e-9);
}

struct BadCase {
  const char* yaml;
  const char* message;
};

TEST(ReadCamchainYaml, RefusesBadFilesNamingTheKey) {
  const std::string good_tail =
      "  intrinsics: [400, 400, 320, 240]\n  distortion_model: radtan\n"
      "  distortion_coeffs: [0.1, 0.01, 0.0, 0.0]\n  resolution: [640, 480]\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"cam1:\n  camera_model: pinhole\n" + good_tail, "cam0"},
      {"cam0:\n  camera_model: mei\n" + good_tail, "unsupported camera model 'mei'"},
      {"cam0:\n  camera_model: omni\n" + good_tail,
       "the omni model expects 5 numbers [xi, fu, fv, pu, pv], got 4"},
      {"cam0:\n  camera_model: ds\n  intrinsics: [-0.2, 0.57, 350, 349, 366, 249]\n"
       "  distortion_model: radtan\n  distortion_coeffs: [0.1, 0.01, 0.0, 0.0]\n"
       "  resolution: [752, 480]\n",
       "unsupported distortion model 'radtan' for camera model ds (supported: none)"},
      {"cam0:\n  camera_model: ds\n  intrinsics: [-0.2, 1.3, 350, 349, 366, 249]\n"
       "  distortion_model: none\n  resolution: [752, 480]\n",
       "cam0/intrinsics: ds alpha must be in [0, 1]"},
      {"cam0:\n  camera_model: eucm\n  intrinsics: [-0.1, 1.0, 350, 349, 366, 249]\n"
       "  distortion_model: none\n  resolution: [752, 480]\n",
       "cam0/intrinsics: eucm alpha must be in [0, 1]"},
      {"cam0:\n  camera_model: eucm\n  intrinsics: [0.6, 1.0, 350, -349, 366, 249]\n"
       "  distortion_model: none\n  resolution: [752, 480]\n",
       "focal lengths"},
      {"cam0:\n  camera_model: omni\n  intrinsics: [-0.5, 350, 349, 366, 249]\n"
       "  distortion_model: none\n  resolution: [752, 480]\n",
       "omni xi must be >= 0"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: fov\n  distortion_coeffs: [4.0]\n  resolution: [640, 480]\n",
       "cam0/distortion_coeffs: fov w must be in [0, pi)"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: fov\n  distortion_coeffs: [0.9, 0.1]\n  resolution: [640, 480]\n",
       "the fov model takes 1 coefficient, got 2"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: equi\n  distortion_coeffs: [0.1, 0.0, 0.0, 0.0]\n"
       "  resolution: [640, 480]\n",
       "unsupported distortion model 'equi'"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: equidistant\n  distortion_coeffs: [0.1, 0.0, 0.0, 0.0, 0.0]\n"
       "  resolution: [640, 480]\n",
       "the equidistant model takes 4 coefficients, got 5"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320]\n"
       "  distortion_model: none\n  resolution: [640, 480]\n",
       "expects 4 numbers"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [-400, 400, 320, 240]\n"
       "  distortion_model: none\n  resolution: [640, 480]\n",
       "focal lengths"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: radtan\n  distortion_coeffs: [0.1, 0.2]\n  resolution: [640, 480]\n",
       "takes 4 or 5 coefficients, got 2"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: none\n  resolution: [640.5, 480]\n",
       "resolution"},
      {"cam0:\n  camera_model: pinhole\n" + good_tail +
           "  T_cam_imu:\n  - [1, 0, 0, 0]\n  - [0, 2, 0, 0]\n  - [0, 0, 1, 0]\n  - [0, 0, 0, 1]\n",
       "not a rigid transform"},
      {"cam0:\n  camera_model: pinhole\n" + good_tail + "  line_delay: -1e-5\n", "line_delay"},
      {"cam0:\n  camera_model: pinhole\n" + good_tail + "cam2:\n  camera_model: pinhole\n",
       "without gaps"},
      {"cam0:\n  camera_model: pinhole\n  intrinsics: [400, 400, 320, 240]\n"
       "  distortion_model: none\n",
       "resolution"},
  };
  testing::ExpectEachFileRefused(
      cases, "bad.yaml", [](const std::string& path) { ReadCamchainYaml(path); });
}

// Every model of the camera tests (camera/camera_test_models.h) written and read back.
TEST(CamchainYamlText, RoundTripsEveryCameraModelExactly) {
  testing::TempDir dir;
  for (const testing::TestCamera& t : testing::AllTestCameras()) {
    Camchain camchain(1);
    camchain[0].camera = t.camera;
    const std::string text = CamchainYamlText(camchain);
    const Camchain back = ReadCamchainYaml(dir.Write("model.yaml", text));
    ASSERT_EQ(back.size(), 1u);
    const Camera& c = back[0].camera;
    EXPECT_EQ(c.projection, t.camera.projection) << t.label;
    EXPECT_EQ(c.distortion, t.camera.distortion) << t.label;
    EXPECT_EQ(c.radtan_k3, t.camera.radtan_k3) << t.label;
    EXPECT_EQ(c.intrinsics(), t.camera.intrinsics()) << t.label << "\n" << text;
    EXPECT_EQ(c.width, t.camera.width);
    EXPECT_EQ(c.height, t.camera.height);
    EXPECT_EQ(c.model_name(), t.camera.model_name());
  }
}

// The Kalibr order of intrinsics and coefficients, read and written, per camera model.
TEST(ReadCamchainYaml, KalibrParameterOrderOfEveryModel) {
  struct Case {
    const char* model;
    const char* intrinsics;
    const char* distortion;
    const char* coeffs;
    IntrinsicsVector expected;  // splinecal's layout
  };
  auto v = [](std::initializer_list<double> values) {
    IntrinsicsVector k = IntrinsicsVector::Zero();
    int i = 0;
    for (double x : values) k(i++) = x;
    return k;
  };
  const std::vector<Case> cases = {
      {"pinhole", "[401, 402, 321, 241]", "none", "[]", v({401, 402, 321, 241})},
      {"pinhole",
       "[401, 402, 321, 241]",
       "radtan",
       "[-0.28, 0.07, 0.0002, 0.00002]",
       v({401, 402, 321, 241, 0, 0, -0.28, 0.07, 0.0002, 0.00002})},
      {"pinhole",
       "[401, 402, 321, 241]",
       "radtan",
       "[-0.28, 0.07, 0.0002, 0.00002, -0.01]",
       v({401, 402, 321, 241, 0, 0, -0.28, 0.07, 0.0002, 0.00002, -0.01})},
      {"pinhole",
       "[401, 402, 321, 241]",
       "equidistant",
       "[0.01, 0.002, -0.001, 0.0003]",
       v({401, 402, 321, 241, 0, 0, 0.01, 0.002, -0.001, 0.0003})},
      {"pinhole", "[401, 402, 321, 241]", "fov", "[0.92]", v({401, 402, 321, 241, 0, 0, 0.92})},
      {"omni", "[1.8, 401, 402, 321, 241]", "none", "[]", v({401, 402, 321, 241, 1.8})},
      {"omni",
       "[0.8, 401, 402, 321, 241]",
       "radtan",
       "[-0.05, 0.01, 0.0002, -0.0001]",
       v({401, 402, 321, 241, 0.8, 0, -0.05, 0.01, 0.0002, -0.0001})},
      {"eucm", "[0.59, 1.1, 401, 402, 321, 241]", "none", "[]", v({401, 402, 321, 241, 0.59, 1.1})},
      {"ds",
       "[-0.2409573942, 0.5669968992, 349.7560023, 348.7245423, 365.8944076, 249.3299557]",
       "none",
       "[]",
       v({349.7560023, 348.7245423, 365.8944076, 249.3299557, -0.2409573942, 0.5669968992})},
  };
  testing::TempDir dir;
  for (const Case& c : cases) {
    const std::string yaml = std::string("cam0:\n  camera_model: ") + c.model +
                             "\n  intrinsics: " + c.intrinsics +
                             "\n  distortion_model: " + c.distortion +
                             "\n  distortion_coeffs: " + c.coeffs + "\n  resolution: [640, 480]\n";
    const Camchain camchain = ReadCamchainYaml(dir.Write("in.yaml", yaml));
    EXPECT_EQ(camchain[0].camera.intrinsics(), c.expected) << yaml;
    // Written back in the same order (17 significant digits reproduce the decimal inputs).
    const YAML::Node written = testing::LoadStrictYaml(CamchainYamlText(camchain))["cam0"];
    const YAML::Node given = testing::LoadStrictYaml(yaml)["cam0"];
    EXPECT_EQ(written["camera_model"].as<std::string>(), c.model);
    EXPECT_EQ(written["distortion_model"].as<std::string>(), c.distortion);
    for (const char* key : {"intrinsics", "distortion_coeffs"}) {
      ASSERT_EQ(written[key].size(), given[key].size()) << key << "\n" << yaml;
      for (size_t i = 0; i < given[key].size(); ++i) {
        EXPECT_EQ(written[key][i].as<double>(), given[key][i].as<double>()) << key << " " << i;
      }
    }
  }
}

TEST(ReadCamchainYaml, InvalidParametersNameFileLineAndProblem) {
  testing::TempDir dir;
  const std::string path = dir.Write("ds.yaml",
                                     "cam0:\n  camera_model: ds\n"
                                     "  intrinsics: [-0.2, 1.3, 350, 349, 366, 249]\n"
                                     "  distortion_model: none\n  resolution: [752, 480]\n");
  try {
    ReadCamchainYaml(path);
    ADD_FAILURE() << "accepted ds alpha 1.3";
  } catch (const Error& e) {
    EXPECT_EQ(e.path(), path);
    EXPECT_EQ(e.line(), 3);
    EXPECT_THAT(e.message(), HasSubstr("ds alpha must be in [0, 1]"));
  }
}

TEST(ReadCamchainYaml, MissingFileNamesIt) {
  try {
    ReadCamchainYaml("/nonexistent/camchain.yaml");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/camchain.yaml"));
  }
}

}  // namespace
}  // namespace splinecal
