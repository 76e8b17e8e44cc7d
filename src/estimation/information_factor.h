// The sparse LDL^T factorisation of a compressed information matrix H = J^T J (the normal
// equations of a solved spline problem), and what the covariances and the variance components
// take from it: solves H^-1 B, and the entries of H^-1 on the pattern of H (selected inversion).
// src-private: estimation/compressed_information.cc assembles H and uses it.
//
// Ordering. H is assembled in an elimination order chosen on the graph of its PARAMETER BLOCKS
// (BlockEliminationOrder: approximate minimum degree, Amestoy-Davis-Duff 1996, on the blocks).
// Minimum degree on the scalar columns fails on the spline problems with a bias spline: a bias
// control point is a 3-column block coupled to every control pose of its ~4 s support (2400
// columns at 0.01 s knots), which exceeds AMD's dense-row cut (10 sqrt(n) = 2088 for n = 43,599),
// so the heuristic moves it to the end, and then every pose column eliminated before it fills
// in with all the bias columns it has met. On the EuRoC calibration at 0.01 s knots that left
// 12.6M non-zeros in L (3.4e9 flops, the same with CHOLMOD's AMD and METIS); on the block graph
// (7.3k nodes, cut at 857) a bias block is an ordinary node, eliminated where its support ends:
// 2.9M non-zeros, 1.4e8 flops (docs/performance.md "Calibrate at Kalibr's knot density in
// under 20 s").
//
// Selected inversion (Takahashi, Fagan & Chen 1973; Erisman & Tinney 1975). With
// H = L D L^T (L unit lower triangular) and Z = H^-1 = L^-T D^-1 L^-1, column j of Z below the
// diagonal and its diagonal follow from the columns after it:
//
//   Z_ij = - sum_{k in S_j} Z_ik L_kj   (i in S_j),     Z_jj = 1 / D_j - sum_{k in S_j} L_kj Z_kj,
//
// S_j = the rows of L's column j. Every Z_ik needed lies in L's pattern (S_j minus anything
// before k is contained in S_k), so Z is computed on exactly L's pattern -- which holds H's -- at
// about the cost of the factorisation, instead of the dense inverse.
#ifndef SPLINECAL_SRC_ESTIMATION_INFORMATION_FACTOR_H_
#define SPLINECAL_SRC_ESTIMATION_INFORMATION_FACTOR_H_

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <vector>

namespace splinecal {
namespace internal {

// The order in which to eliminate num_blocks parameter blocks whose couplings are given as
// cliques (the block ids every residual group touches; each id in [0, num_blocks)): approximate
// minimum degree on the block graph. A permutation of 0 .. num_blocks - 1.
std::vector<int> BlockEliminationOrder(int num_blocks, const std::vector<std::vector<int>>& cliques);

class InformationFactor {
 public:
  // Factors H (square, symmetric; the upper triangle is read, in place when H holds only that
  // triangle) in its own order: assemble it in
  // BlockEliminationOrder. ok() is false when H is not numerically positive definite: a pivot
  // that is not finite or not above 1e-14 of its diagonal entry.
  explicit InformationFactor(const Eigen::SparseMatrix<double>& H);

  bool ok() const { return ok_; }
  Eigen::Index size() const { return diagonal_.size(); }
  // Non-zeros of L below the diagonal (the fill the ordering left).
  Eigen::Index FactorNonZeros() const { return ok_ ? ldlt_.matrixL().nestedExpression().nonZeros() : 0; }

  // H^-1 B (empty when !ok()).
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& B) const;

  // Computes H^-1 on the pattern of L (once; false when !ok()).
  bool ComputeSelectedInverse();
  // The dense (H^-1)[indices, indices] (indices distinct). Every pair of indices must be coupled
  // in H -- the indices of one residual group are -- or lie in L's pattern; a pair that does not
  // throws splinecal::Error. Needs ComputeSelectedInverse().
  Eigen::MatrixXd InverseOn(const std::vector<int>& indices) const;

 private:
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
      ldlt_;
  Eigen::VectorXd diagonal_;      // D
  bool ok_ = false;
  std::vector<double> inverse_;   // H^-1 below the diagonal, at L's stored positions
  Eigen::VectorXd inverse_diagonal_;
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ESTIMATION_INFORMATION_FACTOR_H_
