#include "splinecal/camera/camera_model.h"

#include <Eigen/LU>
#include <cmath>

#include "splinecal/units.h"

namespace splinecal {

namespace {

// Newton's method for the unprojection stops when the residual of D(x) = x_d is below this
// (normalised image units; 1e-14 is ~1e-11 px at a focal length of 1000 px, far under any
// detector's precision, and a few ulps above the rounding floor of D near |x| ~ 1).
constexpr double kUnprojectTolerance = 1e-14;
// An unprojection whose residual stays above this after the iterations did not converge
// (normalised units; ~1e-6 px at fu = 1000 px).
constexpr double kUnprojectAcceptance = 1e-9;
constexpr int kMaxUnprojectIterations = 30;

}  // namespace

std::string DistortionModelName(DistortionModel model) {
  switch (model) {
    case DistortionModel::kNone:
      return "none";
    case DistortionModel::kRadTan:
      return "radtan";
    case DistortionModel::kEquidistant:
      return "equidistant";
  }
  return "none";
}

IntrinsicsVector PinholeCamera::intrinsics() const {
  IntrinsicsVector v;
  v << fu, fv, pu, pv, distortion_coeffs;
  return v;
}

void PinholeCamera::set_intrinsics(const IntrinsicsVector& intrinsics) {
  fu = intrinsics(0);
  fv = intrinsics(1);
  pu = intrinsics(2);
  pv = intrinsics(3);
  distortion_coeffs = intrinsics.tail<4>();
}

namespace internal {

void DistortWithJacobians(DistortionModel model,
                          const Eigen::Vector4d& k,
                          double x,
                          double y,
                          Eigen::Vector2d* d,
                          Eigen::Matrix2d* J_d_xy,
                          Eigen::Matrix<double, 2, 4>* J_d_k) {
  const double r2 = x * x + y * y;
  switch (model) {
    case DistortionModel::kNone:
      if (d != nullptr) *d = Eigen::Vector2d(x, y);
      if (J_d_xy != nullptr) J_d_xy->setIdentity();
      if (J_d_k != nullptr) J_d_k->setZero();
      return;
    case DistortionModel::kRadTan: {
      const double k1 = k(0), k2 = k(1), p1 = k(2), p2 = k(3);
      const double radial = 1.0 + k1 * r2 + k2 * r2 * r2;
      if (d != nullptr) {
        *d = Eigen::Vector2d(x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                             y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
      }
      if (J_d_xy != nullptr) {
        // d radial / dx = (2 k1 + 4 k2 r^2) x, the same with y.
        const double g = 2.0 * k1 + 4.0 * k2 * r2;
        (*J_d_xy)(0, 0) = radial + g * x * x + 2.0 * p1 * y + 6.0 * p2 * x;
        (*J_d_xy)(0, 1) = g * x * y + 2.0 * p1 * x + 2.0 * p2 * y;
        (*J_d_xy)(1, 0) = g * x * y + 2.0 * p1 * x + 2.0 * p2 * y;
        (*J_d_xy)(1, 1) = radial + g * y * y + 6.0 * p1 * y + 2.0 * p2 * x;
      }
      if (J_d_k != nullptr) {
        (*J_d_k) << x * r2, x * r2 * r2, 2.0 * x * y, r2 + 2.0 * x * x,  //
            y * r2, y * r2 * r2, r2 + 2.0 * y * y, 2.0 * x * y;
      }
      return;
    }
    case DistortionModel::kEquidistant: {
      double s;                             // theta_d / r
      double ds_dr_over_r;                  // (ds/dr) / r
      Eigen::Vector4d theta_powers_over_r;  // theta^(2i+1) / r, i = 1..4
      if (r2 < kEquidistantSeriesRSq) {
        // Series (header comment); theta ~ r to first order in the coefficient Jacobian.
        s = 1.0 + (k(0) - 1.0 / 3.0) * r2;
        ds_dr_over_r = 2.0 * (k(0) - 1.0 / 3.0);
        theta_powers_over_r << r2, r2 * r2, r2 * r2 * r2, r2 * r2 * r2 * r2;
      } else {
        const double r = std::sqrt(r2);
        const double theta = std::atan(r);
        const double t2 = theta * theta;
        const double poly = 1.0 + t2 * (k(0) + t2 * (k(1) + t2 * (k(2) + t2 * k(3))));
        const double theta_d = theta * poly;
        // d theta_d / d theta = 1 + 3 k1 t^2 + 5 k2 t^4 + 7 k3 t^6 + 9 k4 t^8; dtheta/dr =
        // 1/(1+r^2).
        const double dpoly =
            1.0 + t2 * (3.0 * k(0) + t2 * (5.0 * k(1) + t2 * (7.0 * k(2) + t2 * 9.0 * k(3))));
        const double dtheta_d_dr = dpoly / (1.0 + r2);
        s = theta_d / r;
        // (theta_d' r - theta_d) / r^3: cancels for small r, but it is multiplied by x x^T
        // (|.| <= r^2) below, so the absolute error of the Jacobian stays ~eps.
        ds_dr_over_r = (dtheta_d_dr * r - theta_d) / (r2 * r);
        const double theta_over_r = theta / r;
        theta_powers_over_r << theta_over_r * t2, theta_over_r * t2 * t2,
            theta_over_r * t2 * t2 * t2, theta_over_r * t2 * t2 * t2 * t2;
      }
      if (d != nullptr) *d = Eigen::Vector2d(s * x, s * y);
      if (J_d_xy != nullptr) {
        const Eigen::Vector2d p(x, y);
        *J_d_xy = s * Eigen::Matrix2d::Identity() + ds_dr_over_r * p * p.transpose();
      }
      if (J_d_k != nullptr) {
        J_d_k->row(0) = x * theta_powers_over_r.transpose();
        J_d_k->row(1) = y * theta_powers_over_r.transpose();
      }
      return;
    }
  }
}

}  // namespace internal

bool PinholeCamera::Project(const Eigen::Vector3d& p_c,
                            Eigen::Vector2d* uv,
                            Eigen::Matrix<double, 2, 3>* J_uv_p,
                            Eigen::Matrix<double, 2, kNumIntrinsics>* J_uv_intrinsics) const {
  if (!(p_c.z() > kMinDepth)) return false;
  const double inv_z = 1.0 / p_c.z();
  const double x = p_c.x() * inv_z;
  const double y = p_c.y() * inv_z;
  Eigen::Vector2d d;
  Eigen::Matrix2d J_d_xy;
  Eigen::Matrix<double, 2, 4> J_d_k;
  internal::DistortWithJacobians(distortion,
                                 distortion_coeffs,
                                 x,
                                 y,
                                 &d,
                                 J_uv_p != nullptr ? &J_d_xy : nullptr,
                                 J_uv_intrinsics != nullptr ? &J_d_k : nullptr);
  if (uv != nullptr) *uv = Eigen::Vector2d(fu * d.x() + pu, fv * d.y() + pv);
  if (J_uv_p != nullptr) {
    // d(x, y)/d p_c = [[1/Z, 0, -x/Z], [0, 1/Z, -y/Z]].
    Eigen::Matrix<double, 2, 3> J_xy_p;
    J_xy_p << inv_z, 0.0, -x * inv_z, 0.0, inv_z, -y * inv_z;
    Eigen::Matrix2d F = J_d_xy;
    F.row(0) *= fu;
    F.row(1) *= fv;
    *J_uv_p = F * J_xy_p;
  }
  if (J_uv_intrinsics != nullptr) {
    J_uv_intrinsics->setZero();
    (*J_uv_intrinsics)(0, 0) = d.x();
    (*J_uv_intrinsics)(1, 1) = d.y();
    (*J_uv_intrinsics)(0, 2) = 1.0;
    (*J_uv_intrinsics)(1, 3) = 1.0;
    J_uv_intrinsics->block<1, 4>(0, 4) = fu * J_d_k.row(0);
    J_uv_intrinsics->block<1, 4>(1, 4) = fv * J_d_k.row(1);
  }
  return true;
}

bool PinholeCamera::IsDistortionMonotonic(double x, double y) const {
  Eigen::Matrix2d J;
  internal::DistortWithJacobians(distortion, distortion_coeffs, x, y, nullptr, &J, nullptr);
  return J.determinant() > 0.0;
}

bool PinholeCamera::Unproject(const Eigen::Vector2d& uv,
                              Eigen::Vector3d* ray,
                              Eigen::Matrix<double, 3, 2>* J_ray_uv,
                              Eigen::Matrix<double, 3, kNumIntrinsics>* J_ray_intrinsics) const {
  if (!(fu != 0.0 && fv != 0.0) || !uv.allFinite()) return false;
  const Eigen::Vector2d target((uv.x() - pu) / fu, (uv.y() - pv) / fv);
  Eigen::Vector2d p = target;  // (x, y); D is close to the identity near the axis
  if (distortion == DistortionModel::kEquidistant) {
    // 1-D Newton in theta: theta (1 + k1 t^2 + ...) = theta_d = |x_d|.
    const double theta_d = target.norm();
    if (theta_d * theta_d >= internal::kEquidistantSeriesRSq) {
      const Eigen::Vector4d& k = distortion_coeffs;
      double theta = theta_d;
      for (int i = 0; i < kMaxUnprojectIterations; ++i) {
        const double t2 = theta * theta;
        const double f =
            theta * (1.0 + t2 * (k(0) + t2 * (k(1) + t2 * (k(2) + t2 * k(3))))) - theta_d;
        const double df =
            1.0 + t2 * (3.0 * k(0) + t2 * (5.0 * k(1) + t2 * (7.0 * k(2) + t2 * 9.0 * k(3))));
        if (!(df > 0.0)) return false;
        theta -= f / df;
        if (std::abs(f) < kUnprojectTolerance) break;
      }
      if (!(theta > 0.0 && theta < 0.5 * kPi)) return false;
      p = target * (std::tan(theta) / theta_d);
    } else {
      p = target / (1.0 + (distortion_coeffs(0) - 1.0 / 3.0) * target.squaredNorm());
    }
  } else if (distortion == DistortionModel::kRadTan) {
    for (int i = 0; i < kMaxUnprojectIterations; ++i) {
      Eigen::Vector2d d;
      Eigen::Matrix2d J;
      internal::DistortWithJacobians(distortion, distortion_coeffs, p.x(), p.y(), &d, &J, nullptr);
      const Eigen::Vector2d f = d - target;
      if (f.lpNorm<Eigen::Infinity>() < kUnprojectTolerance) break;
      if (!(J.determinant() > 0.0)) return false;
      p -= J.inverse() * f;
      if (!p.allFinite()) return false;
    }
  }
  Eigen::Vector2d d;
  Eigen::Matrix2d J_d_xy;
  Eigen::Matrix<double, 2, 4> J_d_k;
  internal::DistortWithJacobians(distortion, distortion_coeffs, p.x(), p.y(), &d, &J_d_xy, &J_d_k);
  if (!((d - target).lpNorm<Eigen::Infinity>() < kUnprojectAcceptance)) return false;
  if (!(J_d_xy.determinant() > 0.0)) return false;
  if (ray != nullptr) *ray = Eigen::Vector3d(p.x(), p.y(), 1.0);
  if (J_ray_uv == nullptr && J_ray_intrinsics == nullptr) return true;
  const Eigen::Matrix2d J_inv = J_d_xy.inverse();
  if (J_ray_uv != nullptr) {
    J_ray_uv->setZero();
    J_ray_uv->topRows<2>() = J_inv * Eigen::Vector2d(1.0 / fu, 1.0 / fv).asDiagonal();
  }
  if (J_ray_intrinsics != nullptr) {
    // d x_d / d intrinsics: x_d = (u - pu) / fu, y_d = (v - pv) / fv.
    Eigen::Matrix<double, 2, kNumIntrinsics> J_target = Eigen::Matrix<double, 2, 8>::Zero();
    J_target(0, 0) = -target.x() / fu;
    J_target(1, 1) = -target.y() / fv;
    J_target(0, 2) = -1.0 / fu;
    J_target(1, 3) = -1.0 / fv;
    J_target.rightCols<4>() = -J_d_k;
    J_ray_intrinsics->setZero();
    J_ray_intrinsics->topRows<2>() = J_inv * J_target;
  }
  return true;
}

}  // namespace splinecal
