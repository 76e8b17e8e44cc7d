#include "splinecal/io/observations_csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "splinecal/error.h"
#include "testing/refusals.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

TEST(ReadObservationsCsv, ReadsSortsAndToleratesFormatting) {
  testing::TempDir dir;
  const std::vector<Observation> obs =
      ReadObservationsCsv(dir.Write("obs.csv",
                                    "#t_ns,cam_id,point_id,u,v\r\n"
                                    "1403715273262142976, 0, 17, 412.25, 233.5\r\n"
                                    "\r\n"
                                    "# a comment\n"
                                    "1403715273212142976,0,3,1.5e2,2\n"
                                    "1403715273262142976,0,2,10,20\n"
                                    "1403715273262142976,1,2,11,21\n"));
  ASSERT_EQ(obs.size(), 4u);
  EXPECT_EQ(obs[0].t_ns, 1403715273212142976);  // exact int64, never through a double
  EXPECT_EQ(obs[0].point_id, 3);
  EXPECT_EQ(obs[0].uv, Eigen::Vector2d(150.0, 2.0));
  EXPECT_EQ(obs[1].point_id, 2);
  EXPECT_EQ(obs[2].point_id, 17);
  EXPECT_EQ(obs[3].cam_id, 1);
  const std::vector<ObservationFrame> frames = GroupIntoFrames(obs);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[1].observations.size(), 2u);
  EXPECT_EQ(frames[2].cam_id, 1);
}

TEST(WriteObservationsCsv, RoundTripsExactly) {
  std::vector<Observation> obs(3);
  obs[0] = {1000000000, 0, 5, Eigen::Vector2d(1.0 / 3.0, 479.99999999999)};
  obs[1] = {1000000000, 0, 6, Eigen::Vector2d(-0.5, 1e-17)};
  obs[2] = {2000000001, 2, 123456789012, Eigen::Vector2d(700.125, 0.0)};
  std::ostringstream text;
  WriteObservationsCsv(obs, &text);
  EXPECT_THAT(text.str(), HasSubstr("#t_ns,cam_id,point_id,u,v\n"));
  testing::TempDir dir;
  const std::vector<Observation> back = ReadObservationsCsv(dir.Write("o.csv", text.str()));
  ASSERT_EQ(back.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(back[i].t_ns, obs[i].t_ns);
    EXPECT_EQ(back[i].cam_id, obs[i].cam_id);
    EXPECT_EQ(back[i].point_id, obs[i].point_id);
    EXPECT_EQ(back[i].uv, obs[i].uv);
  }
}

TEST(ReadObservationsCsv, RefusesBadRowsNamingLineAndColumn) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"1,0,2,3\n", "bad.csv:1: expected 5 columns"},
      {"1.5,0,2,3,4\n", "bad.csv:1:1"},
      {"1,-1,2,3,4\n", "cam_id"},
      {"1,0,-2,3,4\n", "point_id must be >= 0"},
      {"1,0,2,nan,4\n", "bad.csv:1:7"},
      {"1,0,2,3,1e9\n", "v"},
      {"#t_ns,cam_id,point_id,u,v\n", "no observations"},
      {"5,0,2,3,4\n6,0,2,3,4\n5,0,2,3.5,4\n", "bad.csv:3: point 2 of camera 0 appears twice"},
  };
  testing::ExpectEachFileRefused(
      cases, "bad.csv", [](const std::string& path) { ReadObservationsCsv(path); });
}

}  // namespace
}  // namespace splinecal
