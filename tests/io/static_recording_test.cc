#include "splinecal/io/static_recording.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "splinecal/error.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr char kEurocHeader[] =
    "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
    "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";

// Expects `read` to throw Error whose what() contains `text`.
template <typename F>
void ExpectError(F read, const std::string& text) {
  try {
    read();
    ADD_FAILURE() << "no error; expected '" << text << "'";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(text));
  }
}

TEST(ReadEurocStaticRecording, ReadsAxesAndRateFromTimestamps) {
  testing::TempDir dir;
  const std::string path = dir.Write("imu.csv",
                                     std::string(kEurocHeader) +
                                         "1000000000,0.1,0.2,0.3,0.4,0.5,9.8\r\n"
                                         "\n"
                                         "# a comment\n"
                                         "1005000000, 0.11, 0.21, 0.31, 0.41, 0.51, 9.81\n"
                                         "1010000000,0.12,0.22,0.32,0.42,0.52,9.82\n");
  StaticReadOptions options;
  options.gyro_scale = 2.0;
  const StaticRecording recording = ReadEurocStaticRecording(path, options);
  EXPECT_DOUBLE_EQ(recording.rate_hz, 200.0);
  EXPECT_EQ(recording.source, path);
  ASSERT_EQ(recording.axes.size(), 6u);
  EXPECT_EQ(recording.axes[0].name(), "gyro_x");
  EXPECT_EQ(recording.axes[5].name(), "accel_z");
  EXPECT_THAT(recording.axes[0].samples, ElementsAre(0.2, 0.22, 0.24));
  EXPECT_THAT(recording.axes[5].samples, ElementsAre(9.8, 9.81, 9.82));
}

TEST(ReadEurocStaticRecording, RefusesBadInputWithFileAndLine) {
  testing::TempDir dir;
  const std::string header = kEurocHeader;
  ExpectError(
      [&] {
        ReadEurocStaticRecording(dir.Write("nan.csv",
                                           header + "1000,0,0,0,0,0,9.8\n"
                                                    "2000,0,nan,0,0,0,9.8\n"));
      },
      "nan.csv:3:");
  ExpectError(
      [&] {
        ReadEurocStaticRecording(dir.Write("order.csv",
                                           header + "2000,0,0,0,0,0,9.8\n"
                                                    "2000,0,0,0,0,0,9.8\n"));
      },
      "order.csv:3:1: timestamps not increasing");
  ExpectError(
      [&] { ReadEurocStaticRecording(dir.Write("columns.csv", header + "1000,0,0,0,0,9.8\n")); },
      "columns.csv:2: expected 7 columns");
  ExpectError(
      [&] { ReadEurocStaticRecording(dir.Write("one.csv", header + "1000,0,0,0,0,0,9.8\n")); },
      "one.csv: needs at least 2 data rows, found 1");
  ExpectError([&] { ReadEurocStaticRecording(dir.File("missing.csv")); }, "missing.csv");
  std::string gap = header;
  for (int k = 0; k < 20; ++k) gap += std::to_string(1000 + 10 * k) + ",0,0,0,0,0,9.8\n";
  gap += "100000,0,0,0,0,0,9.8\n";
  ExpectError([&] { ReadEurocStaticRecording(dir.Write("gap.csv", gap)); }, "gap.csv:22: gap of");
  ExpectError(
      [&] {
        ReadEurocStaticRecording(dir.Write("g.csv",
                                           header + "1000,0,0,0,0,0,1.0\n"
                                                    "5001000,0,0,0,0,0,1.01\n"));
      },
      "units of g");
  StaticReadOptions in_g;
  in_g.accel_scale = 9.80665;
  EXPECT_NO_THROW(ReadEurocStaticRecording(dir.File("g.csv"), in_g));
}

