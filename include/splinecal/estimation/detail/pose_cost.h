// The pose residual of `splinecal fit`: one pose T_w_m of the pose source (motion capture,
// ground truth, simulator) against the spline T_w_s(t) of the IMU, with the time offset and the
// extrinsic between them, with analytic Jacobians (their automatic-differentiation twin is the
// tests' oracle, tests/testing/autodiff_costs.h).
//
// (estimation/pose_fit.h has a segment pose cost for fitting control poses to poses; it has no time
// offset, no extrinsic and no sigma weights, hence this one.)
//
// Frames and time (docs/conventions.md "Frames and notation", "Time"): the pose source reports
// T_w_m, the pose of its body frame m; the spline represents the IMU s in the same world w, on the
// IMU's clock. The extrinsic T_m_s maps IMU-frame points into m, so T_w_m = T_w_s T_m_s^-1. A
// pose stamped t_pose on the pose source's clock was taken at IMU time t = t_pose + time_offset.
// The residual
//
//   T_pred = T_w_s(t_pose + time_offset) T_m_s^-1
//   r      = [ (p_pred - p_measured) / sigma_m ;  Log(R_measured^T R_pred) / sigma_rad ]   (6)
//
// Parameter blocks: the four control poses of the segment the residual is attached to (7 each),
// the time offset [s] (1), T_m_s (7; {px, py, pz, qx, qy, qz, qw}). Hold the last two constant
// when they are not estimated.
//
// The segment is fixed when the residual is built (from the initial time offset): a time offset
// that moves t outside that segment evaluates the same segment polynomial at u outside [0, 1]
// (smooth, exact for the parameters it depends on); `splinecal fit` re-attaches such residuals
// and solves again (docs/fit.md, "Time offset").
//
// T_w_s(t) is the pose spline's trajectory model (PoseResidualData::model,
// spline/trajectory_model.h); every formula below holds for both models, with J_T,k and xi the
// model's own.
//
// Jacobians (RIGHT perturbations, lie/se3.h). With e the right-tangent change of T_pred:
//   dr / de         = blockdiag(R_pred / sigma_m, Jr^-1(phi_r) / sigma_rad),
//                     phi_r = Log(R_m^T R_pred)
//   control pose k: e = Ad(T_m_s) J_T,k d_k     (T Exp(e_T) X = T X Exp(Ad(X^-1) e_T) with
//                                                X = T_m_s^-1; J_T,k: spline/segment_jacobians.h)
//   time offset:    e = Ad(T_m_s) xi dtau,      xi = [v_s; w_s] = vee(T^-1 dT/dt), the body twist
//   extrinsic:      e = -Ad(T_m_s) delta        (T_m_s Exp(delta): X -> Exp(-delta) X)
// and pose blocks are lifted to the ambient block exactly (estimation/detail/pose_block_jacobian.h).
#ifndef SPLINECAL_ESTIMATION_DETAIL_POSE_COST_H_
#define SPLINECAL_ESTIMATION_DETAIL_POSE_COST_H_

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <optional>

#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

struct PoseResidualData {
  int segment_index = 1;  // i: control poses i-1 .. i+2
  double dt_s = 0.0;      // pose knot spacing [s]
  // t_pose - t0 [s]: the pose's stamp on the pose source's clock relative to the spline's first
  // knot time (subtract in int64 ns first). u = (t_s + time_offset) / dt - i.
  double t_s = 0.0;
  SE3d T_w_m;               // measured pose
  double sigma_m = 1e-3;    // position std [m]
  double sigma_rad = 1e-3;  // rotation std [rad]
  // The pose spline's model.
  TrajectoryModel model = TrajectoryModel::kSE3;
  // Optional knot caches for this evaluation point (not owned).
  const SplineEvaluationCallback* shared = nullptr;
};

class PoseCostFunction : public ceres::SizedCostFunction<6, 7, 7, 7, 7, 1, 7> {
 public:
  explicit PoseCostFunction(const PoseResidualData& data) : data_(data) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

  const PoseResidualData& data() const { return data_; }

 private:
  PoseResidualData data_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_POSE_COST_H_
