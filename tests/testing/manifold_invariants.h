// Ceres' manifold invariants (ceres/manifold_test_utils.h) as one function: Plus(x, 0) = x,
// Minus(x, x) = 0, the Plus/Minus round trips, and the Plus, Minus and
// RightMultiplyByPlusJacobian Jacobians against numeric differentiation, for the tests of every
// splinecal manifold (lie/se3_manifold.h, estimation/gravity_manifold.h).
#ifndef SPLINECAL_TESTS_TESTING_MANIFOLD_INVARIANTS_H_
#define SPLINECAL_TESTS_TESTING_MANIFOLD_INVARIANTS_H_

#include <ceres/manifold.h>
#include <ceres/manifold_test_utils.h>
#include <gtest/gtest.h>

#include <Eigen/Core>

namespace splinecal {
namespace testing {

// EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD at x, delta and y (an ambient point, a tangent vector and
// a second point) within Ceres' relative `tolerance`.
inline void ExpectManifoldInvariantsHold(const ceres::Manifold& manifold,
                                         const Eigen::VectorXd& x,
                                         const Eigen::VectorXd& delta,
                                         const Eigen::VectorXd& y,
                                         double tolerance) {
  // The names the macro uses unqualified: the matchers and Vector.
  using ceres::HasCorrectMinusJacobianAt;
  using ceres::HasCorrectPlusJacobianAt;
  using ceres::HasCorrectRightMultiplyByPlusJacobianAt;
  using ceres::MinusPlusIsIdentityAt;
  using ceres::MinusPlusJacobianIsIdentityAt;
  using ceres::PlusMinusIsIdentityAt;
  using ceres::Vector;
  using ceres::XMinusXIsZeroAt;
  using ceres::XPlusZeroIsXAt;
  EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD(manifold, x, delta, y, tolerance);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_MANIFOLD_INVARIANTS_H_
