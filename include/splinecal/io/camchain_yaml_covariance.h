// The covariance of a camera calibration, as `splinecal intrinsics` writes it into camchain.yaml
// under each camera (an extra key that Kalibr's readers ignore), read for `splinecal calibrate`'s
// priors on the intrinsics and the camera chain (calib/calibrate.h, docs/calibrate.md):
//
//   camN:
//     ... Kalibr's keys (io/camchain_yaml.h) ...
//     splinecal_covariance:
//       parameters: [fu, fv, pu, pv, k1, k2, p1, p2]   # see below
//       matrix: [[...], ...]                           # rows and columns in that order
//       block_seconds: 2.0                             # informational (the time blocks of the
//                                                      # cluster-robust covariance)
//
// `parameters` lists the camera's active intrinsics in Kalibr's order for its model
// (camera/camchain.h, KalibrIntrinsicsOrder then KalibrDistortionOrder, the entries its model
// estimates), then, for camera n > 0 whose T_cn_cnm1 was estimated, T_cn_cnm1_rho_x,
// T_cn_cnm1_rho_y, T_cn_cnm1_rho_z, T_cn_cnm1_phi_x, T_cn_cnm1_phi_y, T_cn_cnm1_phi_z: the right
// perturbation T_cn_cnm1 * Exp([rho; phi]) (lie/se3.h). Units: px, unitless (distortion, xi,
// alpha, beta), m, rad. Names: the project's (fu fv pu pv; radtan k1 k2 p1 p2 k3; equidistant
// k1..k4; fov w; xi, alpha, beta) or the synonyms the agreed schema's example uses (fx fy cx cy
// for fu fv pu pv, r1 r2 for p1 p2), case as written here.
#ifndef SPLINECAL_IO_CAMCHAIN_YAML_COVARIANCE_H_
#define SPLINECAL_IO_CAMCHAIN_YAML_COVARIANCE_H_

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"

namespace splinecal {

// The number of T_cn_cnm1 tangent coordinates at the end of a covariance that has them.
inline constexpr int kChainTangentSize = 6;

struct CameraCovariance {
  // Indices into the intrinsics layout (camera/camera_model.h) of the first rows, in the file's
  // (Kalibr's) order.
  std::vector<int> intrinsics;
  bool has_T_cn_cnm1 = false;  // the last kChainTangentSize rows: T_cn_cnm1's [rho; phi]
  Eigen::MatrixXd matrix;      // symmetric positive definite
  double block_seconds = std::numeric_limits<double>::quiet_NaN();  // NaN when absent
};

// The names `parameters` must hold for `camera` (the project's names), intrinsics first, then
// the T_cn_cnm1 tangent when with_chain.
std::vector<std::string> CovarianceParameterNames(const Camera& camera, bool with_chain);

// One entry per camera of `camchain` (read from the same file by ReadCamchainYaml): nullopt
// where the camera has no splinecal_covariance. Throws splinecal::Error (file:line: camN/...) for
// a malformed block: names that do not match the camera's model (or T_cn_cnm1 rows for cam0 or
// for a camera without T_cn_cnm1), a matrix that is not square of that size, not symmetric, or
// not positive definite.
std::vector<std::optional<CameraCovariance>> ReadCamchainCovariances(const std::string& path,
                                                                     const Camchain& camchain);

// The YAML text of one covariance block (the map under splinecal_covariance, indented by
// `indent` spaces), for writers and tests: 17 significant digits, so that it reads back exactly.
std::string CameraCovarianceYamlText(const Camera& camera,
                                     const CameraCovariance& covariance,
                                     int indent);

}  // namespace splinecal

#endif  // SPLINECAL_IO_CAMCHAIN_YAML_COVARIANCE_H_
