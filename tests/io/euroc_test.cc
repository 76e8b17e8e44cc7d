#include "splinecal/io/euroc.h"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "testing/paths.h"
#include "testing/refusals.h"
#include "testing/shared_data.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

const char kHeader[] =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
    "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";

std::string ImuRows(int count, int64_t period_ns = 5000000) {
  std::string text;
  for (int i = 0; i < count; ++i) {
    text += std::to_string(1403715273262142976LL + i * period_ns) + ",0.1,-0.2,0.3,0.5,0.1,9.8\n";
  }
  return text;
}

std::string ErrorOf(const std::string& path) {
  return testing::ErrorOf([&] { ReadEurocImu(path); });
}

TEST(ReadEurocImu, ReadsRowsExactly) {
  TempDir dir;
  const auto samples = ReadEurocImu(dir.Write("imu.csv", kHeader + ImuRows(3)));
  ASSERT_EQ(samples.size(), 3u);
  EXPECT_EQ(samples[2].t_ns, 1403715273262142976LL + 2 * 5000000);
  EXPECT_EQ(samples[0].gyro, Eigen::Vector3d(0.1, -0.2, 0.3));
  EXPECT_EQ(samples[0].accel, Eigen::Vector3d(0.5, 0.1, 9.8));
}

TEST(ReadEurocImu, WriteThenReadIsBitExact) {
  TempDir dir;
  std::vector<ImuSample> samples(4);
  for (int i = 0; i < 4; ++i) {
    samples[i].t_ns = 1000 + i * int64_t{5000000};  // 200 Hz (readers refuse other units)
    samples[i].gyro = Eigen::Vector3d(1.0 / 3.0, -2e-17, 123.456789) * (i + 1);
    samples[i].accel = Eigen::Vector3d(9.81, 0.1 + i, -std::acos(-1.0));
  }
  std::ostringstream text;
  WriteEurocImu(samples, &text);
  const auto read = ReadEurocImu(dir.Write("imu.csv", text.str()));
  ASSERT_EQ(read.size(), samples.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].t_ns, samples[i].t_ns);
    EXPECT_EQ(read[i].gyro, samples[i].gyro);
    EXPECT_EQ(read[i].accel, samples[i].accel);
  }
}

TEST(ReadEurocImu, HeaderWithoutHashIsSkipped) {
  TempDir dir;
  EXPECT_EQ(ReadEurocImu(dir.Write("imu.csv", "timestamp,wx,wy,wz,ax,ay,az\n" + ImuRows(2))).size(),
            2u);
}

TEST(ReadEurocImu, BadInputNamesFileLineAndProblem) {
  TempDir dir;
  EXPECT_THAT(ErrorOf(dir.Write("a.csv", kHeader + ImuRows(2) + "1,2,3\n")),
              HasSubstr("a.csv:4: expected 7 columns"));
  EXPECT_THAT(ErrorOf(dir.Write("b.csv", kHeader + ImuRows(2) + "1403715273272142976,nan,0,0,0,0,9.8\n")),
              HasSubstr("b.csv:4:21: gyro x: value 'nan' is not a finite number"));
  EXPECT_THAT(ErrorOf(dir.Write("c.csv", kHeader + ImuRows(2) + ImuRows(1))),
              HasSubstr("c.csv:4:1: timestamps not increasing"));
  EXPECT_THAT(ErrorOf(dir.Write("d.csv", kHeader)), HasSubstr("d.csv: needs at least 2 IMU samples"));
  EXPECT_THAT(ErrorOf(dir.Write("e.csv", "")), HasSubstr("needs at least 2"));
  EXPECT_THAT(ErrorOf(dir.File("missing.csv")), HasSubstr("missing.csv: cannot open"));
}

TEST(ReadEurocImu, GapIsRefusedAtTheRowAfterIt) {
  TempDir dir;
  std::string text = kHeader + ImuRows(20);
  text += std::to_string(1403715273262142976LL + 100 * 5000000LL) + ",0,0,0,0,0,9.8\n";
  EXPECT_THAT(ErrorOf(dir.Write("gap.csv", text)), HasSubstr("gap.csv:22: gap of 0.405 s"));
}

