#include "splinecal/io/parallel_euroc_imu.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>

#include "splinecal/io/static_recording.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace internal {
namespace {

using testing::TempDir;

// Enough rows that every hardware thread gets a share, in the spellings TextFileReader accepts:
// CRLF, blanks around commas, comment and blank lines, a leading '+'.
std::string Rows(int count) {
  std::string text =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\r\n\n";
  for (int k = 0; k < count; ++k) {
    text += std::to_string(1000000000LL + 5000000LL * k) + (k % 3 ? "," : " , ") +
            std::to_string(k) + "e-4,+0.25,-0.5,0.1,0.2,9.81" + (k % 2 ? "\r\n" : "\n");
    if (k % 97 == 0) text += "  # comment\n   \n";
  }
  return text;
}

TEST(ReadEurocImuParallel, ReadsEveryRowInOrderAndScales) {
  TempDir dir;
  const std::string path = dir.Write("imu.csv", Rows(1000));
  const std::optional<EurocImuColumns> columns = ReadEurocImuParallel(path, 2.0, 1.0);
  ASSERT_TRUE(columns.has_value());
  ASSERT_EQ(columns->values[0].size(), 1000u);
  for (int k = 0; k < 1000; ++k) EXPECT_EQ(columns->values[0][k], 2.0 * (k / 1e4)) << k;
  EXPECT_EQ(columns->values[1].back(), 0.5);
  EXPECT_EQ(columns->values[5].front(), 9.81);
  EXPECT_EQ(columns->first_t_ns, 1000000000LL);
  EXPECT_EQ(columns->last_t_ns, 1000000000LL + 5000000LL * 999);
  EXPECT_EQ(columns->largest_step_ns, 5000000LL);
}

// Many small shares (the line ends counted per share, rows parsed into place, the gaps of comment
// lines closed), rows in the common spelling (17 significant digits) and in others (exponents,
// blanks, CRLF, '+'), a file without a header: every number as the line-by-line path reads it.
TEST(ReadEurocImuParallel, ManySharesReadAsTheLineByLinePath) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::string text;
  for (int k = 0; k < 3000; ++k) {
    char row[256];
    const double v[6] = {0.01 * normal(rng),
                         1e-5 * normal(rng),
                         -0.2 * normal(rng),
                         0.1 + normal(rng),
                         0.05 * normal(rng),
                         9.81 + 0.03 * normal(rng)};
    const char* format = k % 5 == 0   ? "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\r\n"
                         : k % 7 == 0 ? "%lld, %.6e,+%.6f,%.17g ,%.9f,%.17g,%.17g\n"
                                      : "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n";
    std::snprintf(row,
                  sizeof(row),
                  format,
                  1403636579758555392LL + 5000000LL * k,
                  v[0],
                  v[1],
                  v[2],
                  v[3],
                  v[4],
                  v[5]);
    text += row;
    if (k % 211 == 0) text += "# a comment\n\n";
  }
  TempDir dir;
  const std::string path = dir.Write("imu.csv", text);
  StaticReadOptions line_by_line;
  line_by_line.parallel_min_bytes = INT64_MAX;
  const StaticRecording recording = ReadEurocStaticRecording(path, line_by_line);
  for (const bool avx2 : {false, true}) {  // AVX2 where the processor has it
    ParallelReadOptions options;
    options.share_bytes = 1000;
    options.avx2 = avx2;
    const std::optional<EurocImuColumns> columns = ReadEurocImuParallel(path, 1.0, 1.0, options);
    ASSERT_TRUE(columns.has_value());
    for (int a = 0; a < 6; ++a) {
      ASSERT_EQ(columns->values[a], recording.axes[a].samples) << "axis " << a << " avx2 " << avx2;
    }
    EXPECT_EQ(columns->first_t_ns, 1403636579758555392LL);
    EXPECT_EQ(columns->last_t_ns, 1403636579758555392LL + 5000000LL * 2999);
    EXPECT_EQ(columns->largest_step_ns, 5000000LL);
  }
}

TEST(ReadEurocImuParallel, HandsAnythingUnusualBack) {
  TempDir dir;
  const std::string rows = Rows(1000);
  for (const std::string& bad : {
           std::string("t,gx,gy,gz,ax,ay,az\n") + rows,  // header without '#'
           rows + "6000000000,0,0,0,0,0\n",              // a column missing
           rows + "6000000000,0,0,0,0,0,nan\n",          // not finite
           rows + "6000000000,0,0,0,0,0,2e4\n",          // implausible accel
           rows + "6000000000,2e3,0,0,0,0,9.8\n",        // implausible gyro
           rows + "1000000000,0,0,0,0,0,9.8\n",          // timestamps go back
           std::string("1000,0,0,0,0,0,9.8\n"),          // one row
       }) {
    EXPECT_FALSE(ReadEurocImuParallel(dir.Write("bad.csv", bad), 1.0, 1.0).has_value()) << bad;
  }
  // The limits apply after scaling: 5000 deg/s is within 1e3 rad/s.
  EXPECT_TRUE(ReadEurocImuParallel(
                  dir.Write("deg.csv", rows + "6000000000,5000,0,0,0,0,9.8\n"), 0.0175, 1.0)
                  .has_value());
  // inf stays refused when a tiny scale would make the limit inf too.
  EXPECT_FALSE(
      ReadEurocImuParallel(dir.Write("inf.csv", rows + "6000000000,inf,0,0,0,0,9.8\n"), 1e-300, 1.0)
          .has_value());
  EXPECT_FALSE(ReadEurocImuParallel(dir.File("missing.csv"), 1.0, 1.0).has_value());
}

}  // namespace
}  // namespace internal
}  // namespace splinecal
