// The exporters against what each project publishes for the EuRoC rig. The expected numbers are
// facts copied from the named files (their text and code are not used):
//   OpenVINS    config/euroc_mav/kalibr_imucam_chain.yaml, kalibr_imu_chain.yaml (rpng/open_vins)
//   VINS-Fusion config/euroc/euroc_stereo_imu_config.yaml (HKUST-Aerial-Robotics/VINS-Fusion)
//   basalt      data/euroc_ds_calib.json (VladyslavUsenko/basalt), calibration B of
//               ../shared/data/euroc_imu_april/REFERENCE.md
// The OpenVINS and VINS-Fusion files hold the dataset's Kalibr calibration, which data/ bundles as
// euroc_april_frames/camchain_euroc.yaml (T_cam_imu, the inverse of what they publish).
#include "splinecal/io/calibration_export.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/yaml_document.h"
#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using testing::BundledDataPath;
using testing::TempDir;

// OpenVINS' and VINS-Fusion's T_imu_cam / body_T_cam (camera into IMU), row by row.
constexpr double kPublishedTImuCam0[3][4] = {
    {0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975},
    {0.999557249008, 0.0149672133247, 0.025715529948, -0.064676986768},
    {-0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949}};
constexpr double kPublishedTImuCam1[3][4] = {
    {0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556},
    {0.999598781151, 0.0130119051815, 0.0251588363115, 0.0453689425024},
    {-0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038}};
// The published values have 12 significant digits and camchain_euroc.yaml's T_cam_imu as many;
// inverting a 12-digit transform moves the result by a few 1e-12: 1e-10 is "within printed
// precision" with room for that and nothing more.
constexpr double kPoseTolerance = 1e-10;

CalibrationExport EurocKalibrCalibration() {
  CalibrationExport calibration;
  calibration.camchain = ReadCamchainYaml(BundledDataPath("euroc_april_frames/camchain_euroc.yaml"));
  calibration.camchain[0].cam_overlaps = {1};
  calibration.camchain[1].cam_overlaps = {0};
  calibration.imu_noise = ReadImuYaml(BundledDataPath("euroc_v1_01_easy_20s/sensor.yaml"));
  return calibration;
}

const std::string& Contents(const std::vector<OutputFile>& files, const std::string& name) {
  return OutputFileContents(files, name);
}

// Writes `text` and reads it back with splinecal's YAML layer (which takes OpenCV's %YAML:1.0
// header and !!opencv-matrix, as OpenVINS and VINS read them).
YamlDocument ReadBack(const TempDir& dir, const std::string& name, const std::string& text) {
  return YamlDocument(dir.Write(name, text));
}

void ExpectPose(const std::vector<std::vector<double>>& rows, const double expected[3][4]) {
  ASSERT_EQ(rows.size(), 4u);
  for (int r = 0; r < 3; ++r) {
    ASSERT_EQ(rows[r].size(), 4u);
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(rows[r][c], expected[r][c], kPoseTolerance) << "row " << r << " col " << c;
    }
  }
}