TEST(ReadEurocImu, AccelerometerInUnitsOfGIsRefusedWithAHint) {
  TempDir dir;
  std::string text = kHeader;
  for (int i = 0; i < 10; ++i) text += std::to_string(1000000 + i * 5000000) + ",0,0,0,0,0,1.0\n";
  const std::string path = dir.Write("g.csv", text);
  EXPECT_THAT(ErrorOf(path), HasSubstr("units of g"));
  ImuReadOptions options;
  options.accel_scale = 9.80665;
  options.check_accel_units = false;
  EXPECT_DOUBLE_EQ(ReadEurocImu(path, options)[0].accel.z(), 9.80665);
}

TEST(ReadEurocGroundTruth, ReadsSeventeenColumnsAndNormalisesQuaternion) {
  TempDir dir;
  const std::string path = dir.Write(
      "gt.csv",
      "#time(ns),px,py,pz,qw,qx,qy,qz,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz\n"
      "100,1,2,3,1.0001,0,0,0,4,5,6,0.1,0.2,0.3,0.4,0.5,0.6\n"
      "200,1,2,3,0,1,0,0,4,5,6,0.1,0.2,0.3,0.4,0.5,0.6\n");
  const auto states = ReadEurocGroundTruth(path);
  ASSERT_EQ(states.size(), 2u);
  EXPECT_NEAR(states[0].q_w_s.norm(), 1.0, 1e-15);
  EXPECT_EQ(states[1].q_w_s.x(), 1.0);
  EXPECT_EQ(states[0].v_w, Eigen::Vector3d(4, 5, 6));
  EXPECT_EQ(states[0].gyro_bias, Eigen::Vector3d(0.1, 0.2, 0.3));
  EXPECT_EQ(states[0].accel_bias, Eigen::Vector3d(0.4, 0.5, 0.6));
}

TEST(ReadEurocGroundTruth, NonUnitQuaternionIsRefused) {
  TempDir dir;
  const std::string path = dir.Write("gt.csv",
                                     "100,1,2,3,2,0,0,0,4,5,6,0,0,0,0,0,0\n"
                                     "200,1,2,3,1,0,0,0,4,5,6,0,0,0,0,0,0\n");
  EXPECT_THAT(
      [&] { ReadEurocGroundTruth(path); },
      ::testing::ThrowsMessage<Error>(::testing::HasSubstr("gt.csv:1:11: quaternion has norm 2")));
}

TEST(ReadEurocGroundTruth, SharedRealDataReads) {
  const std::string path = testing::SharedDataDir() + "/euroc_v1_01_easy/groundtruth.csv";
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_v1_01_easy/groundtruth.csv");
  const auto states = ReadEurocGroundTruth(path);
  EXPECT_EQ(states.size(), 2895u);
  const auto imu = ReadEurocImu(testing::SharedDataDir() + "/euroc_v1_01_easy/imu0.csv");
  EXPECT_EQ(imu.size(), 29120u);
  EXPECT_EQ(imu.front().t_ns, states.front().t_ns);
}

}  // namespace
}  // namespace splinecal

namespace splinecal {
namespace {

TEST(ReadEurocImu, ImplausibleMagnitudeIsRefusedWithTheLimit) {
  testing::TempDir dir;
  const std::string path = dir.Write("huge.csv",
                                     "1000,0,0,0,0,0,9.8\n"
                                     "2000,0,1e300,0,0,0,9.8\n");
  EXPECT_THAT([&] { ReadEurocImu(path); },
              ::testing::ThrowsMessage<Error>(
                  ::testing::HasSubstr("huge.csv:2:8: gyro y: value 1e+300 is beyond the "
                                       "plausible 1000 rad/s")));
}

}  // namespace
}  // namespace splinecal
