#include "splinecal/sim/simulation_trajectory.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/sim/trajectories.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr int64_t kKnotSpacingNs = 50'000'000;
constexpr int64_t kStartNs = kKnotSpacingNs;
constexpr int64_t kEndNs = kStartNs + 2'000'000'000;  // 2 s: quick fits
// A 0.05 s spline follows these smooth trajectories to well below a millimetre.
constexpr double kFitPositionRmsM = 1e-3;

PoseFitOptions Recording(std::vector<std::string>* lines) {
  PoseFitOptions options;
  options.progress = [lines](const std::string& line) { lines->push_back(line); };
  return options;
}

TEST(FitSimulationTrajectory, AnalyticByNameOverTheRange) {
  SimulationTrajectory trajectory;
  trajectory.name = "figure8";
  std::vector<std::string> lines;
  const SimulationSpline spline =
      FitSimulationTrajectory(trajectory, kStartNs, kEndNs, kKnotSpacingNs, Recording(&lines));
  EXPECT_EQ(spline.source, "figure8");
  const SE3Splined s = spline.fit.MakeSpline();
  EXPECT_LE(s.start_time_ns(), kStartNs);
  EXPECT_GE(s.end_time_ns(), kEndNs);
  EXPECT_LT(spline.fit.position_rms_m, kFitPositionRmsM);
  ASSERT_GE(lines.size(), 2u);
  EXPECT_EQ(lines.front(),
            "simulate: fitting the figure8 trajectory (2.000000 s, knots every 0.050000 s)");
  EXPECT_THAT(lines.back(), StartsWith("simulate: spline fit position RMS "));
}

TEST(FitSimulationTrajectory, RecordedPosesWinAndKeepTheirName) {
  SimulationTrajectory trajectory;
  trajectory.name = "no such name";  // ignored with recorded poses
  trajectory.recorded_poses =
      Figure8Trajectory().Sample(0, kEndNs + kKnotSpacingNs, kKnotSpacingNs / 10);
  trajectory.recorded_source = "poses.txt";
  std::vector<std::string> lines;
  const SimulationSpline spline =
      FitSimulationTrajectory(trajectory, kStartNs, kEndNs, kKnotSpacingNs, Recording(&lines));
  EXPECT_EQ(spline.source, "poses.txt");
  EXPECT_LT(spline.fit.position_rms_m, kFitPositionRmsM);
  ASSERT_FALSE(lines.empty());
  EXPECT_THAT(lines.front(), HasSubstr("s knots to 421 poses of poses.txt"));
}

TEST(FitSimulationTrajectory, CalibrationMotionForCam0) {
  SimulationTrajectory trajectory;
  trajectory.name = "calibration";
  const SimulationSpline spline =
      FitSimulationTrajectory(trajectory, 1'000'000'000, 3'000'000'000, kKnotSpacingNs);
  EXPECT_EQ(spline.source, "calibration");
  EXPECT_GE(spline.fit.MakeSpline().end_time_ns(), 3'000'000'000);
}

TEST(FitSimulationTrajectory, UnknownNameNamesTheChoices) {
  SimulationTrajectory trajectory;
  trajectory.name = "spiral";
  try {
    FitSimulationTrajectory(trajectory, kStartNs, kEndNs, kKnotSpacingNs);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("vio_course"));
  }
}

}  // namespace
}  // namespace splinecal
