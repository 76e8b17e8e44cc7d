#include "splinecal/io/yaml_document.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/io/kalibr_yaml.h"
#include "testing/paths.h"
#include "testing/refusals.h"
#include "testing/shared_data.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

using testing::ErrorOf;

TEST(YamlDocument, OpenCvHeaderMatricesAndRows) {
  TempDir dir;
  const std::string path = dir.Write("s.yaml",
                                     "%YAML:1.0\n"
                                     "T_BS:\n  cols: 2\n  rows: 2\n  data: [1, 2,\n         3, 4]\n"
                                     "cam0:\n  T_cam_imu:\n  - [1, 0]\n  - [0, 1]\n"
                                     "  intrinsics: [400, 401, 320, 240]\n");
  const YamlDocument yaml(path);
  EXPECT_THAT(yaml.Rows("T_BS"), ::testing::ElementsAre(std::vector<double>{1, 2},
                                                        std::vector<double>{3, 4}));
  EXPECT_THAT(yaml.Rows("cam0/T_cam_imu")[1], ::testing::ElementsAre(0.0, 1.0));
  EXPECT_THAT(yaml.Numbers("cam0/intrinsics"), ::testing::ElementsAre(400, 401, 320, 240));
  EXPECT_FALSE(yaml.Has("cam1"));
  EXPECT_THAT(yaml.TopLevelKeys(), ::testing::ElementsAre("T_BS", "cam0"));
}

TEST(YamlDocument, ErrorsNameTheLine) {
  TempDir dir;
  const std::string path = dir.Write("a.yaml", "a: 1\nb: abc\nc:\n  d: [1, x]\n");
  const YamlDocument yaml(path);
  EXPECT_THAT(ErrorOf([&] { yaml.Number("b"); }), HasSubstr("a.yaml:2: 'b' must be a number, got 'abc'"));
  EXPECT_THAT(ErrorOf([&] { yaml.Numbers("c/d"); }), HasSubstr("a.yaml:4: 'c/d' must be a number"));
  EXPECT_THAT(ErrorOf([&] { yaml.Number("zz"); }), HasSubstr("missing key 'zz'"));
  EXPECT_THAT(ErrorOf([&] { YamlDocument bad(dir.Write("b.yaml", "a: [1, 2\nb: 3\n")); }),
              HasSubstr("b.yaml:"));
  EXPECT_THAT(ErrorOf([&] { YamlDocument bad(dir.Write("c.yaml", "- 1\n- 2\n")); }),
              HasSubstr("expected a YAML map"));
}

TEST(YamlDocument, NonFiniteImplausibleAndTyposNameTheLine) {
  TempDir dir;
  const std::string path = dir.Write("a.yaml",
                                     "a: .nan\nb: 1e999\nc: [1, 2e300]\nd: 5\n"
                                     "cam0:\n  intrinsic: [1, 2]\n  Rostopic: x\n"
                                     "points:\n  - [0, 1]\n  - [2, 3]\n");
  const YamlDocument yaml(path);
  EXPECT_THAT(ErrorOf([&] { yaml.Number("a"); }), HasSubstr("a.yaml:1: 'a' is not finite"));
  EXPECT_THAT(ErrorOf([&] { yaml.Number("b"); }), HasSubstr("a.yaml:2: 'b' is not finite"));
  EXPECT_THAT(ErrorOf([&] { yaml.BoundedNumbers("c", 1e6, "px"); }),
              HasSubstr("a.yaml:3: 'c' value 2e+300 is beyond the plausible 1e+06 px"));
  EXPECT_EQ(yaml.BoundedNumber("d", 10.0, "m"), 5.0);
  EXPECT_THAT(ErrorOf([&] { yaml.PositiveNumber("d", 1.0, "m"); }),
              HasSubstr("a.yaml:4: 'd' value 5 is beyond the plausible 1 m"));
  EXPECT_EQ(yaml.Line("d"), 4);
  EXPECT_EQ(yaml.Line("points/1"), 10);
  EXPECT_EQ(yaml.Line("nope"), 0);
  // A near miss of a known key the map lacks is a typo; other unknown keys are ignored.
  EXPECT_THAT(ErrorOf([&] { yaml.CheckTypos("cam0", {"intrinsics", "rostopic"}); }),
              HasSubstr("a.yaml:6: unknown key 'cam0/intrinsic': did you mean 'intrinsics'?"));
  EXPECT_THAT(ErrorOf([&] { yaml.CheckTypos("cam0", {"rostopic"}); }),
              HasSubstr("a.yaml:7: unknown key 'cam0/Rostopic': did you mean 'rostopic'?"));
  EXPECT_EQ(ErrorOf([&] { yaml.CheckTypos("", {"points", "e"}); }), "no error");
}

TEST(ReadImuYaml, EurocSensorFileWithOpenCvHeader) {
  const std::string path =
      testing::SharedDataDir() + "/euroc_v1_01_easy/sensor.yaml";
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_v1_01_easy/sensor.yaml");
  const ImuNoise noise = ReadImuYaml(path);
  EXPECT_DOUBLE_EQ(noise.gyroscope_noise_density, 1.6968e-4);
  EXPECT_DOUBLE_EQ(noise.gyroscope_random_walk, 1.9393e-5);
  EXPECT_DOUBLE_EQ(noise.accelerometer_noise_density, 2.0e-3);
  EXPECT_DOUBLE_EQ(noise.accelerometer_random_walk, 3.0e-3);
  EXPECT_DOUBLE_EQ(noise.update_rate_hz, 200.0);
}

TEST(ReadImuYaml, WrittenTextReadsBack) {
  TempDir dir;
  ImuNoise noise;
  noise.gyroscope_noise_density = 1.0 / 3.0;
  noise.update_rate_hz = 400;
  const ImuNoise read = ReadImuYaml(dir.Write("imu.yaml", ImuYamlText(noise)));
  EXPECT_EQ(read.gyroscope_noise_density, noise.gyroscope_noise_density);
  EXPECT_EQ(read.accelerometer_random_walk, noise.accelerometer_random_walk);
  EXPECT_EQ(read.update_rate_hz, 400);
}

TEST(ReadImuYaml, NegativeOrMissingDensityIsRefused) {
  TempDir dir;
  EXPECT_THAT(ErrorOf([&] {
                ReadImuYaml(dir.Write("a.yaml",
                                      "accelerometer_noise_density: -1\n"
                                      "accelerometer_random_walk: 1\n"
                                      "gyroscope_noise_density: 1\ngyroscope_random_walk: 1\n"));
              }),
              HasSubstr("a.yaml:1: 'accelerometer_noise_density' must be positive"));
  EXPECT_THAT(ErrorOf([&] { ReadImuYaml(dir.Write("b.yaml", "update_rate: 200\n")); }),
              HasSubstr("missing key 'accelerometer_noise_density'"));
}

}  // namespace
}  // namespace splinecal
