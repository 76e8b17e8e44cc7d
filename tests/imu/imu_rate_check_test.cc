// The IMU-rate gate (imu/imu_rate.h: CheckImuRate) and its use by the readers: real EuRoC
// imu_april passes; the same file with microsecond timestamps is refused naming the unit.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/static_recording.h"
#include "testing/microsecond_imu.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(double rate_hz, bool from_timestamps = true) {
  try {
    CheckImuRate(rate_hz, "imu.csv", from_timestamps);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(CheckImuRate, NamesTheUnitTheTimestampsLookLike) {
  EXPECT_EQ(ErrorOf(10.0), "");
  EXPECT_EQ(ErrorOf(200.0), "");
  EXPECT_EQ(ErrorOf(10000.0), "");
  EXPECT_EQ(ErrorOf(200000.0),
            "imu.csv: IMU sample rate 200000 Hz from the timestamps is outside 10 Hz .. 10 kHz: "
            "the timestamps look like microseconds (then the IMU runs at 200 Hz); they must be "
            "int64 nanoseconds: multiply them by 1000");
  EXPECT_THAT(ErrorOf(2e8), HasSubstr("look like milliseconds (then the IMU runs at 200 Hz)"));
  EXPECT_THAT(ErrorOf(2.0), HasSubstr("too slow for an IMU"));
  EXPECT_THAT(ErrorOf(0.0), HasSubstr("do not advance"));
  EXPECT_THAT(ErrorOf(200000.0, false), HasSubstr("give the sample rate in Hz"));
}

TEST(CheckImuRate, EveryReaderRefusesMicrosecondTimestamps) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/imu0.csv");
  // The real file passes (200 Hz, SOURCE.md).
  const std::vector<ImuSample> imu = ReadEurocImu(testing::SharedDataPath("euroc_imu_april/imu0.csv"));
  EXPECT_NEAR(ImuRateHz(imu), 200.0, 0.01);  // 1 / the median step

  testing::TempDir dir;
  const std::string us =
      testing::WriteMicrosecondImu(dir, testing::SharedDataPath("euroc_imu_april/imu0.csv"));
  const std::string expected = "imu_us.csv: IMU sample rate 200000 Hz from the timestamps";
  try {
    ReadEurocImu(us);
    ADD_FAILURE() << "ReadEurocImu accepted microseconds";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(expected));
  }
  // allan's reader, on both of its paths (parallel for a big file, line by line otherwise).
  for (const int64_t parallel_min_bytes : {int64_t{0}, int64_t{1} << 40}) {
    StaticReadOptions options;
    options.parallel_min_bytes = parallel_min_bytes;
    try {
      ReadEurocStaticRecording(us, options);
      ADD_FAILURE() << "ReadEurocStaticRecording accepted microseconds";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("imu_us.csv: IMU sample rate"));
      EXPECT_THAT(e.what(), HasSubstr("look like microseconds"));
    }
  }
}

}  // namespace
}  // namespace splinecal
