// Numeric Jacobians for tests: central differences, Ridders' extrapolation, and derivatives along
// a RIGHT perturbation of a group element (splinecal's one convention, lie/se3.h).
//
// Usage (test-only, header-only; include as "testing/numeric_diff.h"):
//
//   // f: R^n -> R^m, any callable taking a vector and returning an Eigen vector. It may take
//   // `const Eigen::VectorXd&` or a fixed size (`const Eigen::Vector3d&`): the VectorXd argument
//   // converts implicitly. Fixed-size results assign to a fixed-size matrix.
//   const Eigen::Matrix3d J_num = testing::CentralDifferenceJacobian(
//       [&](const Eigen::Vector3d& v) -> Eigen::Vector3d { return R * v; }, v0);
//
//   // More accurate (typically 1e-12 relative for smooth f), about 10x the evaluations:
//   Eigen::VectorXd error;
//   const Eigen::MatrixXd J_r = testing::RiddersJacobian(f, x0, {}, &error);
//
//   // d f(T Exp(d)) / d d at d = 0 (T an SO3d or SE3d; f takes the group element):
//   const Eigen::MatrixXd J_p_T = testing::RightPerturbationJacobian(
//       [&](const SE3d& T_w_s) -> Eigen::Vector3d { return T_w_s * p_s; }, T_w_s);
//
//   // A group-valued function g (e.g. a spline pose): differentiate its right-tangent change
//   //   Log(g(x0)^-1 g(x))   (central differences of this are O(h^2) accurate)
//   const SE3d g0 = g(x0);
//   const Eigen::MatrixXd J_g_x = testing::CentralDifferenceJacobian(
//       [&](const Eigen::VectorXd& x) { return RightMinus(g(x), g0); }, x0);
//
// Step sizes are absolute (in the units of x). Choose them for the scale of your inputs.
#ifndef SPLINECAL_TESTS_TESTING_NUMERIC_DIFF_H_
#define SPLINECAL_TESTS_TESTING_NUMERIC_DIFF_H_

