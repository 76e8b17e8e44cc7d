// The value part of a scalar that may be a ceres::Jet, for typed tests over double and Jet that
// compare against double results.
#ifndef SPLINECAL_TESTS_TESTING_JET_VALUES_H_
#define SPLINECAL_TESTS_TESTING_JET_VALUES_H_

#include <ceres/jet.h>

#include <Eigen/Core>

namespace splinecal {
namespace testing {

inline double Value(double x) { return x; }
template <int N>
double Value(const ceres::Jet<double, N>& x) {
  return x.a;
}

// Value() of every entry.
template <typename Derived>
Eigen::MatrixXd Values(const Eigen::MatrixBase<Derived>& m) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (int r = 0; r < m.rows(); ++r) {
    for (int c = 0; c < m.cols(); ++c) out(r, c) = Value(m(r, c));
  }
  return out;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_JET_VALUES_H_
