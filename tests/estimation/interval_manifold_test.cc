// IntervalManifold (estimation/interval_manifold.h): Ceres' bounded Plus, as a manifold.
#include "splinecal/estimation/interval_manifold.h"

#include <gtest/gtest.h>

namespace splinecal {
namespace {

TEST(IntervalManifoldTest, PlusClampsToTheInterval) {
  const IntervalManifold manifold(-0.1, 0.2);
  double x = 0.05;
  double out = 0.0;
  double delta = 0.1;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &out));
  EXPECT_DOUBLE_EQ(out, 0.15);
  delta = 1.0;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &out));
  EXPECT_EQ(out, 0.2);
  delta = -1.0;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &out));
  EXPECT_EQ(out, -0.1);
}

TEST(IntervalManifoldTest, JacobiansMatchFiniteDifferencesInside) {
  const IntervalManifold manifold(0.0, 1.0);
  const double x = 0.4;
  const double h = 1e-6;
  double plus_h = 0.0;
  double minus_h = 0.0;
  ASSERT_TRUE(manifold.Plus(&x, &h, &plus_h));
  const double negative_h = -h;
  ASSERT_TRUE(manifold.Plus(&x, &negative_h, &minus_h));
  double plus_jacobian = 0.0;
  ASSERT_TRUE(manifold.PlusJacobian(&x, &plus_jacobian));
  EXPECT_NEAR(plus_jacobian, (plus_h - minus_h) / (2.0 * h), 1e-9);
  double minus_jacobian = 0.0;
  ASSERT_TRUE(manifold.MinusJacobian(&x, &minus_jacobian));
  double y_minus_x_plus = 0.0;
  double y_minus_x_minus = 0.0;
  const double y_plus = x + h;
  const double y_minus = x - h;
  ASSERT_TRUE(manifold.Minus(&y_plus, &x, &y_minus_x_plus));
  ASSERT_TRUE(manifold.Minus(&y_minus, &x, &y_minus_x_minus));
  EXPECT_NEAR(minus_jacobian, (y_minus_x_plus - y_minus_x_minus) / (2.0 * h), 1e-9);
}

TEST(IntervalManifoldTest, MinusInvertsPlusInside) {
  const IntervalManifold manifold(-1.0, 1.0);
  const double x = 0.25;
  const double y = -0.5;
  double delta = 0.0;
  ASSERT_TRUE(manifold.Minus(&y, &x, &delta));
  double back = 0.0;
  ASSERT_TRUE(manifold.Plus(&x, &delta, &back));
  EXPECT_DOUBLE_EQ(back, y);
}

}  // namespace
}  // namespace splinecal
