#include "splinecal/estimation/marginal_covariance.h"

#include <ceres/ceres.h>
#include <ceres/covariance.h>
#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <utility>

#include "compressed_information.h"

namespace splinecal {

using internal::CompressedInformation;

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
    const bool extras = options.cluster_of || !options.noise_factors.empty() ||
                        options.reported_map.size() > 0;
    std::vector<internal::ResidualLabel> clusterings;
    if (options.cluster_of) {
      clusterings.push_back(options.cluster_of);
      for (const auto& further : options.further_cluster_of) clusterings.push_back(further);
    }
    CompressedInformation compressed(problem, options.group_of, clusterings, options.num_threads);
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
      result.method = "sparse LDL^T of the compressed information (block minimum degree order)";
      Eigen::MatrixXd mapped;
      CompressedInformation::CovarianceExtras covariance_extras;
      covariance_extras.A = options.reported_map;
      covariance_extras.label_factors = options.noise_factors;
      ok = compressed.MappedCovariance(blocks, &mapped, &covariance_extras);
      if (ok) {
        full.resize(mapped.rows(), mapped.cols());
        full = mapped;
        if (covariance_extras.noise.allFinite() && covariance_extras.noise.size() > 0) {
          result.noise_covariance = covariance_extras.noise;
        }
        // The first clustering is cluster_of's, the others the further ones.
        for (size_t c = 0; c < clusterings.size(); ++c) {
          MarginalCovariance& target = c == 0 ? result : result.further.emplace_back();
          const Eigen::MatrixXd& robust = covariance_extras.robust[c];
          if (robust.allFinite() && robust.size() > 0) {
            target.robust_covariance = robust;
            target.num_clusters = compressed.num_clusters(static_cast<int>(c));
          }
        }
      }
    }
  }
  result.ok = ok && full.allFinite();
  if (result.ok) result.covariance = full;
  for (MarginalCovariance& further : result.further) {
    further.ok = result.ok;
    further.method = result.method;
    if (further.ok) further.covariance = result.covariance;
    further.noise_covariance = result.noise_covariance;
  }
  return result;
}

ReportedCovariance ReportedCovarianceOf(const MarginalCovariance& marginal) {
  ReportedCovariance reported;
  const Eigen::MatrixXd& model = marginal.covariance;
  const int n = static_cast<int>(model.rows());
  Eigen::VectorXd variance = model.diagonal();
  const Eigen::VectorXd model_variance = variance;
  if (marginal.noise_covariance.rows() == n) {
    variance = variance.cwiseMax(marginal.noise_covariance.diagonal());
  }
  reported.robust_ratio = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  if (marginal.robust_covariance.rows() == n && marginal.num_clusters >= 2) {
    // Wilson-Hilferty: chi^2_k quantile ~ k (1 - 2/(9k) + z sqrt(2/(9k)))^3, z = 1.645 (95%).
    const double k = marginal.num_clusters - 1.0;
    const double c = 2.0 / (9.0 * k);
    const double quantile = std::pow(1.0 - c + 1.6448536 * std::sqrt(c), 3);
    reported.robust_threshold = std::sqrt(quantile);
    for (int i = 0; i < n; ++i) {
      const double ratio = marginal.robust_covariance(i, i) / variance[i];
      reported.robust_ratio[i] = std::sqrt(std::max(0.0, ratio));
      if (ratio > quantile) variance[i] = marginal.robust_covariance(i, i);
    }
  }
  reported.inflation = (variance.array() / model_variance.array()).sqrt().matrix();
  reported.covariance =
      reported.inflation.asDiagonal() * model * reported.inflation.asDiagonal();
  return reported;
}

}  // namespace splinecal
