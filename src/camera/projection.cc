#include "splinecal/camera/projection.h"

#include <cmath>

namespace splinecal {
namespace internal {

bool ProjectToPlane(ProjectionModel model,
                    const Eigen::Vector2d& params,
                    const Eigen::Vector3d& p,
                    Eigen::Vector2d* m,
                    Eigen::Matrix<double, 2, 3>* J_m_p,
                    Eigen::Matrix2d* J_m_params) {
  double den = 0.0;
  if (!ProjectionDenominator(model, params.data(), p, &den)) return false;
  const Eigen::Vector2d m_value = p.head<2>() / den;
  if (m != nullptr) *m = m_value;
  if (J_m_p == nullptr && J_m_params == nullptr) return true;
  // g_p = d den / d p, g_params = d den / d params (header comment).
  Eigen::Vector3d g_p = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d g_params = Eigen::Vector2d::Zero();
  const double x = p.x(), y = p.y(), z = p.z();
  switch (model) {
    case ProjectionModel::kPinhole:
      break;
    case ProjectionModel::kOmni: {
      const double xi = params(0);
      const double d = p.norm();
      g_p += (xi / d) * p;
      g_params(0) = d;
      break;
    }
    case ProjectionModel::kEucm: {
      const double alpha = params(0), beta = params(1);
      const double r2 = x * x + y * y;
      const double rho = std::sqrt(beta * r2 + z * z);
      g_p = (alpha / rho) * Eigen::Vector3d(beta * x, beta * y, z) +
            (1.0 - alpha) * Eigen::Vector3d::UnitZ();
      g_params << rho - z, alpha * r2 / (2.0 * rho);
      break;
    }
    case ProjectionModel::kDoubleSphere: {
      const double xi = params(0), alpha = params(1);
      const double d1 = p.norm();
      const double s = xi * d1 + z;
      const double d2 = std::sqrt(x * x + y * y + s * s);
      const Eigen::Vector3d g_s = (xi / d1) * p + Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d g_d2 = (Eigen::Vector3d(x, y, 0.0) + s * g_s) / d2;
      g_p = alpha * g_d2 + (1.0 - alpha) * g_s;
      g_params << alpha * s * d1 / d2 + (1.0 - alpha) * d1, d2 - s;
      break;
    }
  }
  if (J_m_p != nullptr) {
    J_m_p->setZero();
    J_m_p->leftCols<2>().setIdentity();
    *J_m_p -= m_value * g_p.transpose();
    *J_m_p /= den;
  }
  if (J_m_params != nullptr) *J_m_params = -m_value * g_params.transpose() / den;
  return true;
}

bool LiftToBearing(ProjectionModel model,
                   const Eigen::Vector2d& params,
                   const Eigen::Vector2d& m,
                   Eigen::Vector3d* bearing) {
  if (!m.allFinite()) return false;
  const double r2 = m.squaredNorm();
  Eigen::Vector3d b;
  switch (model) {
    case ProjectionModel::kPinhole:
      b = Eigen::Vector3d(m.x(), m.y(), 1.0);
      break;
    case ProjectionModel::kOmni: {  // [Mei07]
      const double xi = params(0);
      const double discriminant = 1.0 + (1.0 - xi * xi) * r2;
      if (!(discriminant >= 0.0)) return false;
      const double eta = (xi + std::sqrt(discriminant)) / (1.0 + r2);
      b = Eigen::Vector3d(eta * m.x(), eta * m.y(), eta - xi);
      break;
    }
    case ProjectionModel::kEucm: {  // [Usenko18]
      const double alpha = params(0), beta = params(1);
      const double discriminant = 1.0 - (2.0 * alpha - 1.0) * beta * r2;
      if (!(discriminant >= 0.0)) return false;
      const double m_z =
          (1.0 - beta * alpha * alpha * r2) / (alpha * std::sqrt(discriminant) + 1.0 - alpha);
      b = Eigen::Vector3d(m.x(), m.y(), m_z);
      break;
    }
    case ProjectionModel::kDoubleSphere: {  // [Usenko18]
      const double xi = params(0), alpha = params(1);
      const double discriminant = 1.0 - (2.0 * alpha - 1.0) * r2;
      if (!(discriminant >= 0.0)) return false;
      const double m_z =
          (1.0 - alpha * alpha * r2) / (alpha * std::sqrt(discriminant) + 1.0 - alpha);
      const double inner = m_z * m_z + (1.0 - xi * xi) * r2;
      if (!(inner >= 0.0)) return false;
      const double eta = (m_z * xi + std::sqrt(inner)) / (m_z * m_z + r2);
      b = Eigen::Vector3d(eta * m.x(), eta * m.y(), eta * m_z - xi);
      break;
    }
    default:
      return false;
  }
  const double norm = b.norm();
  if (!(norm > 0.0) || !b.allFinite()) return false;
  *bearing = b / norm;
  return true;
}

}  // namespace internal
}  // namespace splinecal
