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
//     ceres::Covariance's copies of the Jacobian would dominate memory): one sparse LDL^T of the
//     whole H, in a minimum-degree order of its parameter blocks (banded by the spline's local
//     support), and Cov(c) = (H^-1)_cc by one solve per reported coordinate; it refuses an H that
//     is not positive definite and a covariance whose correlation matrix is numerically singular
//     (eigenvalues below 1e-12 of the largest).
// Both give the same numbers (tests/estimation/marginal_covariance_test.cc). Residuals with a
// ceres::LossFunction are taken without it (splinecal's robust residuals robustify inside).
#ifndef SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_
#define SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace splinecal {

enum class CovarianceBackend {
  kAuto,           // by size (file comment)
  kCeres,          // ceres::Covariance on the compressed problem
  kSchur,          // (H^-1)_cc by a sparse factorisation of the compressed information
  kCeresUncompressed,  // ceres::Covariance on the problem itself (tests: the reference)
};

struct MarginalCovarianceOptions {
  CovarianceBackend backend = CovarianceBackend::kAuto;
  // kAuto uses ceres::Covariance up to this many compressed Jacobian entries (~5 minutes of
  // 200 Hz IMU at dt = 0.1 s), the sparse factorisation above.
  double max_ceres_covariance_entries = 3e6;
  int num_threads = 1;
  // Residual clusters for the cluster-robust covariance (below): the cluster (>= 0) of each
  // residual block, e.g. its time window. Empty: not computed. Uses the kSchur backend.
  std::function<int(ceres::ResidualBlockId)> cluster_of;
  // Further clusterings of the same residual blocks (e.g. by kind of view beside cluster_of's
  // time windows; each may put a residual in kModelNoiseCluster on its own), each giving its own
  // cluster-robust covariance from the same linearisation and factorisation as cluster_of's:
  // MarginalCovariance::further, in this order. Needs cluster_of.
  std::vector<std::function<int(ceres::ResidualBlockId)>> further_cluster_of;
  // Noise levels the data shows (estimation/variance_components.h): residual group l's variance
  // is noise_factors[l] times what its weights assume (groups by group_of; groups not listed:
  // 1). Empty: not computed. Uses the kSchur backend.
  std::function<int(ceres::ResidualBlockId)> group_of;
  std::map<int, double> noise_factors;
  // Reported quantities q = reported_map x of the blocks' tangent coordinates x (e.g. a bias
  // spline's time average); empty: q = x. With a map, every covariance of the result is of q.
  // Uses the kSchur backend.
  Eigen::MatrixXd reported_map;
};

struct MarginalCovariance {
  bool ok = false;             // false: H is singular (some direction is not determined)
  Eigen::MatrixXd covariance;  // the requested blocks' tangent coordinates, in request order
  std::string method;          // which backend ran, in words
  // With MarginalCovarianceOptions::cluster_of: the cluster-robust ("sandwich") covariance of
  // the same blocks (White 1982; Liang & Zeger 1986),
  //   (H^-1 M H^-1)_cc,   M = G / (G - 1) sum_k g_k g_k^T,   g_k = sum_{i in cluster k} J_i^T e_i,
  // which stays honest when the residuals are correlated within a cluster or the model misses
  // something (vibration, a knot spacing too coarse, unmodelled sensor errors): it measures how
  // much the clusters' pulls on the solution actually scatter instead of assuming it from the
  // weights. Empty when not asked for or with fewer than 2 clusters.
  Eigen::MatrixXd robust_covariance;
  int num_clusters = 0;
  // With noise_factors: the covariance of the same estimate when the residuals' noise is the one
  // the data shows, H^-1 (sum_l f_l H_l) H^-1 (the weights stay as they were: an estimate
  // weighted by assumed noise, whose covariance uses the measured noise). Empty otherwise.
  Eigen::MatrixXd noise_covariance;
  // One per MarginalCovarianceOptions::further_cluster_of: ok, covariance, method and
  // noise_covariance as above, robust_covariance and num_clusters of that clustering.
  std::vector<MarginalCovariance> further;
};

// The covariance an estimate reports (docs/calibrate.md, "How much to trust the numbers"):
// each variance is the largest of
//   * the weights' (covariance: the noise the weights assume),
//   * the measured noise's (noise_covariance), and
//   * the cluster-robust one (robust_covariance), where it is significantly larger: beyond the
//     95% quantile of its own scatter under the noise model, chi^2_{G-1} / (G - 1) for G
//     clusters (Wilson-Hilferty). Below it the difference is the robust estimate's own noise
//     (it rests on G clusters only), and taking it would only add that noise.
// Row and column k are scaled by the same factor, so the correlations stay those of the noise
// model.
struct ReportedCovariance {
  Eigen::MatrixXd covariance;
  Eigen::VectorXd inflation;      // reported std / the weights' std, per coordinate
  Eigen::VectorXd robust_ratio;   // cluster-robust std / the noise model's std (NaN: none)
  double robust_threshold = 0.0;  // the std ratio above which the robust one is taken
};
ReportedCovariance ReportedCovarianceOf(const MarginalCovariance& marginal);

// The marginal covariance of `blocks` (free parameter blocks of `problem`, each at most once)
// at the problem's current values. Evaluates every residual block once.
MarginalCovariance ComputeMarginalCovariance(ceres::Problem* problem,
                                             const std::vector<const double*>& blocks,
                                             const MarginalCovarianceOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_MARGINAL_COVARIANCE_H_
