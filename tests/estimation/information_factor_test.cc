// The factorisation behind the covariances and variance components
// (src/estimation/information_factor.h): its solves and its selected inverse against the dense
// inverse, its refusal of singular and indefinite matrices, and the fill of the block ordering
// against minimum degree on the scalars on a spline-like structure with a bias spline.
#include "../../src/estimation/information_factor.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/OrderingMethods>
#include <random>
#include <vector>

#include "splinecal/error.h"

namespace splinecal {
namespace internal {
namespace {

// The normal equations of a spline problem in miniature: `poses` 6-column control-pose blocks,
// each residual group coupling 4 consecutive ones (an IMU segment) with the bias control point
// whose support holds them (3 columns; a new point every bias_spacing poses, each reaching over
// 4 spacings; a gyro and an accelerometer block per point), and one 9-column block coupled to
// everything (extrinsic, gravity, time offset).
// H = J^T J + I from random rows with that pattern: positive definite by construction.
struct SplineLikeProblem {
  int num_blocks = 0;
  std::vector<int> block_start;             // scalar offset of each block, then the size
  std::vector<std::vector<int>> cliques;    // the blocks of each residual group
  Eigen::SparseMatrix<double> H;            // in the blocks' own order
};

SplineLikeProblem MakeSplineLike(int poses, int bias_spacing, uint32_t seed) {
  SplineLikeProblem p;
  const int num_bias = poses / bias_spacing + 4;
  std::vector<int> sizes(poses, 6);
  for (int m = 0; m < 2 * num_bias; ++m) sizes.push_back(3);
  sizes.push_back(9);
  p.num_blocks = static_cast<int>(sizes.size());
  p.block_start.push_back(0);
  for (int s : sizes) p.block_start.push_back(p.block_start.back() + s);
  const int n = p.block_start.back();
  const int global = p.num_blocks - 1;
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<Eigen::Triplet<double>> rows;
  int row = 0;
  for (int i = 0; i + 4 <= poses; ++i) {
    std::vector<int> clique = {i, i + 1, i + 2, i + 3};
    const int first_bias = i / bias_spacing;
    for (int m = first_bias; m < first_bias + 4; ++m) {
      clique.push_back(poses + 2 * m);      // gyro bias point
      clique.push_back(poses + 2 * m + 1);  // accelerometer bias point
    }
    clique.push_back(global);
    for (int r = 0; r < 6; ++r, ++row) {
      for (int b : clique) {
        for (int c = p.block_start[b]; c < p.block_start[b + 1]; ++c) {
          rows.emplace_back(row, c, normal(rng));
        }
      }
    }
    p.cliques.push_back(clique);
  }
  Eigen::SparseMatrix<double> J(row, n);
  J.setFromTriplets(rows.begin(), rows.end());
  Eigen::SparseMatrix<double> identity(n, n);
  identity.setIdentity();
  p.H = Eigen::SparseMatrix<double>(J.transpose() * J) + identity;
  p.H.makeCompressed();
  return p;
}

// P H P^T with the blocks in `order` (each block's columns kept together and in order), and
// the scalar permutation used (new index of each old one).
Eigen::SparseMatrix<double> InBlockOrder(const SplineLikeProblem& p,
                                         const std::vector<int>& order,
                                         std::vector<int>* new_index) {
  new_index->assign(p.block_start.back(), -1);
  int next = 0;
  for (int b : order) {
    for (int c = p.block_start[b]; c < p.block_start[b + 1]; ++c) (*new_index)[c] = next++;
  }
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P(p.block_start.back());
  for (int c = 0; c < p.block_start.back(); ++c) P.indices()[c] = (*new_index)[c];
  Eigen::SparseMatrix<double> permuted;
  permuted = p.H.selfadjointView<Eigen::Lower>().twistedBy(P);
  return permuted;
}

TEST(BlockEliminationOrder, IsAPermutationOfTheBlocks) {
  const SplineLikeProblem p = MakeSplineLike(60, 10, 1);
  std::vector<int> order = BlockEliminationOrder(p.num_blocks, p.cliques);
  ASSERT_EQ(static_cast<int>(order.size()), p.num_blocks);
  std::sort(order.begin(), order.end());
  for (int b = 0; b < p.num_blocks; ++b) EXPECT_EQ(order[b], b);
}

// The reason for the block order: with a bias point's scalar degree above AMD's dense-row cut
// (here over 960 columns against 10 sqrt(7,413) = 861), minimum degree on the scalars leaves
// more than twice the fill of the block order (calibrate on EuRoC at 0.01 s knots: 4.3 times).
TEST(BlockEliminationOrder, LeavesLessFillThanScalarMinimumDegreeWithABiasSpline) {
  const SplineLikeProblem p = MakeSplineLike(1200, 40, 2);
  std::vector<int> new_index;
  const InformationFactor blocks(
      InBlockOrder(p, BlockEliminationOrder(p.num_blocks, p.cliques), &new_index));
  ASSERT_TRUE(blocks.ok());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>>
      scalars(p.H);
  ASSERT_EQ(scalars.info(), Eigen::Success);
  const Eigen::Index scalar_fill = scalars.matrixL().nestedExpression().nonZeros();
  EXPECT_LT(blocks.FactorNonZeros(), scalar_fill / 2)
      << "block order " << blocks.FactorNonZeros() << " vs scalar AMD " << scalar_fill;
}

TEST(InformationFactor, SolvesAndSelectedInverseMatchTheDenseInverse) {
  const SplineLikeProblem p = MakeSplineLike(80, 12, 3);
  std::vector<int> new_index;
  const Eigen::SparseMatrix<double> H =
      InBlockOrder(p, BlockEliminationOrder(p.num_blocks, p.cliques), &new_index);
  InformationFactor factor(H);
  ASSERT_TRUE(factor.ok());
  const Eigen::SparseMatrix<double> full = H.selfadjointView<Eigen::Lower>();
  const Eigen::MatrixXd dense = Eigen::MatrixXd(full);
  const Eigen::MatrixXd inverse = dense.inverse();
  const double scale = inverse.cwiseAbs().maxCoeff();
  std::mt19937 rng(4);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd B(H.rows(), 3);
  for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = normal(rng);
  EXPECT_LT((factor.Solve(B) - inverse * B).cwiseAbs().maxCoeff(),
            1e-10 * (inverse * B).cwiseAbs().maxCoeff());
  ASSERT_TRUE(factor.ComputeSelectedInverse());
  // Every residual group's coordinates: the entries the variance components read.
  for (const std::vector<int>& clique : p.cliques) {
    std::vector<int> indices;
    for (int b : clique) {
      for (int c = p.block_start[b]; c < p.block_start[b + 1]; ++c) {
        indices.push_back(new_index[c]);
      }
    }
    const Eigen::MatrixXd Z = factor.InverseOn(indices);
    for (size_t a = 0; a < indices.size(); ++a) {
      for (size_t b = 0; b < indices.size(); ++b) {
        ASSERT_NEAR(Z(a, b), inverse(indices[a], indices[b]), 1e-11 * scale) << a << " " << b;
      }
    }
  }
}

TEST(InformationFactor, InverseOnRefusesAPairOutsideThePattern) {
  const SplineLikeProblem p = MakeSplineLike(200, 10, 5);
  std::vector<int> new_index;
  InformationFactor factor(
      InBlockOrder(p, BlockEliminationOrder(p.num_blocks, p.cliques), &new_index));
  ASSERT_TRUE(factor.ComputeSelectedInverse());
  // The first and the last control pose share no residual and no fill: (H^-1) there is not
  // computed.
  EXPECT_THROW(factor.InverseOn({new_index[p.block_start[0]], new_index[p.block_start[199]]}),
               Error);
}

TEST(InformationFactor, RefusesSingularAndIndefiniteMatrices) {
  Eigen::SparseMatrix<double> singular(3, 3);  // rank 2: rows 1 and 2 equal
  singular.insert(0, 0) = 2.0;
  singular.insert(1, 1) = 1.0;
  singular.insert(2, 1) = 1.0;
  singular.insert(1, 2) = 1.0;
  singular.insert(2, 2) = 1.0;
  EXPECT_FALSE(InformationFactor(singular).ok());
  Eigen::SparseMatrix<double> indefinite(2, 2);
  indefinite.insert(0, 0) = 1.0;
  indefinite.insert(1, 0) = 2.0;
  indefinite.insert(0, 1) = 2.0;
  indefinite.insert(1, 1) = 1.0;
  InformationFactor factor(indefinite);
  EXPECT_FALSE(factor.ok());
  EXPECT_FALSE(factor.ComputeSelectedInverse());
  EXPECT_EQ(factor.Solve(Eigen::MatrixXd::Ones(2, 1)).size(), 0);
}

}  // namespace
}  // namespace internal
}  // namespace splinecal
