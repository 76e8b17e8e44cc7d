// The Gauss-Newton information J^T J of a solved ceres::Problem, compressed per group of residual
// blocks (src-private: estimation/marginal_covariance.cc and estimation/variance_components.cc
// share it).
//
// Residual blocks are grouped by (label, first parameter block): for the spline's residuals the
// first block is the segment's first control pose, so a group is one residual kind over one
// segment. Each group stores its information H_g = sum J^T J over the union of its blocks in
// tangent coordinates, block by block: the pairs of blocks some residual block couples, each
// dense (a spline segment's group is dense, ~4x fewer entries than J at 200 Hz; a target
// view's group with every point free couples each point's offset with the pose and the
// intrinsics, not with the other points, so that most of its square is zero: the free-target
// intrinsics on EuRoC's imu_april peaked at 2.5 GB with dense groups, 0.67 GB without). The sum
// of the groups is the problem's H; the label keeps residual kinds apart so that per-kind
// quantities -- tr(H^-1 H_label) for variance components -- can be formed.
#ifndef SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_
#define SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace splinecal {
namespace internal {

// The label of a residual block (>= 0), or -1 to leave it out of the information entirely.
using ResidualLabel = std::function<int(ceres::ResidualBlockId)>;

class CompressedInformation {
 public:
  // Evaluates every residual block of `problem` once at its current values. label_of may be
  // empty (every block gets label 0). clusterings (may be empty): ways to cluster the residual
  // blocks for the cluster-robust covariance, each giving every residual block its cluster
  // (>= 0); per clustering the gradient g_k = sum J^T e of each cluster's residuals is kept; a
  // block of kModelNoiseCluster (estimation/model_noise_cluster.h) is in no cluster of that
  // clustering, its information J^T J is kept apart instead. One linearisation serves every
  // clustering. The residual blocks are evaluated on up to num_threads threads
  // (their cost functions must allow it, as Ceres' do) and merged in order, so the result does
  // not depend on num_threads.
  explicit CompressedInformation(ceres::Problem* problem,
                                 const ResidualLabel& label_of = {},
                                 const std::vector<ResidualLabel>& clusterings = {},
                                 int num_threads = 1);

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

  // The covariance of q = A x, x the requested blocks' tangent coordinates (A empty: q = x),
  // every other block being nuisance: A Cov(c) A^T with Cov(c) = (H^-1)_cc
  // = (H_cc - H_ca H_aa^-1 H_ac)^-1. Computed from one sparse LDL^T of the whole H
  // (estimation/information_factor.h) as B^T Y with Y = H^-1 B, B = E_c A^T (E_c places the
  // requested coordinates in H): one solve per reported coordinate, whatever the number of
  // requested ones (calibrate's 450 bias coordinates enter through their 6 time averages).
  // False when H is not positive definite, or when the covariance of q is numerically singular
  // (its correlation matrix has an eigenvalue below 1e-12 of its largest: a combination of the
  // reported quantities the data does not determine). Consumes the groups.
  // Extras, with Y as above:
  //   * robust, one per clustering: the cluster-robust covariance A (H^-1 M H^-1)_cc A^T with
  //     M = G / (G - 1) sum_k g_k g_k^T over the G clusters, plus the information H_m of the
  //     kModelNoiseCluster residuals: sum_k (Y^T g_k)(Y^T g_k)^T G/(G-1) + Y_m^T H_m Y_m
  //     (empty for a clustering of fewer than 2 clusters);
  //   * with label_factors (label -> f_l), noise: the covariance when label l's residuals have
  //     f_l times the variance their weights assume, A (H^-1 (sum_l f_l H_l) H^-1)_cc A^T
  //     = B^T Y + sum_{groups of labels with f != 1} (f - 1) Y_g^T H_g Y_g (Y_g: the group's
  //     rows of Y).
  struct CovarianceExtras {
    Eigen::MatrixXd A;
    std::map<int, double> label_factors;
    std::vector<Eigen::MatrixXd> robust;  // per clustering
    Eigen::MatrixXd noise;   // empty without label_factors
  };
  bool MappedCovariance(const std::vector<const double*>& requested,
                        Eigen::MatrixXd* covariance,
                        CovarianceExtras* extras = nullptr);
  int num_clusters(int clustering) const {
    return static_cast<int>(cluster_gradients_.at(clustering).size());
  }

