// The covariance of a camera's calibrated parameters, camchain.yaml's `splinecal_covariance`
// (written by `splinecal intrinsics`, io/camchain_yaml.h; a prior for the next step).
#ifndef SPLINECAL_CAMERA_PARAMETER_COVARIANCE_H_
#define SPLINECAL_CAMERA_PARAMETER_COVARIANCE_H_

#include <Eigen/Core>
#include <string>
#include <vector>

namespace splinecal {

// parameters: the active intrinsics in the order of camchain.yaml's `intrinsics` then
// `distortion_coeffs`, by intrinsics/intrinsics_observability.h's IntrinsicName (fu fv pu pv,
// k1 k2 p1 p2, xi alpha, ...); for camera n > 0 with an estimated T_cn_cnm1 then
// T_cn_cnm1_rho_x, _rho_y, _rho_z, T_cn_cnm1_phi_x, _phi_y, _phi_z, the right perturbation
// T_cn_cnm1 * Exp([rho; phi]). matrix: in that order [px, -, m, rad]. block_seconds: the length of
// the time blocks of its cluster-robust part [s] (0: none). Cameras' cross-covariances are not
// kept.
struct ParameterCovariance {
  std::vector<std::string> parameters;
  Eigen::MatrixXd matrix;
  double block_seconds = 0.0;
};

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_PARAMETER_COVARIANCE_H_
