// The projection stage of every camera model of camera/camera_model.h: a point p = (x, y, z) in
// the camera frame goes to the normalised image point (before distortion)
//
//   m = (x, y) / den(p)
//
// Every projection splinecal supports has this form [Usenko18]; params = (m0, m1), entries 4 and
// 5 of the intrinsics vector. Points on one ray through the camera centre share m (den is
// homogeneous of degree 1), so d m / d p . p = 0.
//
//   model    params         den(p)                                     valid region Omega
//   pinhole  (0, 0)         z                                          z > kPinholeMinDepth
//   omni     (xi, 0)        z + xi d,  d = |p|                         z > -w d,  w = xi for
//            Mei's unified model [Mei07] (Kalibr's `omni`)             xi <= 1, 1/xi for xi > 1
//   eucm     (alpha, beta)  alpha rho + (1 - alpha) z,                 z > -w(alpha) rho
//            rho = sqrt(beta (x^2 + y^2) + z^2)  [Khomutenko16]
//   ds       (xi, alpha)    alpha d2 + (1 - alpha) s,  s = xi d1 + z,   z > -w2 d1,
//            d1 = |p|,  d2 = sqrt(x^2 + y^2 + s^2)  [Usenko18]          w2 = (w1 + xi) /
//                                                                      sqrt(2 w1 xi + xi^2 + 1),
//                                                                      w1 = w(alpha)
//   w(alpha) = alpha / (1 - alpha) for alpha <= 1/2, (1 - alpha) / alpha for alpha > 1/2.
// and den > 0 in every case. The regions are [Usenko18]'s (its unified model with alpha =
// xi / (1 + xi) is Mei's with xi; its w becomes xi or 1/xi). Beyond them a model still returns
// numbers, but they fold back onto pixels of points inside (or divide by zero at the border).
//
// Jacobians (ProjectToPlane), with g_p = d den / d p (3) and g_params = d den / d params (2):
//   d m / d p      = ([I_2 | 0] - m g_p^T) / den
//   d m / d params = -m g_params^T / den
//   pinhole  g_p = e_z,                            g_params = (0, 0)
//   omni     g_p = e_z + xi p / d,                 g_params = (d, 0)
//   eucm     g_p = alpha (beta x, beta y, z) / rho + (1 - alpha) e_z,
//            g_params = (rho - z, alpha (x^2 + y^2) / (2 rho))
//   ds       g_s = xi p / d1 + e_z,  g_d2 = ((x, y, 0) + s g_s) / d2,
//            g_p = alpha g_d2 + (1 - alpha) g_s,
//            g_params = (alpha s d1 / d2 + (1 - alpha) d1,  d2 - s)
//
// Lifting (LiftToBearing): the unit bearing b with m = (b_x, b_y) / den(b), r^2 = |m|^2:
//   pinhole  b ~ (m_x, m_y, 1)
//   omni     eta = (xi + sqrt(1 + (1 - xi^2) r^2)) / (1 + r^2),  b = (eta m_x, eta m_y, eta - xi)
//            [Mei07]; needs 1 + (1 - xi^2) r^2 >= 0
//   eucm     m_z = (1 - beta alpha^2 r^2) / (alpha sqrt(1 - (2 alpha - 1) beta r^2) + 1 - alpha),
//            b ~ (m_x, m_y, m_z) [Usenko18]; needs (2 alpha - 1) beta r^2 <= 1
//   ds       m_z = (1 - alpha^2 r^2) / (alpha sqrt(1 - (2 alpha - 1) r^2) + 1 - alpha),
//            eta = (m_z xi + sqrt(m_z^2 + (1 - xi^2) r^2)) / (m_z^2 + r^2),
//            b ~ eta (m_x, m_y, m_z) - (0, 0, xi) [Usenko18]; needs (2 alpha - 1) r^2 <= 1
// All three are closed forms, valid beyond 90 degrees off the axis (b_z < 0).
//
// References (docs/references.md): [Mei07] C. Mei, P. Rives, "Single View Point Omnidirectional
// Camera Calibration from Planar Grids", ICRA 2007; [Khomutenko16] B. Khomutenko, G. Garcia,
// P. Martinet, "An Enhanced Unified Camera Model", IEEE RA-L 2016; [Usenko18] V. Usenko,
// N. Demmel, D. Cremers, "The Double Sphere Camera Model", 3DV 2018 (arXiv:1807.08957): its
// review of the unified, extended unified and double sphere models gives each projection,
// unprojection and valid region in the form used here.
#ifndef SPLINECAL_CAMERA_PROJECTION_H_
#define SPLINECAL_CAMERA_PROJECTION_H_

