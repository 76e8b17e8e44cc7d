// Which interpolation turns the control poses T_i (SE(3), uniform knots) into the trajectory
// T_w_s(t). Both models share the control poses, their 7-parameter Ceres blocks, SE3Manifold's
// RIGHT perturbation T Exp([rho; phi]), the knot caches and the orientation (docs/conventions.md,
// "The spline"; docs/math.md):
//
//   kSE3        the coupled cumulative cubic B-spline on SE(3) ([Lovegrove13], the conventions'
//               spline): T(t) = T_{i-1} prod_j Exp(Bt_j(u) Omega_{i+j-1}), Omega_k =
//               Log(T_{k-1}^-1 T_k). Its translation blends through the rotations.
//               spline/segment.h, spline/segment_jacobians.h.
//   kSplitSO3R3 the split spline of Kalibr and basalt ([Sommer20]): the same cumulative spline on
//               SO(3) for R(t), and the ordinary cubic B-spline of the control positions for p(t):
//               R(t) = R_{i-1} prod_j Exp(Bt_j(u) phi_{i+j-1}), phi_k = Log(R_{k-1}^T R_k),
//               p(t) = sum_j B_j(u) p_{i-1+j}. spline/split_segment.h,
//               spline/split_segment_jacobians.h.
//
// The orientation R_w_s(t), the body angular velocity and acceleration are identical in the two
// models (the rotation of Exp([rho; phi]) is Exp(phi)); the position and its derivatives differ.
// `fit` and `calibrate` use kSE3 unless told otherwise (--trajectory split); docs/conventions.md
// says why.
#ifndef SPLINECAL_SPLINE_TRAJECTORY_MODEL_H_
#define SPLINECAL_SPLINE_TRAJECTORY_MODEL_H_

#include <string_view>

namespace splinecal {

enum class TrajectoryModel {
  kSE3,         // coupled cumulative SE(3) spline (default)
  kSplitSO3R3,  // split SO(3) x R^3 spline
};

// The name files and flags use: "se3" or "split".
inline const char* TrajectoryModelName(TrajectoryModel model) {
  switch (model) {
    case TrajectoryModel::kSE3:
      return "se3";
    case TrajectoryModel::kSplitSO3R3:
      return "split";
  }
  return "se3";  // unreachable: every enumerator is handled above
}

// Parses "se3" or "split" into *model; false (and *model untouched) for anything else.
inline bool ParseTrajectoryModel(std::string_view name, TrajectoryModel* model) {
  if (name == "se3") {
    *model = TrajectoryModel::kSE3;
    return true;
  }
  if (name == "split") {
    *model = TrajectoryModel::kSplitSO3R3;
    return true;
  }
  return false;
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_TRAJECTORY_MODEL_H_
