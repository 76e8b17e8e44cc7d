#include "splinecal/io/spline_csv.h"

#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

SE3Splined ExampleSpline(TrajectoryModel model = TrajectoryModel::kSE3) {
  std::vector<SE3d> poses;
  for (int i = 0; i < 7; ++i) {
    const Vector6<double> xi = (Vector6<double>() << 0.3 * i, -0.1 * i, 1.0 / 3.0, 0.2 * i,
                                0.05 * i * i, -0.4)
                                   .finished();
    poses.push_back(SE3d::Exp(xi));
  }
  return SE3Splined(poses, 1403715273262142976LL, 50000000, model);
}

// The error ReadSplineCsv throws for `text`, or "no error".
std::string ReadError(const TempDir& dir, const std::string& text) {
  try {
    ReadSplineCsv(dir.Write("s.csv", text));
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
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
  auto error_of = [&](const std::string& text) { return ReadError(dir, text); };
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

// The "# trajectory:" line carries the model (spline/trajectory_model.h): written first, read back
// with the poses, and the split spline read back evaluates as the split spline, not as the
// coupled one on the same control poses.
TEST(SplineCsv, TheTrajectoryModelRoundTrips) {
  TempDir dir;
  for (TrajectoryModel model : {TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3}) {
    const SE3Splined spline = ExampleSpline(model);
    std::ostringstream text;
    WriteSplineCsv(spline, &text);
    EXPECT_EQ(
        text.str().rfind(std::string("# trajectory: ") + TrajectoryModelName(model) + "\n", 0), 0u);
    const SE3Splined read = ReadSplineCsv(dir.Write("spline.csv", text.str()));
    EXPECT_EQ(read.model(), model);
    const int64_t t_ns = spline.start_time_ns() + 12345678;
    EXPECT_EQ(read.PoseNs(t_ns).translation(), spline.PoseNs(t_ns).translation());
  }
  const int64_t t_ns = ExampleSpline().start_time_ns() + 12345678;
  EXPECT_GT((ExampleSpline(TrajectoryModel::kSplitSO3R3).PoseNs(t_ns).translation() -
             ExampleSpline().PoseNs(t_ns).translation())
                .norm(),
            1e-3);
}

TEST(SplineCsv, TheTrajectoryLineIsOptionalAndMayStandAnywhereWithSpaces) {
  TempDir dir;
  std::ostringstream text;
  WriteSplineCsv(ExampleSpline(), &text);
  std::string rows = text.str();
  rows = rows.substr(rows.find('\n') + 1);  // without the model line: written before it existed
  EXPECT_EQ(ReadSplineCsv(dir.Write("old.csv", rows)).model(), TrajectoryModel::kSE3);
  EXPECT_EQ(ReadSplineCsv(dir.Write("late.csv", rows + "  #   trajectory:split  \n")).model(),
            TrajectoryModel::kSplitSO3R3);
  // Other comments are not the key.
  EXPECT_EQ(ReadSplineCsv(dir.Write("other.csv", "# trajectory of the drone\n" + rows)).model(),
            TrajectoryModel::kSE3);
}

TEST(SplineCsv, RefusesAnUnknownOrRepeatedTrajectoryModelAtItsLine) {
  TempDir dir;
  std::ostringstream text;
  WriteSplineCsv(ExampleSpline(), &text);
  std::string rows = text.str();
  rows = rows.substr(rows.find('\n') + 1);
  EXPECT_THAT(ReadError(dir, "# trajectory: coupled\n" + rows),
              HasSubstr("s.csv:1: trajectory: expected se3 or split, got 'coupled'"));
  EXPECT_THAT(ReadError(dir, "# trajectory:\n" + rows),
              HasSubstr("s.csv:1: trajectory: expected se3 or split, got ''"));
  EXPECT_THAT(ReadError(dir, "# trajectory: split\n" + rows + "# trajectory: split\n"),
              HasSubstr("s.csv:10: the trajectory model is given twice"));
}

}  // namespace
}  // namespace splinecal
