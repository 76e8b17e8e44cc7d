// The Gauss-Newton information J^T J of a solved ceres::Problem, compressed per group of residual
// blocks (src-private: estimation/marginal_covariance.cc and estimation/variance_components.cc
// share it).
//
// Residual blocks are grouped by (label, first parameter block): for the spline's residuals the
// first block is the segment's first control pose, so a group is one residual kind over one
// segment. Each group stores its information H_g = sum J^T J over the union of its blocks in
// tangent coordinates (dense, at most the group's tangent size squared: ~4x fewer entries than
// J at 200 Hz). The sum of the groups is the problem's H; the label keeps residual kinds apart
// so that per-kind quantities -- tr(H^-1 H_label) for variance components -- can be formed.
#ifndef SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_
#define SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <utility>
#include <vector>

namespace splinecal {
namespace estimation_internal {

// The label of a residual block (>= 0), or -1 to leave it out of the information entirely.
using ResidualLabel = std::function<int(ceres::ResidualBlockId)>;

class CompressedInformation {
 public:
  // Evaluates every residual block of `problem` once at its current values. label_of may be
  // empty (every block gets label 0). cluster_of (may be empty): the cluster of each residual
  // block (>= 0) for the cluster-robust covariance; the gradient g_k = sum J^T e of each
  // cluster's residuals is kept.
  explicit CompressedInformation(ceres::Problem* problem,
                                 const ResidualLabel& label_of = {},
                                 const ResidualLabel& cluster_of = {});

  bool evaluation_failed() const { return evaluation_failed_; }

  // Entries of the compressed Jacobian (sum of the groups' squared dimensions).
  double CompressedEntries() const;

  // Per label: the number of residual rows and the sum of their squared (weighted) residuals.
  const std::map<int, int>& num_residuals() const { return num_residuals_; }
  const std::map<int, double>& squared_sum() const { return squared_sum_; }

  // The compressed problem over tangent blocks: one linear residual R [d...] per group with
  // H = R^T R (eigen-decomposition; zero eigenvalues dropped). Consumes the groups.
  void BuildCeresProblem();
  ceres::Problem* problem() { return compressed_.get(); }
  // The tangent block standing for `block` after BuildCeresProblem (nullptr if it appears in no
  // residual).
  const double* TangentBlock(const double* block) const;

  // Cov(c) = (H_cc - H_ca H_aa^-1 H_ac)^-1 of the requested blocks c (every other block is
  // nuisance). False when H_aa is not positive definite or the complement is numerically
  // singular. Consumes the groups.
  // Extras in reported coordinates q = A x of the requested blocks' tangent coordinates x
  // (A empty: q = x):
  //   * mapped: A Cov(c) A^T;
  //   * with clusters, robust: the cluster-robust covariance A (H^-1 M H^-1)_cc A^T with
  //     M = G / (G - 1) sum_k g_k g_k^T over the G clusters, formed from
  //     A (H^-1 g)_c = W^T (g_c - H_ca H_aa^-1 g_a), W = Cov(c) A^T (block elimination);
  //   * with label_factors (label -> f_l), noise: the covariance when label l's residuals have
  //     f_l times the variance their weights assume, A (H^-1 (sum_l f_l H_l) H^-1)_cc A^T
  //     = A Cov(c) A^T + sum_{groups of labels with f != 1} (f - 1) (T W)_g^T H_g (T W)_g with
  //     T = [-H_aa^-1 H_ac; I] (the c rows of H^-1 are Cov(c) T^T, and T^T H T = Cov(c)^-1).
  struct SchurExtras {
    Eigen::MatrixXd A;
    std::map<int, double> label_factors;
    Eigen::MatrixXd mapped;
    Eigen::MatrixXd robust;  // empty without clusters (or fewer than 2)
    Eigen::MatrixXd noise;   // empty without label_factors
  };
  bool SchurCovariance(const std::vector<const double*>& requested,
                       Eigen::MatrixXd* covariance,
                       SchurExtras* extras = nullptr);
  int num_clusters() const { return static_cast<int>(cluster_gradients_.size()); }

  // t_l = tr(H^-1 H_l) for every label l (H_l = the information of label l's residuals): the
  // number of parameters label l's residuals determine, sum_l t_l = dim H. Estimated by
  // Hutchinson's method, t_l = E[w^T H_l w] with w = P^T L^-T z, z a Rademacher vector and
  // H = P^T L L^T P the sparse Cholesky factorisation, so that E[w w^T] = H^-1; `probes`
  // vectors from a fixed seed (relative std about sqrt(2 / (probes t_l))). False when H is not
  // positive definite. Keeps the groups.
  bool LabelTraces(int probes, std::map<int, double>* traces) const;

 private:
  struct Group {
    std::vector<const double*> blocks;
    std::vector<int> sizes;
    std::vector<int> offsets;
    Eigen::MatrixXd H;
    int Index(const double* block, int size);
    void Resize();
  };
  using GroupKey = std::pair<int, const double*>;  // (label, first parameter block)

  // The sparse H = sum of the groups' information, each block at offsets[block].
  Eigen::SparseMatrix<double> Assemble(const std::map<const double*, int>& offsets,
                                       int size) const;

  bool evaluation_failed_ = false;            // a residual block could not be evaluated
  std::map<GroupKey, Group> groups_;
  std::map<const double*, int> block_sizes_;  // tangent sizes
  std::map<int, int> num_residuals_;
  std::map<int, double> squared_sum_;
  // Per cluster, per (free) parameter block: the tangent gradient J^T e of its residuals.
  std::map<int, std::map<const double*, Eigen::VectorXd>> cluster_gradients_;
  std::map<const double*, std::vector<double>> tangent_blocks_;
  std::unique_ptr<ceres::Problem> compressed_;
};

}  // namespace estimation_internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_
