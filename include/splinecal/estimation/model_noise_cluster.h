// The cluster label of a residual whose noise its weights state as it is, for the cluster-robust
// covariance (estimation/marginal_covariance.h, MarginalCovarianceOptions::cluster_of).
//
// A prior from an earlier estimate, r = L^-1 (theta - theta_0) with Sigma = L L^T that
// estimate's covariance, is such a residual: its noise is that estimate's error, independent of
// this problem's data, with covariance Sigma, so its pull J^T e has variance J^T J exactly. The
// cluster-robust covariance takes it so,
//   (H^-1 M H^-1)_cc,   M = G / (G - 1) sum_k g_k g_k^T  +  sum_{model-noise residuals} J^T J,
// with G the data's clusters only. Its realised pull is not a sample of that variance: at the
// solution it balances the data's pulls (all pulls sum to 0), so taken as a cluster of its own
// it would return the data's disagreement with the prior as the prior's noise (a prior 2 of its
// stds from the data would count 4 times its variance).
#ifndef SPLINECAL_ESTIMATION_MODEL_NOISE_CLUSTER_H_
#define SPLINECAL_ESTIMATION_MODEL_NOISE_CLUSTER_H_

namespace splinecal {

// cluster_of's value for such a residual (the data's clusters are >= 0).
inline constexpr int kModelNoiseCluster = -1;

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_MODEL_NOISE_CLUSTER_H_