TEST(ExportOpenVins, EurocEqualsOpenVinsPublishedChainValueByValue) {
  const std::vector<OutputFile> files =
      ExportCalibration(EurocKalibrCalibration(), ExportFormat::kOpenVins);
  TempDir dir;
  const std::string& chain_text = Contents(files, "kalibr_imucam_chain.yaml");
  EXPECT_EQ(chain_text.rfind("%YAML:1.0\n", 0), 0u) << "OpenCV FileStorage needs its header";
  const YamlDocument chain = ReadBack(dir, "kalibr_imucam_chain.yaml", chain_text);
  ExpectPose(chain.Rows("cam0/T_imu_cam"), kPublishedTImuCam0);
  ExpectPose(chain.Rows("cam1/T_imu_cam"), kPublishedTImuCam1);
  EXPECT_EQ(chain.Numbers("cam0/cam_overlaps"), std::vector<double>({1}));
  EXPECT_EQ(chain.Numbers("cam1/cam_overlaps"), std::vector<double>({0}));
  EXPECT_EQ(chain.String("cam0/camera_model"), "pinhole");
  EXPECT_EQ(chain.String("cam0/distortion_model"), "radtan");
  EXPECT_EQ(chain.Numbers("cam0/intrinsics"),
            std::vector<double>({458.654, 457.296, 367.215, 248.375}));
  EXPECT_EQ(chain.Numbers("cam1/intrinsics"),
            std::vector<double>({457.587, 456.134, 379.999, 255.238}));
  EXPECT_EQ(chain.Numbers("cam0/distortion_coeffs"),
            std::vector<double>({-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05}));
  // cam1's p2: OpenVINS prints -3.55590700e-05, the bundled camchain -3.555e-05 (rounded by the
  // dataset's README): 9e-9 apart, so this coefficient is compared at 1e-8.
  const std::vector<double> cam1_distortion = chain.Numbers("cam1/distortion_coeffs");
  const double published_cam1[4] = {-0.28368365, 0.07451284, -0.00010473, -3.55590700e-05};
  ASSERT_EQ(cam1_distortion.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(cam1_distortion[k], published_cam1[k], 1e-8) << k;
  EXPECT_EQ(chain.Numbers("cam0/resolution"), std::vector<double>({752, 480}));
  EXPECT_EQ(chain.String("cam0/rostopic"), "/cam0/image_raw");
  EXPECT_EQ(chain.String("cam1/rostopic"), "/cam1/image_raw");
  EXPECT_EQ(chain.Number("cam0/timeshift_cam_imu"), 0.0);

  const YamlDocument imu = ReadBack(dir, "kalibr_imu_chain.yaml",
                                    Contents(files, "kalibr_imu_chain.yaml"));
  EXPECT_EQ(imu.Number("imu0/accelerometer_noise_density"), 2.0e-3);
  EXPECT_EQ(imu.Number("imu0/accelerometer_random_walk"), 3.0e-3);
  EXPECT_EQ(imu.Number("imu0/gyroscope_noise_density"), 1.6968e-04);
  EXPECT_EQ(imu.Number("imu0/gyroscope_random_walk"), 1.9393e-05);
  EXPECT_EQ(imu.Number("imu0/update_rate"), 200.0);
  EXPECT_EQ(imu.String("imu0/rostopic"), "/imu0");
  EXPECT_EQ(imu.String("imu0/model"), "kalibr");
  EXPECT_EQ(imu.Number("imu0/time_offset"), 0.0);
  const std::vector<std::vector<double>> tg = imu.Rows("imu0/Tg");
  for (const auto& row : tg) EXPECT_EQ(row, std::vector<double>({0, 0, 0}));
}

TEST(ExportVins, EurocExtrinsicsAndTdEqualVinsFusionsConfig) {
  const std::vector<OutputFile> files =
      ExportCalibration(EurocKalibrCalibration(), ExportFormat::kVins);
  TempDir dir;
  const YamlDocument config =
      ReadBack(dir, "vins_config.yaml", Contents(files, "vins_config.yaml"));
  ExpectPose(config.Rows("body_T_cam0"), kPublishedTImuCam0);
  ExpectPose(config.Rows("body_T_cam1"), kPublishedTImuCam1);
  EXPECT_EQ(config.Number("td"), 0.0);
  EXPECT_EQ(config.Integer("num_of_cam"), 2);
  EXPECT_EQ(config.String("imu_topic"), "/imu0");
  EXPECT_EQ(config.String("image1_topic"), "/cam1/image_raw");
  EXPECT_EQ(config.String("cam1_calib"), "cam1.yaml");
  EXPECT_EQ(config.Integer("image_width"), 752);
  // Kalibr's densities, unchanged (the published file's acc_n 0.1 etc. are hand-inflated).
  EXPECT_EQ(config.Number("acc_n"), 2.0e-3);
  EXPECT_EQ(config.Number("gyr_w"), 1.9393e-05);

  const YamlDocument cam0 = ReadBack(dir, "cam0.yaml", Contents(files, "cam0.yaml"));
  EXPECT_EQ(cam0.String("model_type"), "PINHOLE");
  EXPECT_EQ(cam0.Number("projection_parameters/fx"), 458.654);
  EXPECT_EQ(cam0.Number("projection_parameters/cy"), 248.375);
  EXPECT_EQ(cam0.Number("distortion_parameters/k1"), -0.28340811);
  EXPECT_EQ(cam0.Number("distortion_parameters/p2"), 1.76187114e-05);
  EXPECT_EQ(cam0.Integer("image_height"), 480);
}

// basalt's published double-sphere calibration (REFERENCE.md's B), T_imu_cam and intrinsics.
struct BasaltCamera {
  double p[3];
  double q[4];  // x, y, z, w
  double intrinsics[6];  // fx fy cx cy xi alpha
};
constexpr BasaltCamera kBasaltEuroc[2] = {
    {{-0.016774788924641534, -0.068938940687127, 0.005139123188382424},
     {-0.007239825785317818, 0.007541278561558601, 0.7017845426564943, 0.7123125505904486},
     {349.7560023050409, 348.72454229977037, 365.89440762590149, 249.32995565708704,
      -0.2409573942178872, 0.566996899163044}},
    {{-0.01507436282032619, 0.0412627204046637, 0.00316287258752953},
     {-0.0023360576185881625, 0.013000769689092388, 0.7024677108343111, 0.7115930283929829},
     {361.6713883800533, 360.5856493689301, 379.40818394080869, 255.9772968522045,
      -0.21300835384809328, 0.5767008625037023}}};
constexpr double kBasaltAccelBias[3] = {0.001725405479279035, 0.1500005286487319,
                                        0.06708820471592454};
constexpr double kBasaltGyroBias[3] = {-0.002186848441668376, 0.024427823167917037,
                                       0.07668367023977922};

TEST(ExportBasalt, DoubleSphereCalibrationEqualsBasaltsPublishedFile) {
  CalibrationExport calibration;
  for (const BasaltCamera& b : kBasaltEuroc) {
    CameraCalibration c;
    c.camera.projection = ProjectionModel::kDoubleSphere;
    c.camera.fu = b.intrinsics[0];
    c.camera.fv = b.intrinsics[1];
    c.camera.pu = b.intrinsics[2];
    c.camera.pv = b.intrinsics[3];
    c.camera.projection_params = Eigen::Vector2d(b.intrinsics[4], b.intrinsics[5]);
    c.camera.width = 752;
    c.camera.height = 480;
    const SE3d T_imu_cam(SO3d::FromQuaternion(Eigen::Quaterniond(b.q[3], b.q[0], b.q[1], b.q[2])),
                         Eigen::Vector3d(b.p[0], b.p[1], b.p[2]));
    c.T_cam_imu = T_imu_cam.inverse();
    calibration.camchain.push_back(c);
  }
  calibration.accel_bias = Eigen::Vector3d(kBasaltAccelBias);
  calibration.gyro_bias = Eigen::Vector3d(kBasaltGyroBias);

  const std::vector<OutputFile> files = ExportCalibration(calibration, ExportFormat::kBasalt);
  const YAML::Node json = YAML::Load(Contents(files, "calibration.json"))["value0"];
  ASSERT_TRUE(json.IsMap());
  // Two inversions of a pose given to 16 digits: 1e-12 is within its printed precision.
  constexpr double kTolerance = 1e-12;
  for (int i = 0; i < 2; ++i) {
    const BasaltCamera& b = kBasaltEuroc[i];
    const YAML::Node pose = json["T_imu_cam"][i];
    const char* p_names[3] = {"px", "py", "pz"};
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(pose[p_names[k]].as<double>(), b.p[k], kTolerance);
    // q and -q are the same rotation; basalt's file has qw > 0, and so must the export.
    const char* q_names[4] = {"qx", "qy", "qz", "qw"};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(pose[q_names[k]].as<double>(), b.q[k], kTolerance);
    const YAML::Node camera = json["intrinsics"][i];
    EXPECT_EQ(camera["camera_type"].as<std::string>(), "ds");
    const char* names[6] = {"fx", "fy", "cx", "cy", "xi", "alpha"};
    for (int k = 0; k < 6; ++k) {
      EXPECT_EQ(camera["intrinsics"][names[k]].as<double>(), b.intrinsics[k]) << names[k];
    }
    EXPECT_EQ(json["resolution"][i][0].as<int>(), 752);
    EXPECT_EQ(json["resolution"][i][1].as<int>(), 480);
  }
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(json["calib_accel_bias"][k].as<double>(), kBasaltAccelBias[k]);
    EXPECT_EQ(json["calib_gyro_bias"][k].as<double>(), kBasaltGyroBias[k]);
  }
  EXPECT_EQ(json["calib_accel_bias"].size(), 9u);
  EXPECT_EQ(json["calib_gyro_bias"].size(), 12u);
  EXPECT_EQ(json["imu_update_rate"].as<double>(), 200.0);
  EXPECT_EQ(json["cam_time_offset_ns"].as<int64_t>(), 0);
}

