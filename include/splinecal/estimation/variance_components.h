// Variance components: the noise levels of groups of residuals re-estimated from the residuals
// themselves, so that the reported covariance reflects the noise the data shows rather than the
// noise a data sheet assumed (docs/calibrate.md, "How much to trust the numbers").
//
// A least-squares problem whose residual groups l (gyro, accelerometer, bias random walk,
// pixels, ...) are weighted 1 / sigma_l. At the solution, with e_l the weighted residuals of
// group l, n_l their number, H = J^T J the Gauss-Newton information and H_l group l's share of
// it, the estimate of group l's variance factor is (Foerstner 1979; Koch, "Parameter Estimation
// and Hypothesis Testing in Linear Models", 1999, sec. 3.6)
//
//   f_l = e_l^T e_l / r_l,        r_l = n_l - tr(H^-1 H_l)          (the redundancy of group l)
//
// and sigma_l is replaced by sigma_l sqrt(f_l); the problem is solved again with the new weights
// until the factors settle near 1. sum_l tr(H^-1 H_l) = dim H: each group "uses up" the
// parameters it determines, so e_l^T e_l / n_l alone would underestimate the noise of a group
// that determines many parameters (the gyro at fine knot spacings). The traces are exact: the
// entries of H^-1 they need lie on H's own pattern and come from a selected inversion of its
// sparse factorisation (src/estimation/information_factor.h). The relative standard
// deviation of f_l is about sqrt(2 / r_l): a group with a small redundancy (a bias random-walk
// prior that the data overrides) does not determine its own noise level, and `identifiable`
// says so.
#ifndef SPLINECAL_ESTIMATION_VARIANCE_COMPONENTS_H_
#define SPLINECAL_ESTIMATION_VARIANCE_COMPONENTS_H_

#include <ceres/problem.h>

#include <functional>
#include <map>

namespace splinecal {

struct VarianceComponentOptions {
  int num_threads = 1;  // evaluating the residual blocks
  // A group with a smaller redundancy does not determine its variance (f_l uncertain by more
  // than sqrt(2 / 30) = 26%).
  double min_redundancy = 30.0;
};

struct VarianceComponent {
  int num_residuals = 0;     // rows (n_l unless the group's rank was given)
  double squared_sum = 0.0;  // e_l^T e_l (weighted by the current sigmas)
  double redundancy = 0.0;   // r_l = n_l - tr(H^-1 H_l)
  double factor = 1.0;       // f_l = e_l^T e_l / r_l; 1 when not identifiable
  bool identifiable = false;  // r_l >= min_redundancy
};

struct VarianceComponents {
  bool ok = false;  // false: H is not positive definite or a residual could not be evaluated
  std::map<int, VarianceComponent> groups;  // by label
};

// The group of a residual block: a label >= 0. Every residual block must get one (blocks that
// are not re-weighted get their own label: they still use up parameters).
using ResidualGroupOf = std::function<int(ceres::ResidualBlockId)>;

// Evaluates every residual block of `problem` once at its current values. group_ranks: groups
// whose residual rows are linearly dependent -- a prior written per overlapping segment, like
// the bias random walk (9 rows per segment, rank 3 per control point but one) -- count as that
// many independent residuals, n_l = rank, in r_l (the weighted sum of squares is the same
// either way); other groups count their rows.
VarianceComponents EstimateVarianceComponents(ceres::Problem* problem,
                                              const ResidualGroupOf& group_of,
                                              const VarianceComponentOptions& options = {},
                                              const std::map<int, double>& group_ranks = {});

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_VARIANCE_COMPONENTS_H_
