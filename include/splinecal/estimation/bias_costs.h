// IMU biases in `splinecal fit`: constant, or a uniform cubic B-spline in R^3 with a random-walk
// prior weighted by Kalibr's random-walk density ([Kalibr], docs/conventions.md "IMU model").
//
// Bias spline. Control points c_m in R^3 at bias knot times tb_m = tb_0 + m db (db: the bias
// knot spacing). For t in [tb_m, tb_{m+1}), u = (t - tb_m) / db,
//
//   b(t) = sum_{j=0..3} B_j(u) c_{m-1+j},     B_j = Bt_j - Bt_{j+1}   (Bt_4 = 0)
//
// with Bt the cumulative basis of spline/basis.h (so B_0 = (1-u)^3/6, B_1 = (3u^3 - 6u^2 + 4)/6,
// B_2 = (-3u^3 + 3u^2 + 3u + 1)/6, B_3 = u^3/6): the ordinary (non-cumulative) uniform cubic
// B-spline, linear in its control points.
//
// Random-walk prior. A bias that is a Wiener process with density sigma_rw [unit/s/sqrt(Hz) =
// unit/sqrt(s)] has the path log-likelihood -1/(2 sigma_rw^2) int |db/dt|^2 dt; restricted to the
// spline, per bias segment ([Kalibr]: the same integral of the squared derivative),
//
//   1/2 |r|^2 = 1/(2 sigma_rw^2) int_seg |db/dt|^2 dt = 1/(2 sigma_rw^2 db) c^T (M (x) I3) c,
//   M_jk = int_0^1 B_j'(u) B_k'(u) du      (4x4, positive semi-definite, rank 3: a constant bias
//                                           costs nothing, sum_j B_j' = 0)
//
// With M = S^T S (S 3x4 from the eigen-decomposition, the zero eigenvalue dropped), the residual
// of one segment is r = (S (x) I3) c / (sigma_rw sqrt(db)), 9 rows: r[3 m + a] = sum_j S(m, j)
// c_j[a] / (sigma_rw sqrt(db)). It is linear in the control points, so its Jacobian is constant.
// Summed over the segments of the spline it is the whole integral (adjacent segments share
// control points, not integration intervals).
#ifndef SPLINECAL_ESTIMATION_BIAS_COSTS_H_
#define SPLINECAL_ESTIMATION_BIAS_COSTS_H_

#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <array>
#include <cmath>

#include "splinecal/spline/basis.h"

namespace splinecal {

enum class BiasModel {
  kConstant,  // one 3-vector per sensor for the whole recording
  kSpline,    // a cubic B-spline in time with a random-walk prior
};

// The weights B_0..B_3 of the four control points of a bias segment at u (any scalar type).
template <typename T>
std::array<T, 4> BiasSplineWeights(const T& u) {
  const Eigen::Matrix<T, kSplineOrder, 1> bt = CumulativeBasis<0>(u);
  return {bt[0] - bt[1], bt[1] - bt[2], bt[2] - bt[3], bt[3]};
}

// S (3x4) with S^T S = M = int_0^1 B'(u) B'(u)^T du (file comment). M is integrated exactly by
// 3-point Gauss-Legendre quadrature (B' has degree 2, the products degree 4 <= 2*3 - 1).
Eigen::Matrix<double, 3, 4> BiasRandomWalkSqrtInformation();

// The random-walk prior of one bias segment: residual 9 = (S (x) I3) [c0; c1; c2; c3] / (sigma_rw
// sqrt(db)), parameter blocks the segment's four control points (3 each).
class BiasRandomWalkCostFunction : public ceres::SizedCostFunction<9, 3, 3, 3, 3> {
 public:
  // knot_spacing_s: db [s] (> 0); random_walk_density: sigma_rw [unit/s/sqrt(Hz)] (> 0), e.g.
  // ImuNoise::gyroscope_random_walk. CHECKs both (the caller validated the user's values).
  BiasRandomWalkCostFunction(double knot_spacing_s, double random_walk_density);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  // The constant 9x12 Jacobian [S (x) I3] / (sigma_rw sqrt(db)).
  const Eigen::Matrix<double, 9, 12>& jacobian() const { return jacobian_; }

 private:
  Eigen::Matrix<double, 9, 12> jacobian_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_BIAS_COSTS_H_