  // t_l = tr(H^-1 H_l) for every label l (H_l = the information of label l's residuals): the
  // number of parameters label l's residuals determine, sum_l t_l = dim H. Exact: each group's
  // tr(H^-1 H_g) = sum (H^-1 .* H_g) over the group's coordinates, whose entries of H^-1 come
  // from the selected inversion of estimation/information_factor.h (H^-1 on H's own pattern).
  // False when H is not positive definite. Keeps the groups.
  bool LabelTraces(std::map<int, double>* traces) const;

 private:
  struct Group {
    std::vector<const double*> blocks;
    std::vector<int> sizes;
    std::vector<int> offsets;  // of each block in the group's stacked coordinates
    // The non-zero blocks H_ab (a <= b, indices into blocks) of the group's information; the
    // pairs absent are zero.
    std::map<std::pair<int, int>, Eigen::MatrixXd> H;
    int Index(const double* block, int size);
    int Size() const;  // the blocks' total tangent size
    // H_ab (a <= b), zero when first asked for.
    Eigen::MatrixXd& Pair(int a, int b);
    // The whole symmetric Size() x Size() information.
    Eigen::MatrixXd Dense() const;
  };
  // (label, ordinal of the first parameter block). Ordinals, not addresses: every sum over
  // groups or blocks then runs in an order fixed by the problem, so that the same problem built
  // twice (at other heap addresses) gives the same covariance to the last bit.
  using GroupKey = std::pair<int, int>;

  // Adds a residual block's J^T J to `group`: parts = (index in the group, first column in J).
  static void AddInformation(const Eigen::MatrixXd& JtJ,
                             const std::vector<std::pair<int, int>>& parts,
                             Group* group);
  // Y_g^T H_g Y_g, Y_g the rows of Y (over H's coordinates, `offsets`) of the group's blocks.
  static Eigen::MatrixXd QuadraticForm(const Group& group,
                                       const Eigen::MatrixXd& Y,
                                       const std::map<const double*, int>& offsets);

  // Every block's offset in H in the elimination order of estimation/information_factor.h
  // (minimum degree on the block graph); returns the size of H.
  int EliminationOffsets(std::map<const double*, int>* offsets) const;
  // The upper triangle (diagonal included) of the sparse H = sum of the groups' information,
  // each block at offsets[block]: what the factorisation reads, as it reads it (no copy).
  Eigen::SparseMatrix<double> Assemble(const std::map<const double*, int>& offsets,
                                       int size) const;

  bool evaluation_failed_ = false;            // a residual block could not be evaluated
  std::map<GroupKey, Group> groups_;
  std::map<const double*, int> block_sizes_;  // tangent sizes
  std::map<int, int> num_residuals_;
  std::map<int, double> squared_sum_;
  // Per clustering, per cluster, per (free) parameter block by ordinal: the tangent gradient
  // J^T e of its residuals.
  std::vector<std::map<int, std::map<int, Eigen::VectorXd>>> cluster_gradients_;
  // The parameter blocks of the residual blocks in the order they first appear there (residual
  // blocks in the order they were added), and each block's place in it.
  std::vector<const double*> blocks_by_ordinal_;
  std::unordered_map<const double*, int> ordinal_;
  // Per clustering, the information of its kModelNoiseCluster residuals (also in groups_), by
  // the same key.
  std::vector<std::map<GroupKey, Group>> model_noise_groups_;
  std::map<const double*, std::vector<double>> tangent_blocks_;
  std::unique_ptr<ceres::Problem> compressed_;
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ESTIMATION_COMPRESSED_INFORMATION_H_
