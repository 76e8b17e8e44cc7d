// A global-shutter calibration frame handed to Ceres in compact form: the same cost, gradient
// and Gauss-Newton matrix as its 2 rows per target corner, in at most 6 + 6 + kNumIntrinsics + 1
// rows (7 in `splinecal calibrate`'s usual case, against ~250).
//
// Why: Ceres forms J^T J on one thread, block by block, and touches every Jacobian entry several
// times per iteration (scaling, products, validity checks); with 179k corners at 0.01 s knots
// that was the largest single cost of a calibration (docs/performance.md "Calibrate on real data at
// Kalibr's knot density").
//
// How (TargetFrameCostFunction::LinearizeGlobalShutter): the frame's Jacobian factors as
//   J = [A J_T_0 .. A J_T_3 | -A | A xi | C] = G B,   G = [A | C] (m x g),
// B = the block matrix of J_T_k, -I, xi and I (C: target pose and intrinsics columns). With the
// thin Householder QR G = Q R (backward stable, no rank decisions) and q = Q^T r:
//   r' = [q_1..g; |q_g+1..m|; 0...],   J' = [R B; 0; 0...]
//   =>  J'^T J' = B^T R^T R B = J^T J,   J'^T r' = B^T R^T q_1..g = J^T r,   |r'| = |r|,
// so the trust-region model 1/2 |J d + r|^2 and Jacobi's column scaling are those of the rows:
// Ceres takes the same steps, up to rounding. A residual-only evaluation returns [|r|; 0...].
//
// Whatever needs the rows themselves (the variance components' row counts, reprojection errors)
// reads rows(): estimation/compressed_information.cc does. Only for a line delay held at 0 (the
// line delay block constant): Evaluate fails otherwise.
#ifndef SPLINECAL_ESTIMATION_DETAIL_COMPACT_FRAME_COST_H_
#define SPLINECAL_ESTIMATION_DETAIL_COMPACT_FRAME_COST_H_

#include <ceres/cost_function.h>

#include <memory>

#include "splinecal/estimation/reprojection_cost.h"

namespace splinecal {

// A residual block that Ceres sees in another form than its rows (same cost, gradient and J^T J).
class CompactResidual {
 public:
  virtual ~CompactResidual() = default;
  virtual const ceres::CostFunction& rows() const = 0;
  // The cost function whose rows `cost` stands for: rows() of a compact one, else itself.
  static const ceres::CostFunction& RowsOf(const ceres::CostFunction& cost);
};

class CompactFrameCostFunction : public ceres::CostFunction, public CompactResidual {
 public:
  explicit CompactFrameCostFunction(std::unique_ptr<TargetFrameCostFunction> frame);

  // Whether compacting saves rows: more than 6 + 6 + kNumIntrinsics + 1 of them.
  static bool SavesRows(const TargetFrameCostFunction& frame);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const ceres::CostFunction& rows() const override { return *frame_; }

 private:
  std::unique_ptr<TargetFrameCostFunction> frame_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_COMPACT_FRAME_COST_H_
