// A scalar parameter block kept inside [lower, upper] by its Plus instead of by Ceres' parameter
// bounds (a time offset within +-max_time_offset, a line delay within [0, frame period / rows]):
//
//   Plus(x, d)  = clamp(x + d, lower, upper)     PlusJacobian = 1
//   Minus(y, x) = y - x                          MinusJacobian = 1
//
// Why not Problem::SetParameterLowerBound/UpperBound: a problem with bounds is "constrained" for
// Ceres' trust-region minimizer, which then runs a projected Armijo line search along every step
// and evaluates the Jacobian at the candidate inside it, and again when the step is accepted:
// two Jacobian evaluations per iteration instead of one (on the 72 s EuRoC calibration at
// 0.01 s knots, 28 evaluations in 14 iterations, a quarter of the solve; docs/performance.md
// "Calibrate on real data at Kalibr's knot density"). Ceres applies bounds in ParameterBlock::Plus
// by the same clamp, so a step whose line search accepts the full step (the usual case) lands on
// the same point either way. The tangent space is the real line, so covariances are of the scalar
// itself.
#ifndef SPLINECAL_ESTIMATION_INTERVAL_MANIFOLD_H_
#define SPLINECAL_ESTIMATION_INTERVAL_MANIFOLD_H_

#include <ceres/manifold.h>

#include <algorithm>

namespace splinecal {

class IntervalManifold : public ceres::Manifold {
 public:
  IntervalManifold(double lower, double upper) : lower_(lower), upper_(upper) {}

  int AmbientSize() const override { return 1; }
  int TangentSize() const override { return 1; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    *x_plus_delta = std::clamp(*x + *delta, lower_, upper_);
    return true;
  }
  bool PlusJacobian(const double* /*x*/, double* jacobian) const override {
    *jacobian = 1.0;
    return true;
  }
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    *y_minus_x = *y - *x;
    return true;
  }
  bool MinusJacobian(const double* /*x*/, double* jacobian) const override {
    *jacobian = 1.0;
    return true;
  }

  double lower() const { return lower_; }
  double upper() const { return upper_; }

 private:
  double lower_;
  double upper_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_INTERVAL_MANIFOLD_H_