TEST(ExportBasalt, OmniBecomesTheUnifiedModelWithTheSameProjection) {
  // Kalibr's omni (xi, fu) and basalt's ucm (alpha, fx) put every ray on the same pixel when
  // fx = fu / (1 + xi) and alpha = xi / (1 + xi): check it on rays across a wide field.
  CalibrationExport calibration;
  CameraCalibration c;
  c.camera.projection = ProjectionModel::kOmni;
  c.camera.fu = 750.0;
  c.camera.fv = 745.0;
  c.camera.pu = 320.0;
  c.camera.pv = 240.0;
  c.camera.projection_params = Eigen::Vector2d(0.9, 0.0);
  c.camera.width = 640;
  c.camera.height = 480;
  calibration.camchain.push_back(c);
  const YAML::Node json =
      YAML::Load(Contents(ExportCalibration(calibration, ExportFormat::kBasalt),
                          "calibration.json"))["value0"]["intrinsics"][0];
  EXPECT_EQ(json["camera_type"].as<std::string>(), "ucm");
  const double fx = json["intrinsics"]["fx"].as<double>();
  const double fy = json["intrinsics"]["fy"].as<double>();
  const double alpha = json["intrinsics"]["alpha"].as<double>();
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.1, -0.2, 1.0), Eigen::Vector3d(1.5, 0.7, 0.4),
                                   Eigen::Vector3d(-2.0, 1.0, 0.1)}) {
    Eigen::Vector2d uv;
    ASSERT_TRUE(c.camera.Project(p, &uv));
    const double den = alpha * p.norm() + (1.0 - alpha) * p.z();
    EXPECT_NEAR(fx * p.x() / den + c.camera.pu, uv.x(), 1e-9);
    EXPECT_NEAR(fy * p.y() / den + c.camera.pv, uv.y(), 1e-9);
  }
}

