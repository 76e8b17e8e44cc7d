#include "splinecal/spline/knot_layout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "splinecal/error.h"

namespace splinecal {
namespace {

// t0 near an EuRoC epoch, 0.1 s knots, n = 10: valid range [t_1, t_8].
KnotLayout TenKnots() {
  KnotLayout layout;
  layout.t0_ns = 1'403'715'273'262'142'976;
  layout.dt_ns = 100'000'000;
  layout.num_control_poses = 10;
  return layout;
}

TEST(KnotLayout, NanosecondAndSecondLookupsAgree) {
  const KnotLayout layout = TenKnots();
  for (int64_t t = layout.start_time_ns(); t <= layout.end_time_ns(); t += 7'777'777) {
    SegmentPosition by_ns;
    SegmentPosition by_s;
    ASSERT_TRUE(layout.SegmentAtNs(t, &by_ns));
    ASSERT_TRUE(layout.SegmentAt(layout.TimeSinceT0(t), &by_s));
    // A time a few ulps below a knot in seconds may land on the previous segment at u ~ 1:
    // the same instant either way.
    const double place_ns = by_ns.index + by_ns.u;
    const double place_s = by_s.index + by_s.u;
    EXPECT_NEAR(place_ns, place_s, 1e-9) << t;
  }
}

TEST(KnotLayout, EndTimeIsTheLastSegmentAtUOne) {
  const KnotLayout layout = TenKnots();
  SegmentPosition p;
  ASSERT_TRUE(layout.SegmentAtNs(layout.end_time_ns(), &p));
  EXPECT_EQ(p.index, 7);
  EXPECT_EQ(p.u, 1.0);
  ASSERT_TRUE(layout.SegmentAt(layout.end_time(), &p));
  EXPECT_EQ(p.index, 7);
  EXPECT_DOUBLE_EQ(p.u, 1.0);
  ASSERT_TRUE(layout.SegmentAtNs(layout.start_time_ns(), &p));
  EXPECT_EQ(p.index, 1);
  EXPECT_EQ(p.u, 0.0);
}

TEST(KnotLayout, OutsideTheValidRangeIsRefused) {
  const KnotLayout layout = TenKnots();
  SegmentPosition p;
  EXPECT_FALSE(layout.SegmentAtNs(layout.start_time_ns() - 1, &p));
  EXPECT_FALSE(layout.SegmentAtNs(layout.end_time_ns() + 1, &p));
  EXPECT_FALSE(layout.SegmentAt(0.0999, &p));
  EXPECT_FALSE(layout.SegmentAt(0.8001, &p));
  EXPECT_FALSE(layout.SegmentAt(std::nan(""), &p));
  // Within 1e-9 dt of the ends: snapped on.
  EXPECT_TRUE(layout.SegmentAt(0.1 - 1e-12, &p));
  EXPECT_TRUE(layout.SegmentAt(0.8 + 1e-12, &p));
}

TEST(KnotLayout, ClampedSegmentStaysInsideTheSpline) {
  const KnotLayout layout = TenKnots();
  EXPECT_EQ(layout.ClampedSegmentAt(-5.0), 1);
  EXPECT_EQ(layout.ClampedSegmentAt(0.35), 3);
  EXPECT_EQ(layout.ClampedSegmentAt(50.0), 7);
  EXPECT_EQ(layout.ClampedSegmentAt(std::nan("")), 1);
  EXPECT_EQ(layout.ClampedSegmentAtNs(layout.t0_ns - 1), 1);
  EXPECT_EQ(layout.ClampedSegmentAtNs(layout.knot_time_ns(3) + 50'000'000), 3);
  EXPECT_EQ(layout.ClampedSegmentAtNs(layout.end_time_ns()), 7);
  EXPECT_EQ(layout.ClampedSegmentAtNs(layout.end_time_ns() + 1'000'000'000), 7);
}

TEST(KnotLayout, CoveringLayoutStartsAtTheFirstSampleAndEndsAfterTheLast) {
  const KnotLayout layout = KnotLayoutCovering(1'000, 21'001, 1'000);
  EXPECT_EQ(layout.start_time_ns(), 1'000);
  EXPECT_GE(layout.end_time_ns(), 21'001);
  EXPECT_LT(layout.end_time_ns() - layout.dt_ns, 21'001);
  EXPECT_THROW(KnotLayoutCovering(0, 10, 0), Error);
  EXPECT_THROW(KnotLayoutCovering(10, 0, 1), Error);
  EXPECT_THROW(KnotLayoutCovering(0, 1'000'000'000'000'000, 1), Error);
}

}  // namespace
}  // namespace splinecal
