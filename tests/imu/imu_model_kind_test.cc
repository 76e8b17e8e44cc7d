#include "splinecal/imu/imu_model_kind.h"

#include <gtest/gtest.h>

#include <string>

namespace splinecal {
namespace {

TEST(ImuModelKind, KalibrsNamesRoundTrip) {
  for (ImuModelKind kind : {ImuModelKind::kCalibrated,
                            ImuModelKind::kScaleMisalignment,
                            ImuModelKind::kScaleMisalignmentSizeEffect}) {
    ImuModelKind parsed = ImuModelKind::kCalibrated;
    ASSERT_TRUE(ParseImuModelKind(ImuModelName(kind), &parsed));
    EXPECT_EQ(parsed, kind);
    EXPECT_NE(std::string(ImuModelNames()).find(ImuModelName(kind)), std::string::npos);
  }
  EXPECT_STREQ(ImuModelName(ImuModelKind::kScaleMisalignmentSizeEffect),
               "scale-misalignment-size-effect");
}

TEST(ImuModelKind, RejectsOtherSpellingsAndLeavesTheKind) {
  ImuModelKind kind = ImuModelKind::kScaleMisalignment;
  for (const char* name : {"", "Calibrated", "scale_misalignment", "scale-misalignment ", "sm"}) {
    EXPECT_FALSE(ParseImuModelKind(name, &kind)) << name;
    EXPECT_EQ(kind, ImuModelKind::kScaleMisalignment);
  }
}

TEST(ImuModelKind, ParameterCountsAreKalibrs) {
  EXPECT_EQ(NumImuIntrinsicParameters(ImuModelKind::kCalibrated), 0);
  EXPECT_EQ(NumImuIntrinsicParameters(ImuModelKind::kScaleMisalignment), 6 + 6 + 9 + 3);
  EXPECT_EQ(NumImuIntrinsicParameters(ImuModelKind::kScaleMisalignmentSizeEffect), 24 + 6);
}

}  // namespace
}  // namespace splinecal
