#include "splinecal/estimation/detail/pose_cost.h"

#include "splinecal/lie/so3.h"

namespace splinecal {

bool PoseCostFunction::Evaluate(double const* const* parameters,
                                double* residuals,
                                double** jacobians) const {
  const bool pose_jacobians =
      jacobians != nullptr && (jacobians[0] != nullptr || jacobians[1] != nullptr ||
                               jacobians[2] != nullptr || jacobians[3] != nullptr);
  std::optional<SegmentKnotData<double>> local;
  const SegmentKnots<double> knots = internal::SegmentKnotsFor(
      data_.shared, data_.segment_index - 1, parameters, pose_jacobians, &local);
  const double time_offset = parameters[4][0];
  const double u =
      (data_.t_s + time_offset) / data_.dt_s - static_cast<double>(data_.segment_index);
  const Segment<double> segment = MakeSegment(data_.segment_index, u, data_.dt_s);

  SE3d T_w_s;
  ControlPoseJacobian<6> J_T_ctrl;
  EvaluatePoseJacobian(data_.model, knots, segment, &T_w_s, pose_jacobians ? &J_T_ctrl : nullptr);
  const SE3d T_m_s = PoseFromBlock(parameters[5]);
  const SE3d T_pred = T_w_s * T_m_s.inverse();
  const Eigen::Vector3d dp = T_pred.translation() - data_.T_w_m.translation();
  const Eigen::Vector3d phi = (data_.T_w_m.so3().inverse() * T_pred.so3()).Log();
  Eigen::Map<Vector6d> r(residuals);
  r.head<3>() = dp / data_.sigma_m;
  r.tail<3>() = phi / data_.sigma_rad;
  if (jacobians == nullptr) return true;

  // dr/de * Ad(T_m_s): the map from a right-tangent change of T_w_s to the residual.
  Matrix6d dr_de = Matrix6d::Zero();
  dr_de.topLeftCorner<3, 3>() = T_pred.rotationMatrix() / data_.sigma_m;
  dr_de.bottomRightCorner<3, 3>() = RightJacobianInverseSO3(phi) / data_.sigma_rad;
  const Matrix6d dr_deT = dr_de * T_m_s.Adj();

  for (int k = 0; k < kSplineOrder; ++k) {
    if (jacobians[k] == nullptr) continue;
    const Matrix6d J = dr_deT * J_T_ctrl.blocks[k];
    internal::LiftPoseJacobian(J, internal::MakePoseBlockLift(parameters[k]), jacobians[k]);
  }
  if (jacobians[4] != nullptr) {
    // d T_w_s / dt = T_w_s Hat(xi), xi = [v_s; w_s] (body twist).
    Eigen::Vector3d w_s;
    Eigen::Vector3d v_w;
    EvaluateSegment(data_.model, knots, segment, nullptr, &w_s, nullptr, &v_w, nullptr);
    Vector6d xi;
    xi.head<3>() = T_w_s.so3().inverse() * v_w;
    xi.tail<3>() = w_s;
    Eigen::Map<Vector6d> J_offset(jacobians[4]);
    J_offset = dr_deT * xi;
  }
  if (jacobians[5] != nullptr) {
    const Matrix6d J = -dr_deT;
    internal::LiftPoseJacobian(J, internal::MakePoseBlockLift(parameters[5]), jacobians[5]);
  }
  return true;
}

}  // namespace splinecal
