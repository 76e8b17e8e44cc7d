#include "splinecal/calib/camchain_prior.h"

#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <vector>

#include "splinecal/lie/se3_manifold.h"
#include "testing/cost_evaluation.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

// Analytic against Ridders' numeric Jacobians, per block, in the block's tangent space (the
// ambient Jacobian times the manifold's PlusJacobian, as Ceres uses it). Ridders reaches ~1e-10
// relative on these smooth functions; a wrong term (a missing Jr^-1 or Adjoint) is O(|xi|) ~ 1e-2
// relative at the offsets below, so 1e-7 separates them.
constexpr double kRelativeTolerance = 1e-7;

struct Case {
  std::vector<int> intrinsics;
  bool chain = false;
};

// The case as the test list shows it, e.g. "intrinsics_4_5_0_1_2_3_and_chain". Without it
// GoogleTest prints the struct's bytes, the vector's heap pointers included, so the listed name
// changed from build to build and from run to run.
void PrintTo(const Case& c, std::ostream* os) {
  if (!c.intrinsics.empty()) *os << "intrinsics";
  for (int j : c.intrinsics) *os << "_" << j;
  if (c.chain) *os << (c.intrinsics.empty() ? "chain" : "_and_chain");
}

class CamchainPriorTest : public ::testing::TestWithParam<Case> {};

TEST_P(CamchainPriorTest, ResidualIsTheMahalanobisDistanceAndJacobiansMatch) {
  const Case& c = GetParam();
  const int m = static_cast<int>(c.intrinsics.size());
  const int n = m + (c.chain ? 6 : 0);
  // A correlated covariance mixing px, unitless, m and rad.
  Eigen::MatrixXd A = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < i; ++j) A(i, j) = 0.2 * std::cos(1.0 + 2 * i + j);
  }
  Eigen::VectorXd scale(n);
  for (int i = 0; i < n; ++i) scale(i) = i < m ? (c.intrinsics[i] < 6 ? 0.3 : 2e-3) : 1e-3;
  const Eigen::MatrixXd covariance = scale.asDiagonal() * A * A.transpose() * scale.asDiagonal();
  IntrinsicsVector reference;
  reference << 458.6, 457.3, 367.2, 248.4, 0.0, 0.0, -0.28, 0.074, 2e-4, 1.8e-5, 0.0;
  const SE3d T0(SO3d::Exp(Eigen::Vector3d(0.002, -0.001, 0.003)),
                Eigen::Vector3d(-0.11, 0.0004, -0.0008));
  const CamchainPriorCostFunction cost(
      c.intrinsics, reference, c.chain ? std::optional<SE3d>(T0) : std::nullopt, covariance);
  ASSERT_EQ(cost.num_residuals(), n);

  // The state: intrinsics off the reference, and T_cn_imu T_cnm1_imu^-1 = T0 Exp(xi) with a
  // tangent of about 0.02 (far above a real prior's, so that Jr^-1 matters).
  IntrinsicsVector theta = reference;
  for (int i = 0; i < kNumIntrinsics; ++i) theta(i) += (i < 6 ? 0.7 : 3e-3) * std::sin(3.0 * i);
  Vector6d xi;
  xi << 0.004, -0.003, 0.002, 0.02, -0.015, 0.01;
  const SE3d T_cnm1_imu(SO3d::Exp(Eigen::Vector3d(0.3, -1.2, 1.5)),
                        Eigen::Vector3d(0.02, 0.06, -0.01));
  const SE3d T_cn_imu = T0 * SE3d::Exp(xi) * T_cnm1_imu;
  std::array<double, 7> block_n;
  std::array<double, 7> block_nm1;
  PoseToBlock(T_cn_imu, block_n.data());
  PoseToBlock(T_cnm1_imu, block_nm1.data());
  std::vector<double*> blocks;
  if (m > 0) blocks.push_back(theta.data());
  if (c.chain) blocks.insert(blocks.end(), {block_n.data(), block_nm1.data()});

  // |r|^2 = d^T Sigma^-1 d.
  Eigen::VectorXd d(n);
  for (int j = 0; j < m; ++j) d(j) = theta(c.intrinsics[j]) - reference(c.intrinsics[j]);
  if (c.chain) d.tail<6>() = xi;
  Eigen::VectorXd r(n);
  testing::FreeBlockJacobians J(cost);
  ASSERT_TRUE(cost.Evaluate(blocks.data(), r.data(), J.pointers.data()));
  EXPECT_NEAR(r.squaredNorm(), d.dot(covariance.ldlt().solve(d)), 1e-9 * r.squaredNorm());

  SE3Manifold manifold;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const int size = cost.parameter_block_sizes()[b];
    const bool pose = size == 7;
    const int tangent = pose ? 6 : size;
    Eigen::MatrixXd analytic = J.Ambient(b);
    if (pose) {
      testing::FreeBlockJacobians::RowMajor P(7, 6);
      manifold.PlusJacobian(blocks[b], P.data());
      analytic = analytic * P;
    }
    auto f = [&](const Eigen::VectorXd& delta) {
      return testing::ResidualsWithBlockMoved(cost, blocks, b, delta);
    };
    testing::RiddersOptions options;
    options.initial_step = 1e-3;
    const Eigen::MatrixXd numeric =
        testing::RiddersJacobian(f, Eigen::VectorXd::Zero(tangent), options);
    const double largest = analytic.cwiseAbs().maxCoeff();
    ASSERT_GT(largest, 0.0);
    EXPECT_LT((analytic - numeric).cwiseAbs().maxCoeff() / largest, kRelativeTolerance)
        << "block " << b;
  }
}

INSTANTIATE_TEST_SUITE_P(Blocks,
                         CamchainPriorTest,
                         ::testing::Values(Case{{0, 1, 2, 3, 6, 7, 8, 9}, false},
                                           Case{{}, true},
                                           Case{{4, 5, 0, 1, 2, 3}, true}));

}  // namespace
}  // namespace splinecal
