#include "splinecal/camera/distortion.h"

#include <Eigen/LU>
#include <cmath>

#include "splinecal/units.h"

namespace splinecal {
namespace internal {

namespace {

// Newton's method for the undistortion stops when the residual of D(m) = m_d is below this
// (normalised image units; 1e-14 is ~1e-11 px at a focal length of 1000 px, far under any
// detector's precision, and a few ulps above the rounding floor of D near |m| ~ 1).
constexpr double kUndistortTolerance = 1e-14;
constexpr int kMaxUndistortIterations = 30;

// s = theta_d / r of the equidistant model, (ds/dr) / r and ds/dk (file comment of the header).
void EquidistantScale(
    const DistortionCoeffs& d, double r2, double* s, double* ds_dr_over_r, Eigen::Vector4d* ds_dk) {
  if (r2 < kEquidistantSeriesRSq) {
    // Series; theta ~ r to first order in the coefficient Jacobian.
    *s = 1.0 + (d(0) - 1.0 / 3.0) * r2;
    *ds_dr_over_r = 2.0 * (d(0) - 1.0 / 3.0);
    *ds_dk << r2, r2 * r2, r2 * r2 * r2, r2 * r2 * r2 * r2;
    return;
  }
  const double r = std::sqrt(r2);
  const double theta = std::atan(r);
  const double t2 = theta * theta;
  const double poly = 1.0 + t2 * (d(0) + t2 * (d(1) + t2 * (d(2) + t2 * d(3))));
  const double theta_d = theta * poly;
  // d theta_d / d theta; d theta / d r = 1 / (1 + r^2).
  const double dpoly =
      1.0 + t2 * (3.0 * d(0) + t2 * (5.0 * d(1) + t2 * (7.0 * d(2) + t2 * 9.0 * d(3))));
  *s = theta_d / r;
  *ds_dr_over_r = (dpoly / (1.0 + r2) * r - theta_d) / (r2 * r);
  const double theta_over_r = theta / r;
  *ds_dk << theta_over_r * t2, theta_over_r * t2 * t2, theta_over_r * t2 * t2 * t2,
      theta_over_r * t2 * t2 * t2 * t2;
}

// s = r_d / r of the fov model, (ds/dr) / r and ds/dw (file comment of the header).
void FovScale(double w, double r2, double* s, double* ds_dr_over_r, double* ds_dw) {
  if (w * w < kFovSeriesW2) {
    *s = 1.0 + w * w * (1.0 / 12.0 - r2 / 3.0);
    *ds_dr_over_r = -2.0 * w * w / 3.0;
    *ds_dw = 2.0 * w * (1.0 / 12.0 - r2 / 3.0);
    return;
  }
  const double a = 2.0 * std::tan(0.5 * w);
  const double da_dw = 1.0 + 0.25 * a * a;
  if (r2 < kFovSeriesRSq) {
    *s = a / w * (1.0 - a * a * r2 / 3.0);
    *ds_dr_over_r = -2.0 * a * a * a / (3.0 * w);
    // d/dw of (a/w) (1 - a^2 r^2 / 3).
    *ds_dw =
        (da_dw * w - a) / (w * w) * (1.0 - a * a * r2 / 3.0) - a / w * (2.0 * a * da_dw * r2 / 3.0);
    return;
  }
  const double r = std::sqrt(r2);
  const double ar = a * r;
  const double atan_ar = std::atan(ar);
  *s = atan_ar / (w * r);
  *ds_dr_over_r = (ar / (1.0 + ar * ar) - atan_ar) / (w * r2 * r);
  *ds_dw = da_dw / (w * (1.0 + ar * ar)) - *s / w;
}

}  // namespace

void DistortWithJacobians(DistortionModel model,
                          const DistortionCoeffs& d,
                          double x,
                          double y,
                          Eigen::Vector2d* md,
                          Eigen::Matrix2d* J_md_m,
                          Eigen::Matrix<double, 2, kNumDistortionCoeffs>* J_md_d) {
  const double r2 = x * x + y * y;
  if (J_md_d != nullptr) J_md_d->setZero();
  switch (model) {
    case DistortionModel::kNone:
      if (md != nullptr) *md = Eigen::Vector2d(x, y);
      if (J_md_m != nullptr) J_md_m->setIdentity();
      return;
    case DistortionModel::kRadTan: {
      const double k1 = d(0), k2 = d(1), p1 = d(2), p2 = d(3), k3 = d(4);
      const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
      if (md != nullptr) {
        *md = Eigen::Vector2d(x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                              y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y);
      }
      if (J_md_m != nullptr) {
        const double g = 2.0 * k1 + r2 * (4.0 * k2 + 6.0 * k3 * r2);  // d radial/dx = g x
        const double off_diagonal = g * x * y + 2.0 * p1 * x + 2.0 * p2 * y;
        (*J_md_m)(0, 0) = radial + g * x * x + 2.0 * p1 * y + 6.0 * p2 * x;
        (*J_md_m)(0, 1) = off_diagonal;
        (*J_md_m)(1, 0) = off_diagonal;
        (*J_md_m)(1, 1) = radial + g * y * y + 6.0 * p1 * y + 2.0 * p2 * x;
      }
      if (J_md_d != nullptr) {
        const double r4 = r2 * r2;
        (*J_md_d) << x * r2, x * r4, 2.0 * x * y, r2 + 2.0 * x * x, x * r4 * r2,  //
            y * r2, y * r4, r2 + 2.0 * y * y, 2.0 * x * y, y * r4 * r2;
      }
      return;
    }
    case DistortionModel::kEquidistant:
    case DistortionModel::kFov: {
      double s = 1.0;
      double ds_dr_over_r = 0.0;
      Eigen::Vector4d ds_dd = Eigen::Vector4d::Zero();
      if (model == DistortionModel::kEquidistant) {
        EquidistantScale(d, r2, &s, &ds_dr_over_r, &ds_dd);
      } else {
        FovScale(d(0), r2, &s, &ds_dr_over_r, &ds_dd(0));
      }
      const Eigen::Vector2d m(x, y);
      if (md != nullptr) *md = s * m;
      if (J_md_m != nullptr) {
        *J_md_m = s * Eigen::Matrix2d::Identity() + ds_dr_over_r * m * m.transpose();
      }
      if (J_md_d != nullptr) J_md_d->leftCols<4>() = m * ds_dd.transpose();
      return;
    }
  }
}

bool Undistort(DistortionModel model,
               const DistortionCoeffs& d,
               const Eigen::Vector2d& md,
               Eigen::Vector2d* m) {
  if (!md.allFinite()) return false;
  switch (model) {
    case DistortionModel::kNone:
      *m = md;
      return true;
    case DistortionModel::kRadTan: {
      Eigen::Vector2d p = md;  // D is close to the identity near the axis
      for (int i = 0; i < kMaxUndistortIterations; ++i) {
        Eigen::Vector2d f;
        Eigen::Matrix2d J;
        DistortWithJacobians(model, d, p.x(), p.y(), &f, &J, nullptr);
        f -= md;
        if (f.lpNorm<Eigen::Infinity>() < kUndistortTolerance) break;
        if (!(J.determinant() > 0.0)) return false;
        p -= J.inverse() * f;
        if (!p.allFinite()) return false;
      }
      *m = p;
      return true;
    }
    case DistortionModel::kEquidistant: {
      // 1-D Newton in theta: theta (1 + k1 t^2 + ...) = theta_d = |m_d|.
      const double theta_d = md.norm();
      if (theta_d * theta_d < kEquidistantSeriesRSq) {
        *m = md / (1.0 + (d(0) - 1.0 / 3.0) * md.squaredNorm());
        return true;
      }
      double theta = theta_d;
      for (int i = 0; i < kMaxUndistortIterations; ++i) {
        const double t2 = theta * theta;
        const double f =
            theta * (1.0 + t2 * (d(0) + t2 * (d(1) + t2 * (d(2) + t2 * d(3))))) - theta_d;
        const double df =
            1.0 + t2 * (3.0 * d(0) + t2 * (5.0 * d(1) + t2 * (7.0 * d(2) + t2 * 9.0 * d(3))));
        if (!(df > 0.0)) return false;
        theta -= f / df;
        if (std::abs(f) < kUndistortTolerance) break;
      }
      if (!(theta > 0.0 && theta < 0.5 * kPi)) return false;
      *m = md * (std::tan(theta) / theta_d);
      return true;
    }
    case DistortionModel::kFov: {
      const double w = d(0);
      const double r_d2 = md.squaredNorm();
      if (w * w < kFovSeriesW2) {
        // Inverse of s = 1 + w^2 (1/12 - r^2/3) to the same order (r = r_d + O(w^2)).
        *m = md / (1.0 + w * w * (1.0 / 12.0 - r_d2 / 3.0));
        return true;
      }
      const double a = 2.0 * std::tan(0.5 * w);
      if (r_d2 < kFovSeriesRSq) {
        // r / r_d = tan(w r_d) / (a r_d) = (w / a) (1 + w^2 r_d^2 / 3 + O(r_d^4)).
        *m = md * (w / a * (1.0 + w * w * r_d2 / 3.0));
        return true;
      }
      const double r_d = std::sqrt(r_d2);
      if (!(std::abs(w) * r_d < 0.5 * kPi) || !(a != 0.0)) return false;
      *m = md * (std::tan(w * r_d) / (a * r_d));
      return true;
    }
  }
  return false;
}

}  // namespace internal
}  // namespace splinecal