TEST(ExportCalibration, AModelTheFormatCannotHoldIsRefusedNamingTheOnesItCan) {
  CalibrationExport calibration = EurocKalibrCalibration();
  try {
    ExportCalibration(calibration, ExportFormat::kBasalt);
    FAIL() << "basalt has no 4-coefficient radtan";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("basalt cannot hold cam0's camera model pinhole-radtan"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("ds-none"), std::string::npos) << e.what();
  }
  calibration.camchain[0].camera.projection = ProjectionModel::kDoubleSphere;
  calibration.camchain[0].camera.distortion = DistortionModel::kNone;
  EXPECT_THROW(ExportCalibration(calibration, ExportFormat::kVins), Error);
  EXPECT_THROW(ExportCalibration(calibration, ExportFormat::kOpenVins), Error);
}

TEST(ExportCalibration, VinsRefusesCamerasWhoseTimeOffsetsDiffer) {
  CalibrationExport calibration = EurocKalibrCalibration();
  calibration.camchain[1].time_offset_s = 0.002;
  EXPECT_THROW(ExportCalibration(calibration, ExportFormat::kVins), Error);
  calibration.camchain[1].time_offset_s = 0.00001;  // within VINS' one td
  EXPECT_NO_THROW(ExportCalibration(calibration, ExportFormat::kVins));
}