#include <glog/logging.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace splinecal {
namespace testing {

// Default central-difference step: the truncation error h^2/6 |f'''| and the rounding error
// eps |f| / h balance near h = cbrt(eps) ~ 6e-6 for |f|, |f'''| ~ 1; 1e-5 gives about 1e-10
// absolute error on O(1) functions. Tests comparing against it should allow ~1e-8.
inline constexpr double kDefaultCentralDifferenceStep = 1e-5;

// Central differences with a custom difference of outputs: column j =
// minus(f(x + h e_j), f(x - h e_j)) / (2h), for outputs that are not vectors (a pose: pass
// minus = [](const SE3d& a, const SE3d& b) { return RightMinus(a, b); }).
template <typename F, typename Minus>
Eigen::MatrixXd CentralDifferenceJacobianWithMinus(const F& f,
                                                   const Minus& minus,
                                                   const Eigen::VectorXd& x,
                                                   double step = kDefaultCentralDifferenceStep) {
  CHECK_GT(step, 0.0);
  Eigen::MatrixXd jacobian;
  for (int j = 0; j < x.size(); ++j) {
    Eigen::VectorXd x_plus = x;
    Eigen::VectorXd x_minus = x;
    x_plus(j) += step;
    x_minus(j) -= step;
    const Eigen::VectorXd difference = minus(f(x_plus), f(x_minus));
    if (j == 0) jacobian.resize(difference.size(), x.size());
    jacobian.col(j) = difference / (2.0 * step);
  }
  return jacobian;
}

// Central differences: column j = (f(x + h e_j) - f(x - h e_j)) / (2h). Error O(h^2).
template <typename F>
Eigen::MatrixXd CentralDifferenceJacobian(const F& f,
                                          const Eigen::VectorXd& x,
                                          double step = kDefaultCentralDifferenceStep) {
  const auto minus = [](const Eigen::VectorXd& a, const Eigen::VectorXd& b) -> Eigen::VectorXd {
    return a - b;
  };
  return CentralDifferenceJacobianWithMinus(f, minus, x, step);
}

// a (-) b = Log(b^-1 a) for group elements (SO3d, SE3d): the right-tangent difference that
// matches the RIGHT perturbation, a = b Exp(a (-) b).
template <typename Group>
Eigen::VectorXd RightMinus(const Group& a, const Group& b) {
  return (b.inverse() * a).Log();
}

struct RiddersOptions {
  double initial_step = 1e-2;  // First (largest) step h_0, absolute.
  double shrink = 2.0;         // h_{i+1} = h_i / shrink.
  int max_iterations = 10;     // Rows of the extrapolation tableau.
};

// Ridders' method: central differences at steps h_0, h_0/s, h_0/s^2, ... extrapolated to h = 0
// by Richardson's scheme (the error of a central difference is even in h, so each level of the
// tableau removes one more power of h^2):
//   A(0, i) = central difference at h_i
//   A(k, i) = (s^(2k) A(k-1, i) - A(k-1, i-1)) / (s^(2k) - 1)
// The answer is the entry with the smallest error estimate max(|A(k,i) - A(k-1,i)|,
// |A(k,i) - A(k-1,i-1)|); the iteration stops when the diagonal starts to grow (rounding has
// taken over). Vector outputs use the max-norm of the differences. `error_estimate`, if not
// null, receives the estimate per column.
template <typename F>
Eigen::MatrixXd RiddersJacobian(const F& f,
                                const Eigen::VectorXd& x,
                                const RiddersOptions& options = RiddersOptions(),
                                Eigen::VectorXd* error_estimate = nullptr) {
  CHECK_GT(options.initial_step, 0.0);
  CHECK_GT(options.shrink, 1.0);
  CHECK_GE(options.max_iterations, 2);
  const int n = static_cast<int>(x.size());
  const int levels = options.max_iterations;
  const double s2 = options.shrink * options.shrink;
  Eigen::MatrixXd jacobian;
  if (error_estimate != nullptr) error_estimate->resize(n);

  auto central = [&](int j, double h) -> Eigen::VectorXd {
    Eigen::VectorXd x_plus = x;
    Eigen::VectorXd x_minus = x;
    x_plus(j) += h;
    x_minus(j) -= h;
    const Eigen::VectorXd f_plus = f(x_plus);
    const Eigen::VectorXd f_minus = f(x_minus);
    return (f_plus - f_minus) / (2.0 * h);
  };

  for (int j = 0; j < n; ++j) {
    // tableau[k][i]: extrapolation level k from steps up to h_i.
    std::vector<std::vector<Eigen::VectorXd>> tableau(levels, std::vector<Eigen::VectorXd>(levels));
    double h = options.initial_step;
    tableau[0][0] = central(j, h);
    Eigen::VectorXd best = tableau[0][0];
    double best_error = std::numeric_limits<double>::infinity();
    for (int i = 1; i < levels; ++i) {
      h /= options.shrink;
      tableau[0][i] = central(j, h);
      double factor = s2;
      for (int k = 1; k <= i; ++k) {
        tableau[k][i] = (factor * tableau[k - 1][i] - tableau[k - 1][i - 1]) / (factor - 1.0);
        factor *= s2;
        const double error =
            std::max((tableau[k][i] - tableau[k - 1][i]).lpNorm<Eigen::Infinity>(),
                     (tableau[k][i] - tableau[k - 1][i - 1]).lpNorm<Eigen::Infinity>());
        if (error <= best_error) {
          best_error = error;
          best = tableau[k][i];
        }
      }
      if ((tableau[i][i] - tableau[i - 1][i - 1]).lpNorm<Eigen::Infinity>() >= 2.0 * best_error) {
        break;
      }
    }
    if (j == 0) jacobian.resize(best.size(), n);
    jacobian.col(j) = best;
    if (error_estimate != nullptr) (*error_estimate)(j) = best_error;
  }
  return jacobian;
}

// d f(X Exp(d)) / d d at d = 0, by central differences, for X an SO3d or SE3d (any type with
// kDoF, Exp, operator*). f takes the group element and returns an Eigen vector.
template <typename Group, typename F>
Eigen::MatrixXd RightPerturbationJacobian(const F& f,
                                          const Group& x,
                                          double step = kDefaultCentralDifferenceStep) {
  using Tangent = typename Group::Tangent;
  return CentralDifferenceJacobian(
      [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return f(x * Group::Exp(Tangent(d))); },
      Eigen::VectorXd::Zero(Group::kDoF),
      step);
}

// The same with Ridders' extrapolation (initial step 1e-2 rad / m by default).
template <typename Group, typename F>
Eigen::MatrixXd RightPerturbationJacobianRidders(const F& f,
                                                 const Group& x,
                                                 const RiddersOptions& options = RiddersOptions(),
                                                 Eigen::VectorXd* error_estimate = nullptr) {
  using Tangent = typename Group::Tangent;
  return RiddersJacobian(
      [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return f(x * Group::Exp(Tangent(d))); },
      Eigen::VectorXd::Zero(Group::kDoF),
      options,
      error_estimate);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_NUMERIC_DIFF_H_
