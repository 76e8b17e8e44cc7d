// Consider parameters (Schmidt): parameters c held at a given value c_0 whose uncertainty Sigma_c
// is carried into the estimated ones theta instead of being re-estimated. To first order the
// estimate moves with c as theta(c) = theta(c_0) + S (c - c_0), S = d theta / d c, so
//
//   Sigma_theta = Sigma_theta|c + S Sigma_c S^T,        S = -H_tt^-1 H_tc,
//
// with H the information (Gauss-Newton J^T J) of the problem with c free and no prior on it, and
// Sigma_theta|c the covariance with c exact. S comes from the joint covariance P = H^-1 of
// [theta; c] (every nuisance parameter marginalised): by the block inverse,
// P_tc = -H_tt^-1 H_tc (H_cc - H_ct H_tt^-1 H_tc)^-1 = S P_cc, so S = P_tc P_cc^-1, the regression
// of theta on c (Maybeck, Stochastic Models, Estimation and Control I, 1979, Sec. 6.11;
// docs/calibrate.md, "Intrinsics and camera chain"). P_cc is c's covariance from this problem's
// data alone; its inverse the information the data have on c, which is why c must be determined
// by the data (target corners) for S to exist. A common scale of H (the noise model's weights)
// cancels in S.
#ifndef SPLINECAL_CALIB_CONSIDER_COVARIANCE_H_
#define SPLINECAL_CALIB_CONSIDER_COVARIANCE_H_

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <optional>

namespace splinecal {

// S = P_tc P_cc^-1 from the joint covariance `joint` of [theta; c], c its last `num_considered`
// rows. nullopt when P_cc is not positive definite.
inline std::optional<Eigen::MatrixXd> ConsiderSensitivity(const Eigen::MatrixXd& joint,
                                                          int num_considered) {
  const int n = static_cast<int>(joint.rows()) - num_considered;
  const Eigen::MatrixXd P_cc = joint.bottomRightCorner(num_considered, num_considered);
  const Eigen::LLT<Eigen::MatrixXd> llt(P_cc);
  if (llt.info() != Eigen::Success) return std::nullopt;
  // S P_cc = P_tc  <=>  P_cc S^T = P_ct (P_cc symmetric).
  return Eigen::MatrixXd(llt.solve(joint.bottomLeftCorner(num_considered, n)).transpose());
}

// Sigma_theta|c + S Sigma_c S^T.
inline Eigen::MatrixXd AddConsidered(const Eigen::MatrixXd& conditional,
                                     const Eigen::MatrixXd& S,
                                     const Eigen::MatrixXd& Sigma_c) {
  return conditional + S * Sigma_c * S.transpose();
}

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CONSIDER_COVARIANCE_H_