TEST(ExportKalibr, WritesBackWhatItReadsWithTopicsAndOverlaps) {
  const CalibrationExport calibration = EurocKalibrCalibration();
  const std::vector<OutputFile> files = ExportCalibration(calibration, ExportFormat::kKalibr);
  TempDir dir;
  const Camchain back =
      ReadCamchainYaml(dir.Write("camchain-imucam.yaml", Contents(files, "camchain-imucam.yaml")));
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[1].cam_overlaps, std::vector<int>({0}));
  EXPECT_EQ(back[1].rostopic, "/cam1/image_raw");
  EXPECT_TRUE(back[1].T_cam_imu.matrix().isApprox(calibration.camchain[1].T_cam_imu.matrix(), 1e-15));
  const ImuNoise noise = ReadImuYaml(dir.Write("imu.yaml", Contents(files, "imu.yaml")));
  EXPECT_EQ(noise.gyroscope_noise_density, calibration.imu_noise.gyroscope_noise_density);
}

TEST(ReadCalibrationForExport, ReadsCalibratesFolderAndItsNoise) {
  TempDir dir;
  dir.Write("camchain-imucam.yaml",
            testing::ReadFileText(BundledDataPath("euroc_april_frames/camchain_euroc.yaml")));
  dir.Write("result.yaml",
            "gyro_bias: [0.001, 0.002, 0.003]\naccel_bias: [0.1, 0.2, 0.3]\nimu_rate_hz: 199.5\n"
            "imu_noise:\n"
            "  gyroscope_noise_density: {used: 0.0002}\n"
            "  gyroscope_random_walk: {used: 0.00002}\n"
            "  accelerometer_noise_density: {used: 0.003}\n"
            "  accelerometer_random_walk: {used: 0.004}\n");
  const CalibrationExport calibration = ReadCalibrationForExport(dir.path());
  EXPECT_TRUE(calibration.has_imu);
  EXPECT_EQ(calibration.camchain.size(), 2u);
  EXPECT_EQ(calibration.gyro_bias, Eigen::Vector3d(0.001, 0.002, 0.003));
  EXPECT_EQ(calibration.accel_bias, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(calibration.imu_noise.accelerometer_random_walk, 0.004);
  EXPECT_EQ(calibration.imu_noise.update_rate_hz, 199.5);
  // A named imu.yaml wins over result.yaml, rate included.
  const CalibrationExport named = ReadCalibrationForExport(
      dir.path(), BundledDataPath("euroc_v1_01_easy_20s/sensor.yaml"));
  EXPECT_EQ(named.imu_noise.accelerometer_random_walk, 3.0e-3);
  EXPECT_EQ(named.imu_noise.update_rate_hz, 200.0);
}

TEST(ReadCalibrationForExport, AFolderWithoutACamchainIsRefusedNamingIt) {
  TempDir dir;
  try {
    ReadCalibrationForExport(dir.path());
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(dir.path()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("camchain-imucam.yaml"), std::string::npos) << e.what();
  }
}

TEST(ExportCalibration, FormatNamesRoundTrip) {
  for (const char* name : {"openvins", "vins", "basalt", "kalibr"}) {
    ExportFormat format;
    ASSERT_TRUE(ParseExportFormat(name, &format)) << name;
    EXPECT_EQ(ExportFormatName(format), name);
  }
  ExportFormat format = ExportFormat::kKalibr;
  EXPECT_FALSE(ParseExportFormat("OpenVINS", &format));
  EXPECT_EQ(format, ExportFormat::kKalibr);
}

}  // namespace
}  // namespace splinecal
