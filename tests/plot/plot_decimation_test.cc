#include "splinecal/plot/plot_decimation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace splinecal {
namespace plot {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST(DecimatedIndices, ShortSeriesKeepEveryPoint) {
  EXPECT_THAT(DecimatedIndices(4, 10, false), ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(DecimatedIndices(4, 4, true), ElementsAre(0, 1, 2, 3));
  EXPECT_THAT(DecimatedIndices(0, 10, true), IsEmpty());
}

TEST(DecimatedIndices, SmallestStrideThatKeepsAtMostMaxPoints) {
  // 10 points, at most 4: stride ceil(10 / 4) = 3.
  EXPECT_THAT(DecimatedIndices(10, 4, false), ElementsAre(0, 3, 6, 9));
  EXPECT_THAT(DecimatedIndices(11, 4, false), ElementsAre(0, 3, 6, 9));
  for (size_t n : {1u, 7u, 5999u, 6000u, 6001u, 123457u}) {
    EXPECT_LE(DecimatedIndices(n, 6000, false).size(), 6000u) << n;
  }
}

TEST(DecimatedIndices, KeepLastEndsTheSeriesWhereTheDataEnds) {
  EXPECT_THAT(DecimatedIndices(11, 4, true), ElementsAre(0, 3, 6, 9, 10));
  EXPECT_THAT(DecimatedIndices(10, 4, true), ElementsAre(0, 3, 6, 9));  // 9 is already the last
}

TEST(DecimatedIndices, NonPositiveMaxPointsCountsAsOne) {
  EXPECT_THAT(DecimatedIndices(5, 0, false), ElementsAre(0));
  EXPECT_THAT(DecimatedIndices(5, -3, true), ElementsAre(0, 4));
}

}  // namespace
}  // namespace plot
}  // namespace splinecal
