#include "splinecal/io/spline_csv.h"

#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

SE3Splined ExampleSpline() {
  std::vector<SE3d> poses;
  for (int i = 0; i < 7; ++i) {
    const Vector6<double> xi = (Vector6<double>() << 0.3 * i, -0.1 * i, 1.0 / 3.0, 0.2 * i,
                                0.05 * i * i, -0.4)
                                   .finished();
    poses.push_back(SE3d::Exp(xi));
  }
  return SE3Splined(poses, 1403715273262142976LL, 50000000);
}

TEST(SplineCsv, WriteThenReadReproducesTheSplineBitExactly) {
  TempDir dir;
  const SE3Splined spline = ExampleSpline();
  std::ostringstream text;
  WriteSplineCsv(spline, &text);
  const SE3Splined read = ReadSplineCsv(dir.Write("spline.csv", text.str()));
  ASSERT_EQ(read.num_control_poses(), spline.num_control_poses());
  EXPECT_EQ(read.t0_ns(), spline.t0_ns());
  EXPECT_EQ(read.dt_ns(), spline.dt_ns());
  for (int i = 0; i < spline.num_control_poses(); ++i) {
    EXPECT_EQ(read.control_pose(i).translation(), spline.control_pose(i).translation());
    EXPECT_EQ(read.control_pose(i).so3().quaternion().coeffs(),
              spline.control_pose(i).so3().quaternion().coeffs());
  }
  const int64_t t_ns = spline.start_time_ns() + 12345678;
  EXPECT_EQ(read.PoseNs(t_ns).translation(), spline.PoseNs(t_ns).translation());
}

TEST(SplineCsv, RefusesNonUniformSpacingAndTooFewPoses) {
  TempDir dir;
  const std::string row = ",0,0,0,1,0,0,0\n";
  auto error_of = [&](const std::string& text) {
    try {
      ReadSplineCsv(dir.Write("s.csv", text));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(error_of("#t_ns,px,py,pz,qw,qx,qy,qz\n0" + row + "10" + row + "25" + row + "30" + row),
              HasSubstr("s.csv:4:1: knot spacing is not uniform"));
  EXPECT_THAT(error_of("0" + row + "10" + row + "20" + row), HasSubstr("at least 4 control poses"));
  EXPECT_THAT(error_of("0" + row + "0" + row + "0" + row + "0" + row),
              HasSubstr("s.csv:2:1: knot times must increase"));
  // t0 + 2*dt is beyond int64 here: the check must not compute it.
  EXPECT_THAT(error_of("-4000000000000000000" + row + "4000000000000000000" + row + "0" + row +
                       "1" + row),
              HasSubstr("s.csv:3:1: knot spacing is not uniform"));
}

}  // namespace
}  // namespace splinecal