// The parallel fast path (forced here with parallel_min_bytes = 0) gives the same numbers as the
// TextFileReader path, and hands anything unusual to it, so errors keep their line.
TEST(ReadEurocStaticRecording, ParallelPathEqualsReaderPath) {
  testing::TempDir dir;
  std::string text = std::string(kEurocHeader) + "# comment\n\n";
  for (int k = 0; k < 5000; ++k) {
    char line[200];
    std::snprintf(line,
                  sizeof(line),
                  "%lld, %.17g,%.17g,%.17g ,%.17g,%.17g,%.17g%s\n",
                  1000000000LL + 2500000LL * k,
                  std::sin(k * 0.1),
                  1e-3 * k,
                  -0.5,
                  std::cos(k * 0.01),
                  1e-7 * k * k,
                  9.81 + 1e-3 * std::sin(k),
                  k % 7 ? "" : "\r");
    text += line;
    if (k % 1000 == 0) text += "# a comment line in the middle\n";
  }
  const std::string path = dir.Write("big.csv", text);
  StaticReadOptions parallel;
  parallel.parallel_min_bytes = 0;
  parallel.gyro_scale = 0.5;
  StaticReadOptions sequential = parallel;
  sequential.parallel_min_bytes = std::numeric_limits<int64_t>::max();
  const StaticRecording a = ReadEurocStaticRecording(path, parallel);
  const StaticRecording b = ReadEurocStaticRecording(path, sequential);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_DOUBLE_EQ(a.rate_hz, 400.0);
  ASSERT_EQ(a.axes.size(), 6u);
  for (int i = 0; i < 6; ++i) EXPECT_EQ(a.axes[i].samples, b.axes[i].samples) << i;
  EXPECT_EQ(a.axes[0].samples.size(), 5000u);

  const std::string bad = dir.Write("bad.csv", text + "13500000000,0,0,0,0,0,x\n");
  ExpectError([&] { ReadEurocStaticRecording(bad, parallel); }, "bad.csv:5009:");
  const std::string plus = dir.Write("plus.csv", text + "13500000000,+1,0,0,0,0,9.8\n");
  EXPECT_EQ(ReadEurocStaticRecording(plus, parallel).axes[0].samples.back(), 0.5);
}

TEST(ReadColumnStaticRecording, SixColumnsAreGyroThenAccel) {
  testing::TempDir dir;
  const std::string path = dir.Write("six.txt",
                                     "gx gy gz ax ay az\n"
                                     "1 2 3 4 5 6\n"
                                     "1.5\t2.5 3.5  4.5 5.5 6.5\n");
  const StaticRecording recording = ReadColumnStaticRecording(path, 100.0, std::nullopt);
  EXPECT_DOUBLE_EQ(recording.rate_hz, 100.0);
  ASSERT_EQ(recording.axes.size(), 6u);
  EXPECT_EQ(recording.axes[3].name(), "accel_x");
  EXPECT_THAT(recording.axes[3].samples, ElementsAre(4.0, 4.5));
}

TEST(ReadColumnStaticRecording, OneToThreeColumnsOfOneSensor) {
  testing::TempDir dir;
  const std::string path = dir.Write("two.csv", "0.5,1.5\n0.25,1.25\n0.75,1.75\n");
  StaticReadOptions options;
  options.accel_scale = 10.0;
  const StaticRecording recording =
      ReadColumnStaticRecording(path, 50.0, ImuSensor::kAccelerometer, options);
  ASSERT_EQ(recording.axes.size(), 2u);
  EXPECT_EQ(recording.axes[1].name(), "accel_y");
  EXPECT_THAT(recording.axes[0].samples, ElementsAre(5.0, 2.5, 7.5));
  ExpectError([&] { ReadColumnStaticRecording(path, 50.0, std::nullopt); },
              "two.csv:1: 2 column(s) of one sensor: say which with --sensor");
  const std::string six = dir.Write("six.csv", "1,2,3,4,5,6\n1,2,3,4,5,7\n");
  ExpectError([&] { ReadColumnStaticRecording(six, 50.0, ImuSensor::kGyroscope); },
              "six.csv:1: 6 columns are gyro xyz then accel xyz");
  ExpectError(
      [&] {
        ReadColumnStaticRecording(dir.Write("four.csv", "1 2 3 4\n"), 50.0, ImuSensor::kGyroscope);
      },
      "four.csv:1: expected 1, 2, 3 (one sensor) or 6");
  ExpectError(
      [&] {
        ReadColumnStaticRecording(
            dir.Write("ragged.csv", "1 2 3\n1 2\n"), 50.0, ImuSensor::kGyroscope);
      },
      "ragged.csv:2: expected 3 columns");
  ExpectError(
      [&] {
        ReadColumnStaticRecording(dir.Write("word.csv", "1 2\n3 x\n"), 50.0, ImuSensor::kGyroscope);
      },
      "word.csv:2:3: gyro y: expected a number, got 'x'");
  ExpectError([&] { ReadColumnStaticRecording(path, 0.0, ImuSensor::kGyroscope); },
              "must be positive");
}

}  // namespace
}  // namespace splinecal
