// The marginal covariance of some parameter blocks of a solved least-squares problem: blocks in,
// covariance out, in the blocks' tangent spaces (their manifolds' local coordinates).
//
// With J the Jacobian of the weighted residuals at the solution in tangent coordinates and
// H = J^T J the Gauss-Newton information, the wanted blocks c and all other free blocks a,
//
//   Cov(c) = (H^-1)_cc = (H_cc - H_ca H_aa^-1 H_ac)^-1        (Schur complement of H_aa).
//
// Every residual block enters H through its own Jacobian, grouped by its first parameter block
// (for the spline's residuals: the segment), and each group's information is stored once
// (dense, at most the group's tangent size squared: ~4x fewer rows than J at 200 Hz). The
// covariance is then computed by one of two backends, chosen by size:
//   * small problems: ceres::Covariance (SPARSE_QR, its rank detection) on the equivalent
//     problem whose residual per group is R d with R^T R = H_group (same J^T J, same answer);
//   * large ones (more than max_ceres_covariance_entries compressed Jacobian entries, where
//     ceres::Covariance's copies of the Jacobian would dominate memory): H_aa by a sparse LDLT
//     (AMD ordering; banded by the spline's local support) and the Schur complement above,
//     inverted through the eigen-decomposition of its diagonally scaled form, which refuses a
//     numerically singular complement (eigenvalues below 1e-12 of the largest).
// Both give the same numbers (tests/estimation/marginal_covariance_test.cc). Residuals with a
// ceres::LossFunction are taken without it (splinecal's robust residuals robustify inside).
#ifndef SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_
#define SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace splinecal {

enum class CovarianceBackend {
  kAuto,           // by size (file comment)
  kCeres,          // ceres::Covariance on the compressed problem
  kSchur,          // sparse Schur complement of the compressed information
  kCeresUncompressed,  // ceres::Covariance on the problem itself (tests: the reference)
};

struct MarginalCovarianceOptions {
  CovarianceBackend backend = CovarianceBackend::kAuto;
  // kAuto uses ceres::Covariance up to this many compressed Jacobian entries (~5 minutes of
  // 200 Hz IMU at dt = 0.1 s), the Schur complement above.
  double max_ceres_covariance_entries = 3e6;
  int num_threads = 1;
};

struct MarginalCovariance {
  bool ok = false;             // false: H is singular (some direction is not determined)
  Eigen::MatrixXd covariance;  // the requested blocks' tangent coordinates, in request order
  std::string method;          // which backend ran, in words
};

// The marginal covariance of `blocks` (free parameter blocks of `problem`, each at most once)
// at the problem's current values. Evaluates every residual block once.
MarginalCovariance ComputeMarginalCovariance(ceres::Problem* problem,
                                             const std::vector<const double*>& blocks,
                                             const MarginalCovarianceOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_
