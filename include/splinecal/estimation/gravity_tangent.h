// Gravity of known magnitude as 2 degrees of freedom: a tangent basis of the sphere |g| = G and
// the retraction that moves along it [seed001].
//
// What this header implements
//   GravityTangentBasis(g)   B = [b1 b2], 3x2, orthonormal, both columns orthogonal to g, and
//                            (b1, b2, g/|g|) a right-handed frame -- for EVERY direction of g.
//   RetractGravity(g, w)     the point reached from g by walking the great circle of the sphere
//                            of radius |g| in the direction B w for an angle |w| [rad]:
//                              g (+) w = |g| (cos|w| d + sin|w| / |w| B w),   d = g / |g|
//                            d/dw (g (+) w) at w = 0 is |g| B, so a linearisation in w is
//                            g + |g| B w [seed001: g = |g| g_hat + w1 b1 + w2 b2].
//
// Why not VINS-Mono's basis: it takes b1 = normalize(e_z - d (d . e_z)) and switches to e_x only
// when d == e_z exactly. For d = -e_z (gravity straight down the z axis, the usual case in a
// z-up frame) e_z - d (d . e_z) = 0 and the basis is 0/0; near +-e_z it loses digits. Here the
// helper axis is the coordinate axis least aligned with d, so |e_i x d| >= sqrt(2/3) always: the
// basis is well conditioned everywhere (it is discontinuous where the choice of axis switches,
// which is harmless because callers rebuild it at every new estimate).
//
// References: [seed001] VINS-Mono gravity refinement notes (/work/shared/seeds/001_*.txt);
// [Sola18] for the sphere's exponential map (great-circle retraction).
#ifndef SPLINECAL_ESTIMATION_GRAVITY_TANGENT_H_
#define SPLINECAL_ESTIMATION_GRAVITY_TANGENT_H_

#include <glog/logging.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace splinecal {

namespace internal {

// Below this squared angle [rad^2] (angle < 1e-4 rad) RetractGravity uses the series
//   cos t = 1 - t^2/2 + t^4/24,   sin t / t = 1 - t^2/6 + t^4/120
// whose first dropped terms are O(t^6) <= 1e-24: far below double precision.
inline constexpr double kGravityRetractSmallAngleSq = 1e-8;

}  // namespace internal

// Orthonormal basis [b1 b2] of the plane orthogonal to g (any nonzero 3-vector; its norm does
// not matter). (b1, b2, g / |g|) is right-handed: b1 x b2 = g / |g|. CHECKs that g is finite
// and nonzero (a caller's bug: every gravity estimate is).
inline Eigen::Matrix<double, 3, 2> GravityTangentBasis(const Eigen::Vector3d& g) {
  const double norm = g.norm();
  CHECK(std::isfinite(norm) && norm > 0.0) << "GravityTangentBasis needs a nonzero finite vector";
  const Eigen::Vector3d d = g / norm;
  // The coordinate axis least aligned with d: |d_i| <= 1/sqrt(3), so |e_i x d| >= sqrt(2/3).
  int axis = 0;
  d.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
  const Eigen::Vector3d b1 = e.cross(d).normalized();
  const Eigen::Vector3d b2 = d.cross(b1);  // unit: d and b1 are orthonormal
  Eigen::Matrix<double, 3, 2> basis;
  basis.col(0) = b1;
  basis.col(1) = b2;
  return basis;
}

// g (+) w: moves g on its sphere by the angle |w| [rad] along B w, B = GravityTangentBasis(g).
// Keeps |g| (renormalised against rounding drift).
inline Eigen::Vector3d RetractGravity(const Eigen::Vector3d& g, const Eigen::Vector2d& w) {
  const double norm = g.norm();
  const Eigen::Vector3d d = g / norm;
  const Eigen::Vector3d step = GravityTangentBasis(g) * w;  // |step| = |w|
  const double theta_sq = w.squaredNorm();
  double cos_theta;
  double sinc_theta;  // sin(t) / t
  if (theta_sq < internal::kGravityRetractSmallAngleSq) {
    cos_theta = 1.0 - theta_sq / 2.0 + theta_sq * theta_sq / 24.0;
    sinc_theta = 1.0 - theta_sq / 6.0 + theta_sq * theta_sq / 120.0;
  } else {
    const double theta = std::sqrt(theta_sq);
    cos_theta = std::cos(theta);
    sinc_theta = std::sin(theta) / theta;
  }
  const Eigen::Vector3d moved = cos_theta * d + sinc_theta * step;
  return norm * moved.normalized();
}

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_GRAVITY_TANGENT_H_
