// `calibrate` with three IMUs (calib/several_imus_round_trip.h): ~14 s wall on the loaded 2-core
// machine, so with the slow tests (the sanitizer build would take about a minute).
#include <gtest/gtest.h>

#include "calib/several_imus_round_trip.h"

namespace splinecal {
namespace {

TEST(CalibrateImus, ThreeImusRoundTrip) {
  testing::ExpectRoundTrip({testing::kImu1, testing::kImu2});
}

}  // namespace
}  // namespace splinecal
