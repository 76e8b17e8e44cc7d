// Supernodal sparse Cholesky (CHOLMOD) of a symmetric positive definite information matrix H,
// in the fill-reducing ordering Eigen's SimplicialLLT would choose (AMD on the full pattern).
// src-private: estimation/compressed_information.cc uses it for the covariances and the
// variance-component traces.
//
// Why not Eigen's SimplicialLLT: on the spline problems H has ~250 non-zeros per column of L
// (the bias splines and the calibration blocks couple hundreds of control poses), where a
// column-by-column factorisation takes seconds and a supernodal one (dense BLAS on column
// blocks) a fraction of that (docs/performance.md, issue 17). Why the same ordering: the Cholesky
// factor is unique for a given ordering, so the Hutchinson probes P^T L^-T z of
// CompressedInformation::LabelTraces -- and with them every noise level splinecal estimates --
// stay what they were with Eigen, up to rounding.
//
// With P the permutation and P H P^T = L L^T:
//   SolveLt(Z)  = P^T L^-T Z   (a square root of H^-1: E[w w^T] = H^-1 for z with E[z z^T] = I)
//   Solve(B)    = H^-1 B
#ifndef SPLINECAL_SRC_ESTIMATION_SPARSE_CHOLESKY_H_
#define SPLINECAL_SRC_ESTIMATION_SPARSE_CHOLESKY_H_

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

namespace splinecal {
namespace estimation_internal {

class SparseCholesky {
 public:
  // Factors H (square; both triangles stored, only the lower one is read). ok() is false when H
  // is not numerically positive definite or CHOLMOD fails.
  explicit SparseCholesky(const Eigen::SparseMatrix<double>& H);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  bool ok() const { return ok_; }
  Eigen::MatrixXd SolveLt(const Eigen::MatrixXd& Z) const;
  Eigen::MatrixXd Solve(const Eigen::MatrixXd& B) const;

 private:
  struct Cholmod;  // CHOLMOD's workspace and factor (cholmod.h stays out of this header)
  Eigen::MatrixXd SolveSystem(int system, const Eigen::MatrixXd& B) const;

  std::unique_ptr<Cholmod> cholmod_;
  bool ok_ = false;
};

}  // namespace estimation_internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ESTIMATION_SPARSE_CHOLESKY_H_
