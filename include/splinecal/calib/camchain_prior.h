// The prior of `splinecal calibrate` on a camera's intrinsics and on the camera chain's
// T_cn_cnm1 (CalibrateOptions::intrinsics / camera_chain = kPrior; docs/calibrate.md): the
// camchain's calibration (`splinecal intrinsics`) as a Gaussian measurement,
//
//   r = L^-1 (x - x_0),   Sigma = L L^T (the camchain's covariance, io/camchain_yaml_covariance.h)
//   x - x_0 = [theta_j - theta_0,j  for the intrinsics entries j in the covariance's order;
//              Log(T_0^-1 T_cn_imu T_cnm1_imu^-1)]                  (T_0 the camchain's T_cn_cnm1)
//
// so |r|^2 = (x - x_0)^T Sigma^-1 (x - x_0). The chain's tangent is the right perturbation
// T_cn_cnm1 = T_0 Exp([rho; phi]) (lie/se3.h), as the covariance's rows are. With
// E = T_0^-1 T_cn_imu T_cnm1_imu^-1 and xi = Log(E):
//   T_cn_imu Exp(a):    E Exp(Adj(T_cnm1_imu) a)    ->  d xi / d a =  Jr^-1(xi) Adj(T_cnm1_imu)
//   T_cnm1_imu Exp(b):  E Exp(-Adj(T_cnm1_imu) b)   ->  d xi / d b = -Jr^-1(xi) Adj(T_cnm1_imu)
// (Exp(-b) T^-1 = T^-1 Exp(-Adj(T) b)), lifted to the ambient pose blocks exactly
// (estimation/detail/pose_block_jacobian.h); the intrinsics' Jacobian is L^-1 on their columns.
#ifndef SPLINECAL_CALIB_CAMCHAIN_PRIOR_H_
#define SPLINECAL_CALIB_CAMCHAIN_PRIOR_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

// Parameter blocks: the camera's intrinsics (kNumIntrinsics, camera/camera_model.h) when
// `intrinsics` is not empty; then T_cn_imu and T_cnm1_imu (7 each, {p, q}) when T_cn_cnm1 is
// given. `covariance` is over [the intrinsics entries in `intrinsics`' order; T_cn_cnm1's
// tangent], symmetric positive definite.
class CamchainPriorCostFunction : public ceres::CostFunction {
 public:
  CamchainPriorCostFunction(std::vector<int> intrinsics,
                            const IntrinsicsVector& reference,
                            std::optional<SE3d> T_cn_cnm1,
                            const Eigen::MatrixXd& covariance);
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  std::vector<int> intrinsics_;
  IntrinsicsVector reference_;
  std::optional<SE3d> T_cn_cnm1_;
  Eigen::MatrixXd whitening_;  // L^-1
};

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CAMCHAIN_PRIOR_H_
