// `calibrate` with three IMUs (calib/several_imus_round_trip.h): ~14 s wall on the loaded 2-core
// machine, so with the slow tests (the sanitizer build would take about a minute).
#include <gtest/gtest.h>

#include "calib/several_imus_round_trip.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

TEST(CalibrateImus, ThreeImusRoundTrip) {
  testing::ExpectRoundTrip({testing::kImu1, testing::kImu2});
}

// A further IMU with its own Kalibr model (FurtherImu::model): every entry of M_a, M_g, A,
// C_gyro_i (and ry_i, rz_i) and its pose back within 3 std.
TEST(CalibrateImus, TwoImusFurtherScaleMisalignmentRoundTrip) {
  testing::ExpectRoundTrip({testing::WithModel(testing::kImu1, ImuModelKind::kScaleMisalignment)});
}

TEST(CalibrateImus, TwoImusFurtherSizeEffectRoundTrip) {
  testing::ExpectRoundTrip(
      {testing::WithModel(testing::kImu1, ImuModelKind::kScaleMisalignmentSizeEffect)});
}

}  // namespace
}  // namespace splinecal
