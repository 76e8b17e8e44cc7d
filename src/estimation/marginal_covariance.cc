#include "splinecal/estimation/marginal_covariance.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>
#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "compressed_information.h"

namespace splinecal {

using estimation_internal::CompressedInformation;

MarginalCovariance ComputeMarginalCovariance(ceres::Problem* problem,
                                             const std::vector<const double*>& blocks,
                                             const MarginalCovarianceOptions& options) {
  MarginalCovariance result;
  int tangent_total = 0;
  for (const double* block : blocks) tangent_total += problem->ParameterBlockTangentSize(block);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> full(tangent_total,
                                                                              tangent_total);
  ceres::Covariance::Options covariance_options;
  covariance_options.num_threads = options.num_threads;
  covariance_options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(covariance_options);
  bool ok = false;
  if (options.backend == CovarianceBackend::kCeresUncompressed) {
    result.method = "ceres::Covariance (SPARSE_QR) on the problem";
    ok = covariance.Compute(blocks, problem);
    if (ok) ok = covariance.GetCovarianceMatrixInTangentSpace(blocks, full.data());
  } else {
    const bool extras = options.cluster_of || !options.noise_factors.empty();
    CompressedInformation compressed(problem, options.group_of, options.cluster_of);
    if (compressed.evaluation_failed()) {
      result.method = "none: a residual could not be evaluated at the solution";
      return result;
    }
    const bool use_ceres = options.backend == CovarianceBackend::kCeres ||
                           (options.backend == CovarianceBackend::kAuto && !extras &&
                            compressed.CompressedEntries() <= options.max_ceres_covariance_entries);
    if (use_ceres) {
      result.method = "ceres::Covariance (SPARSE_QR) on the compressed problem";
      compressed.BuildCeresProblem();
      std::vector<const double*> tangent_blocks;
      ok = true;
      for (const double* block : blocks) {
        tangent_blocks.push_back(compressed.TangentBlock(block));
        ok = ok && tangent_blocks.back() != nullptr;
      }
      if (ok) ok = covariance.Compute(tangent_blocks, compressed.problem());
      if (ok) ok = covariance.GetCovarianceMatrixInTangentSpace(tangent_blocks, full.data());
    } else {
      result.method = "Schur complement by sparse Cholesky of the compressed information";
      Eigen::MatrixXd marginal;
      Eigen::MatrixXd robust;
      Eigen::MatrixXd scaled;
      ok = compressed.SchurCovariance(blocks,
                                      &marginal,
                                      options.cluster_of ? &robust : nullptr,
                                      options.noise_factors,
                                      &scaled);
      if (ok) full = marginal;
      if (ok && scaled.size() > 0 && scaled.allFinite()) result.noise_covariance = scaled;
      if (ok && robust.size() > 0 && robust.allFinite()) {
        result.robust_covariance = robust;
        result.num_clusters = compressed.num_clusters();
      }
    }
  }
  result.ok = ok && full.allFinite();
  if (result.ok) result.covariance = full;
  return result;
}

}  // namespace splinecal
