// The CHOLMOD factorisation behind the covariances and variance components
// (src/estimation/sparse_cholesky.h) against Eigen: the same square root P^T L^-T of H^-1 as
// Eigen's SimplicialLLT (what the Hutchinson probes used before, so the noise levels stay the
// same), the same solves as a dense decomposition, and a refusal of an indefinite matrix.
#include "../../src/estimation/sparse_cholesky.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <random>
#include <vector>

namespace splinecal {
namespace estimation_internal {
namespace {

// A spline-like information matrix: a band of half-width `band` (the control poses), plus
// `border` columns coupled to everything (the calibration blocks), plus a diagonal load.
Eigen::SparseMatrix<double> SplineLikeInformation(int n, int band, int border, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  // H = J^T J + I from a random sparse J with that structure: positive definite by construction.
  std::vector<Eigen::Triplet<double>> rows;
  int row = 0;
  for (int i = 0; i + band < n - border; ++i, ++row) {
    for (int j = i; j <= i + band; ++j) rows.emplace_back(row, j, normal(rng));
    for (int j = n - border; j < n; ++j) rows.emplace_back(row, j, normal(rng));
  }
  Eigen::SparseMatrix<double> J(row, n);
  J.setFromTriplets(rows.begin(), rows.end());
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  Eigen::SparseMatrix<double> H = Eigen::SparseMatrix<double>(J.transpose() * J) + identity;
  H.makeCompressed();
  return H;
}

TEST(SparseCholeskyTest, SquareRootOfTheInverseIsEigensSimplicialOne) {
  const Eigen::SparseMatrix<double> H = SplineLikeInformation(400, 23, 9, 1);
  const SparseCholesky cholmod(H);
  ASSERT_TRUE(cholmod.ok());
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> eigen(H);
  ASSERT_EQ(eigen.info(), Eigen::Success);
  const Eigen::MatrixXd Z = Eigen::MatrixXd::Random(400, 5);
  const Eigen::MatrixXd W = cholmod.SolveLt(Z);
  ASSERT_EQ(W.rows(), 400);
  for (int p = 0; p < Z.cols(); ++p) {
    const Eigen::VectorXd v = eigen.matrixU().solve(Eigen::VectorXd(Z.col(p)));
    const Eigen::VectorXd w = eigen.permutationPinv() * v;
    // Both are the unique factor of the same ordering: they differ by rounding only.
    EXPECT_LT((W.col(p) - w).norm(), 1e-12 * w.norm()) << "probe " << p;
  }
  // And W W^T is H^-1 (checked on the probes: H W W^T Z' = Z' for Z' = L^T P z).
  const Eigen::MatrixXd Hd = Eigen::MatrixXd(H);
  const Eigen::MatrixXd inverse = Hd.ldlt().solve(Eigen::MatrixXd::Identity(400, 400));
  const Eigen::MatrixXd unit = cholmod.SolveLt(Eigen::MatrixXd::Identity(400, 400));
  EXPECT_LT((unit * unit.transpose() - inverse).norm(), 1e-10 * inverse.norm());
}

TEST(SparseCholeskyTest, SolvesLikeADenseDecomposition) {
  const Eigen::SparseMatrix<double> H = SplineLikeInformation(300, 17, 6, 2);
  const SparseCholesky cholmod(H);
  ASSERT_TRUE(cholmod.ok());
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(300, 7);
  const Eigen::MatrixXd X = cholmod.Solve(B);
  const Eigen::MatrixXd expected = Eigen::MatrixXd(H).ldlt().solve(B);
  ASSERT_EQ(X.rows(), 300);
  EXPECT_LT((X - expected).norm(), 1e-11 * expected.norm());
}

TEST(SparseCholeskyTest, RefusesAnIndefiniteMatrix) {
  Eigen::SparseMatrix<double> H = SplineLikeInformation(100, 5, 2, 3);
  H.coeffRef(50, 50) = -1.0;
  const SparseCholesky cholmod(H);
  EXPECT_FALSE(cholmod.ok());
  EXPECT_EQ(cholmod.SolveLt(Eigen::MatrixXd::Ones(100, 1)).size(), 0);
  EXPECT_EQ(cholmod.Solve(Eigen::MatrixXd::Ones(100, 1)).size(), 0);
}

}  // namespace
}  // namespace estimation_internal
}  // namespace splinecal