#include <Eigen/Core>
#include <cmath>

namespace splinecal {

// Kalibr's camera models (docs/conventions.md, "Camera models").
enum class ProjectionModel { kPinhole, kOmni, kEucm, kDoubleSphere };

inline constexpr int kNumProjectionParams = 2;  // m0, m1 of the intrinsics vector

namespace internal {

// Points closer to the pinhole camera's plane than this [m] do not project (z <= it).
inline constexpr double kPinholeMinDepth = 1e-6;

// w(alpha) of the unified and extended unified models' valid region (file comment).
template <typename T>
T UnifiedW(const T& alpha) {
  return alpha <= T(0.5) ? alpha / (T(1.0) - alpha) : (T(1.0) - alpha) / alpha;
}

// den(p) of the file comment for any scalar (double or ceres::Jet); false (den untouched) outside
// the model's valid region. params points at (m0, m1).
template <typename T>
bool ProjectionDenominator(ProjectionModel model,
                           const T* params,
                           const Eigen::Matrix<T, 3, 1>& p,
                           T* den) {
  using std::sqrt;
  const T& x = p.x();
  const T& y = p.y();
  const T& z = p.z();
  T value;
  switch (model) {
    case ProjectionModel::kPinhole:
      if (!(z > T(kPinholeMinDepth))) return false;
      *den = z;
      return true;
    case ProjectionModel::kOmni: {
      const T& xi = params[0];
      const T d2 = x * x + y * y + z * z;
      if (!(d2 > T(0.0))) return false;
      const T d = sqrt(d2);
      const T w = xi <= T(1.0) ? xi : T(1.0) / xi;
      if (!(z > -w * d)) return false;
      value = z + xi * d;
      break;
    }
    case ProjectionModel::kEucm: {
      const T& alpha = params[0];
      const T& beta = params[1];
      const T rho2 = beta * (x * x + y * y) + z * z;
      if (!(rho2 > T(0.0))) return false;
      const T rho = sqrt(rho2);
      if (!(z > -UnifiedW(alpha) * rho)) return false;
      value = alpha * rho + (T(1.0) - alpha) * z;
      break;
    }
    case ProjectionModel::kDoubleSphere: {
      const T& xi = params[0];
      const T& alpha = params[1];
      const T d1_sq = x * x + y * y + z * z;
      if (!(d1_sq > T(0.0))) return false;
      const T d1 = sqrt(d1_sq);
      const T w1 = UnifiedW(alpha);
      const T w2_sq_denominator = T(2.0) * w1 * xi + xi * xi + T(1.0);
      if (!(w2_sq_denominator > T(0.0))) return false;
      const T w2 = (w1 + xi) / sqrt(w2_sq_denominator);
      if (!(z > -w2 * d1)) return false;
      const T s = xi * d1 + z;
      const T d2 = sqrt(x * x + y * y + s * s);
      value = alpha * d2 + (T(1.0) - alpha) * s;
      break;
    }
    default:
      return false;
  }
  if (!(value > T(0.0))) return false;
  *den = value;
  return true;
}

// m = (x, y) / den(p) and its Jacobians (file comment): J_m_p (2x3), J_m_params (2x2). Outputs
// optional (nullptr). False (outputs untouched) outside the valid region.
bool ProjectToPlane(ProjectionModel model,
                    const Eigen::Vector2d& params,
                    const Eigen::Vector3d& p,
                    Eigen::Vector2d* m,
                    Eigen::Matrix<double, 2, 3>* J_m_p,
                    Eigen::Matrix2d* J_m_params);

// The unit bearing whose normalised image point is m (file comment); false where m is outside
// the image of the valid region. The caller checks the result by projecting it again.
bool LiftToBearing(ProjectionModel model,
                   const Eigen::Vector2d& params,
                   const Eigen::Vector2d& m,
                   Eigen::Vector3d* bearing);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_PROJECTION_H_
