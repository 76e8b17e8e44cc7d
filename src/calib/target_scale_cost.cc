#include "splinecal/calib/detail/target_scale_cost.h"

#include <Eigen/Core>
#include <array>
#include <utility>
#include <vector>

namespace splinecal {

namespace {
constexpr int kPose = 7;  // {px, py, pz, qx, qy, qz, qw}
}  // namespace

TargetScaleCostFunction::TargetScaleCostFunction(std::unique_ptr<ceres::CostFunction> frame,
                                                 int num_poses)
    : owned_(std::move(frame)), frame_(owned_.get()), num_poses_(num_poses) {
  Init();
  if (const auto* compact = dynamic_cast<const CompactResidual*>(frame_)) {
    rows_.reset(new TargetScaleCostFunction(&compact->rows(), num_poses));
  }
}

TargetScaleCostFunction::TargetScaleCostFunction(const ceres::CostFunction* frame, int num_poses)
    : frame_(frame), num_poses_(num_poses) {
  Init();
}

void TargetScaleCostFunction::Init() {
  *mutable_parameter_block_sizes() = frame_->parameter_block_sizes();
  mutable_parameter_block_sizes()->push_back(1);
  set_num_residuals(frame_->num_residuals());
  // Control poses, T_cam_imu (num_poses), T_w_t (num_poses + 3).
  for (int i = 0; i <= num_poses_; ++i) pose_blocks_.push_back(i);
  pose_blocks_.push_back(num_poses_ + 3);
}

bool TargetScaleCostFunction::Evaluate(double const* const* parameters,
                                       double* residuals,
                                       double** jacobians) const {
  const int num_blocks = static_cast<int>(frame_->parameter_block_sizes().size());
  const double s = parameters[num_blocks][0];
  if (!(s > 0.0)) return false;
  std::vector<const double*> inner(parameters, parameters + num_blocks);
  std::vector<std::array<double, kPose>> scaled(pose_blocks_.size());
  for (size_t k = 0; k < pose_blocks_.size(); ++k) {
    const double* block = parameters[pose_blocks_[k]];
    for (int i = 0; i < kPose; ++i) scaled[k][i] = i < 3 ? block[i] / s : block[i];
    inner[pose_blocks_[k]] = scaled[k].data();
  }
  if (jacobians == nullptr) return frame_->Evaluate(inner.data(), residuals, nullptr);
  const int rows = num_residuals();
  const bool with_scale = jacobians[num_blocks] != nullptr;
  std::vector<double*> inner_jacobians(jacobians, jacobians + num_blocks);
  // d r / d s needs every pose block's Jacobian, also of blocks Ceres holds constant.
  std::vector<std::vector<double>> scratch(pose_blocks_.size());
  if (with_scale) {
    for (size_t k = 0; k < pose_blocks_.size(); ++k) {
      // A block at the origin (calibrate's T_w_t) adds nothing to d r / d s.
      const bool at_origin = scaled[k][0] == 0.0 && scaled[k][1] == 0.0 && scaled[k][2] == 0.0;
      if (inner_jacobians[pose_blocks_[k]] != nullptr || at_origin) continue;
      scratch[k].resize(static_cast<size_t>(rows) * kPose);
      inner_jacobians[pose_blocks_[k]] = scratch[k].data();
    }
  }
  if (!frame_->Evaluate(inner.data(), residuals, inner_jacobians.data())) return false;
  using RowMajorPose = Eigen::Matrix<double, Eigen::Dynamic, kPose, Eigen::RowMajor>;
  Eigen::VectorXd d_s = Eigen::VectorXd::Zero(rows);
  for (size_t k = 0; k < pose_blocks_.size(); ++k) {
    if (inner_jacobians[pose_blocks_[k]] == nullptr) continue;
    Eigen::Map<RowMajorPose> J(inner_jacobians[pose_blocks_[k]], rows, kPose);
    const Eigen::Map<const Eigen::Vector3d> t_scaled(scaled[k].data());
    if (with_scale) d_s -= J.leftCols<3>() * t_scaled / s;
    if (jacobians[pose_blocks_[k]] != nullptr) J.leftCols<3>() /= s;
  }
  if (with_scale) Eigen::Map<Eigen::VectorXd>(jacobians[num_blocks], rows) = d_s;
  return true;
}

}  // namespace splinecal
