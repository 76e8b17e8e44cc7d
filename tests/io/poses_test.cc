#include "splinecal/io/poses.h"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

TEST(ReadPoses, TumFormatWithExactNanoseconds) {
  TempDir dir;
  const auto poses = ReadPoses(dir.Write("traj.txt",
                                         "# t tx ty tz qx qy qz qw\n"
                                         "1403715273.262142976 1 2 3 0 0 0 1\n"
                                         "1403715273.312143104 1 2 3 1 0 0 0\n"));
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].t_ns, 1403715273262142976LL);
  EXPECT_EQ(poses[1].t_ns, 1403715273312143104LL);
  EXPECT_EQ(poses[0].p, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(poses[0].q.w(), 1.0);
  EXPECT_EQ(poses[1].q.x(), 1.0);  // TUM's qx qy qz qw order
}

TEST(ReadPoses, EurocGroundTruthIsDetectedByCommas) {
  TempDir dir;
  const auto poses = ReadPoses(dir.Write("gt.csv",
                                         "#time(ns),px,py,pz,qw,qx,qy,qz,vx,vy,vz\n"
                                         "100, 1, 2, 3, 0, 1, 0, 0, 0, 0, 0\n"
                                         "200, 1, 2, 3, 1, 0, 0, 0, 0, 0, 0\n"));
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].t_ns, 100);
  EXPECT_EQ(poses[0].q.x(), 1.0);  // EuRoC's qw qx qy qz order
  EXPECT_EQ(poses[1].q.w(), 1.0);
}

TEST(ReadPoses, WriteTumThenReadIsExact) {
  TempDir dir;
  std::vector<StampedPose> poses(3);
  for (int i = 0; i < 3; ++i) {
    poses[i].t_ns = 1403715273262142976LL + 7 * i;
    poses[i].p = Eigen::Vector3d(1.0 / 3.0, -i, 1e-9);
    poses[i].q = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i + 0.2, Eigen::Vector3d(1, 2, 3).normalized()));
  }
  std::ostringstream text;
  WriteTumTrajectory(poses, &text);
  const auto read = ReadTumTrajectory(dir.Write("t.txt", text.str()));
  ASSERT_EQ(read.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(read[i].t_ns, poses[i].t_ns);
    EXPECT_EQ(read[i].p, poses[i].p);
    EXPECT_NEAR((read[i].q.coeffs() - poses[i].q.coeffs()).norm(), 0.0, 1e-15);
  }
}

TEST(ReadPoses, BadRowsNameTheLine) {
  TempDir dir;
  auto error_of = [&](const std::string& name, const std::string& text) {
    try {
      ReadPoses(dir.Write(name, text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("a.txt", "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n"),
              HasSubstr("a.txt:2: expected 8 columns"));
  EXPECT_THAT(error_of("b.txt", "1 0 0 0 0 0 0 1\n1 0 0 0 0 0 0 1\n"),
              HasSubstr("b.txt:2:1: timestamps not increasing"));
  EXPECT_THAT(error_of("c.txt", "1 0 0 0 0 0 0 1\n"), HasSubstr("needs at least 2 poses"));
  EXPECT_THAT(error_of("d.txt", "1 0 0 0 0 0 0 1\n2 0 0 inf 0 0 0 1\n"),
              HasSubstr("d.txt:2:7: tz: value 'inf' is not a finite number"));
}

}  // namespace
}  // namespace splinecal
