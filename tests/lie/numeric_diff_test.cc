// Tests of the test helper tests/testing/numeric_diff.h (it lives with the lie tests because
// tests/testing/ holds headers only): central differences and Ridders' method on functions
// with known derivatives, the custom-minus variant on a group-valued function, and the
// right-perturbation helpers on SE(3) and SO(3).
#include "testing/numeric_diff.h"

#include <gtest/gtest.h>

#include <cmath>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace {

// Central differences with step 1e-5 on O(1) smooth functions: ~1e-10 absolute error.
constexpr double kCentralTolerance = 1e-9;
// Ridders' extrapolation on smooth functions: close to rounding.
constexpr double kRiddersTolerance = 1e-11;

Eigen::Vector2d TestFunction(const Eigen::Vector3d& x) {
  return Eigen::Vector2d(std::sin(x(0)) * std::exp(x(1)), x(0) * x(1) * x(2) + x(2) * x(2));
}

Eigen::Matrix<double, 2, 3> TestFunctionJacobian(const Eigen::Vector3d& x) {
  Eigen::Matrix<double, 2, 3> j;
  j << std::cos(x(0)) * std::exp(x(1)), std::sin(x(0)) * std::exp(x(1)), 0.0,  //
      x(1) * x(2), x(0) * x(2), x(0) * x(1) + 2.0 * x(2);
  return j;
}

TEST(NumericDiff, CentralDifferenceMatchesAnalytic) {
  const Eigen::Vector3d x(0.3, -0.7, 1.2);
  const Eigen::MatrixXd numeric = testing::CentralDifferenceJacobian(
      [](const Eigen::Vector3d& v) -> Eigen::Vector2d { return TestFunction(v); }, x);
  ASSERT_EQ(numeric.rows(), 2);
  ASSERT_EQ(numeric.cols(), 3);
  EXPECT_LT((numeric - TestFunctionJacobian(x)).norm(), kCentralTolerance);
}

TEST(NumericDiff, RiddersIsMoreAccurateThanCentral) {
  const Eigen::Vector3d x(0.3, -0.7, 1.2);
  Eigen::VectorXd error;
  const Eigen::MatrixXd numeric = testing::RiddersJacobian(
      [](const Eigen::Vector3d& v) -> Eigen::Vector2d { return TestFunction(v); },
      x,
      testing::RiddersOptions(),
      &error);
  EXPECT_LT((numeric - TestFunctionJacobian(x)).norm(), kRiddersTolerance);
  ASSERT_EQ(error.size(), 3);
  EXPECT_LT(error.maxCoeff(), kRiddersTolerance);
}

TEST(NumericDiff, CentralDifferenceWithMinusOnGroupValuedFunction) {
  // g(phi) = Exp(phi): with the right minus its Jacobian is Jr(phi).
  const Eigen::Vector3d phi(0.4, -1.1, 0.8);
  const Eigen::MatrixXd numeric = testing::CentralDifferenceJacobianWithMinus(
      [](const Eigen::Vector3d& p) { return SO3d::Exp(p); },
      [](const SO3d& a, const SO3d& b) { return testing::RightMinus(a, b); },
      phi);
  EXPECT_LT((numeric - RightJacobianSO3(phi)).norm(), kCentralTolerance);
}

TEST(NumericDiff, RightPerturbationJacobianOfPointTransform) {
  // d (T Exp(d) p) / d d at 0 = R [I, -Hat(p)].
  const SE3d pose(SO3d::Exp(Eigen::Vector3d(0.3, 2.0, -1.0)), Eigen::Vector3d(1.0, 2.0, 3.0));
  const Eigen::Vector3d p(-0.5, 0.7, 2.0);
  Eigen::Matrix<double, 3, 6> analytic;
  analytic << pose.so3().matrix(), -pose.so3().matrix() * Hat(p);
  const auto f = [&](const SE3d& t) -> Eigen::Vector3d { return t * p; };
  EXPECT_LT((testing::RightPerturbationJacobian(f, pose) - analytic).norm(), kCentralTolerance);
  EXPECT_LT((testing::RightPerturbationJacobianRidders(f, pose) - analytic).norm(),
            kRiddersTolerance);
}

TEST(NumericDiff, RightPerturbationJacobianOnSO3) {
  // d Log(R Exp(d)) / d d at 0 = Jr^-1(Log R).
  const SO3d r = SO3d::Exp(Eigen::Vector3d(1.0, -0.5, 2.0));
  const Eigen::MatrixXd numeric = testing::RightPerturbationJacobian(
      [](const SO3d& x) -> Eigen::Vector3d { return x.Log(); }, r);
  EXPECT_LT((numeric - RightJacobianInverseSO3(r.Log())).norm(), kCentralTolerance);
}

}  // namespace
}  // namespace splinecal
