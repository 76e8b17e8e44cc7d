#include "splinecal/camera/camera_model.h"

#include <Eigen/LU>
#include <array>
#include <cmath>

#include "splinecal/enum_names.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

struct SupportedModel {
  ProjectionModel projection;
  DistortionModel distortion;
};

// The 8 supported pairs, in the order of the header's table.
constexpr std::array<SupportedModel, 8> kSupportedModels = {{
    {ProjectionModel::kPinhole, DistortionModel::kNone},
    {ProjectionModel::kPinhole, DistortionModel::kRadTan},
    {ProjectionModel::kPinhole, DistortionModel::kEquidistant},
    {ProjectionModel::kPinhole, DistortionModel::kFov},
    {ProjectionModel::kOmni, DistortionModel::kNone},
    {ProjectionModel::kOmni, DistortionModel::kRadTan},
    {ProjectionModel::kEucm, DistortionModel::kNone},
    {ProjectionModel::kDoubleSphere, DistortionModel::kNone},
}};

// Kalibr's camera_model and distortion_model names.
constexpr std::array<EnumName<ProjectionModel>, 4> kProjectionModelNames = {{
    {ProjectionModel::kPinhole, "pinhole"},
    {ProjectionModel::kOmni, "omni"},
    {ProjectionModel::kEucm, "eucm"},
    {ProjectionModel::kDoubleSphere, "ds"},
}};
constexpr std::array<EnumName<DistortionModel>, 4> kDistortionModelNames = {{
    {DistortionModel::kNone, "none"},
    {DistortionModel::kRadTan, "radtan"},
    {DistortionModel::kEquidistant, "equidistant"},
    {DistortionModel::kFov, "fov"},
}};

// The distortion's part of a command-line name (Kalibr shortens equidistant to equi there).
std::string ShortDistortionName(DistortionModel model) {
  return model == DistortionModel::kEquidistant ? "equi" : DistortionModelName(model);
}

// det [J ; b^T / |b|]: the Jacobian on the plane orthogonal to b, with the orientation of the
// header comment (J b = 0 for every model: points on a ray share their pixel).
double TangentDeterminant(const Eigen::Matrix<double, 2, 3>& J, const Eigen::Vector3d& b) {
  Eigen::Matrix3d M;
  M.topRows<2>() = J;
  M.row(2) = b.normalized().transpose();
  return M.determinant();
}

}  // namespace

std::string ProjectionModelName(ProjectionModel model) {
  return NameOf(kProjectionModelNames, model);
}

std::string DistortionModelName(DistortionModel model) {
  return NameOf(kDistortionModelNames, model);
}

std::string CameraModelName(ProjectionModel projection, DistortionModel distortion) {
  return ProjectionModelName(projection) + "-" + ShortDistortionName(distortion);
}

bool IsSupportedCameraModel(ProjectionModel projection, DistortionModel distortion) {
  for (const SupportedModel& m : kSupportedModels) {
    if (m.projection == projection && m.distortion == distortion) return true;
  }
  return false;
}

bool ParseCameraModelName(const std::string& name,
                          ProjectionModel* projection,
                          DistortionModel* distortion) {
  for (const SupportedModel& m : kSupportedModels) {
    if (name == CameraModelName(m.projection, m.distortion)) {
      *projection = m.projection;
      *distortion = m.distortion;
      return true;
    }
  }
  return false;
}

std::string SupportedCameraModelNames() {
  std::string names;
  for (const SupportedModel& m : kSupportedModels) {
    if (!names.empty()) names += ", ";
    names += CameraModelName(m.projection, m.distortion);
  }
  return names;
}

IntrinsicsVector Camera::intrinsics() const {
  IntrinsicsVector v;
  v << fu, fv, pu, pv, projection_params, distortion_coeffs;
  return v;
}

void Camera::set_intrinsics(const IntrinsicsVector& intrinsics) {
  fu = intrinsics(0);
  fv = intrinsics(1);
  pu = intrinsics(2);
  pv = intrinsics(3);
  projection_params = intrinsics.segment<kNumProjectionParams>(kProjectionParamsIndex);
  distortion_coeffs = intrinsics.segment<kNumDistortionCoeffs>(kDistortionCoeffsIndex);
}

std::vector<int> Camera::ActiveIntrinsics() const {
  std::vector<int> active = {0, 1, 2, 3};
  const int m = kProjectionParamsIndex;
  const int d = kDistortionCoeffsIndex;
  switch (projection) {
    case ProjectionModel::kPinhole:
      break;
    case ProjectionModel::kOmni:
      active.push_back(m);
      break;
    case ProjectionModel::kEucm:
    case ProjectionModel::kDoubleSphere:
      active.insert(active.end(), {m, m + 1});
      break;
  }
  switch (distortion) {
    case DistortionModel::kNone:
      break;
    case DistortionModel::kRadTan:
      active.insert(active.end(), {d, d + 1, d + 2, d + 3});
      if (radtan_k3) active.push_back(d + 4);
      break;
    case DistortionModel::kEquidistant:
      active.insert(active.end(), {d, d + 1, d + 2, d + 3});
      break;
    case DistortionModel::kFov:
      active.push_back(d);
      break;
  }
  return active;
}

bool Camera::IsValid(std::string* error) const {
  auto fail = [error](const std::string& problem) {
    if (error != nullptr) *error = problem;
    return false;
  };
  if (!IsSupportedCameraModel(projection, distortion)) {
    return fail("unsupported camera model " + model_name() +
                " (supported: " + SupportedCameraModelNames() + ")");
  }
  if (!intrinsics().allFinite()) return fail("intrinsics must be finite numbers");
  if (!(fu > 0.0) || !(fv > 0.0)) return fail("focal lengths fu, fv must be positive");
  const double m0 = projection_params(0), m1 = projection_params(1);
  switch (projection) {
    case ProjectionModel::kPinhole:
      break;
    case ProjectionModel::kOmni:
      if (!(m0 >= 0.0)) return fail("omni xi must be >= 0");
      break;
    case ProjectionModel::kEucm:
      if (!(m0 >= 0.0 && m0 <= 1.0)) return fail("eucm alpha must be in [0, 1]");
      if (!(m1 > 0.0)) return fail("eucm beta must be positive");
      break;
    case ProjectionModel::kDoubleSphere:
      if (!(m1 >= 0.0 && m1 <= 1.0)) return fail("ds alpha must be in [0, 1]");
      if (!(m0 > -1.0 && m0 <= 1.0)) return fail("ds xi must be in (-1, 1]");
      break;
  }
  if (distortion == DistortionModel::kFov &&
      !(distortion_coeffs(0) >= 0.0 && distortion_coeffs(0) < kPi)) {
    return fail("fov w must be in [0, pi) [rad]");
  }
  return true;
}

bool Camera::Project(const Eigen::Vector3d& p_c,
                     Eigen::Vector2d* uv,
                     Eigen::Matrix<double, 2, 3>* J_uv_p,
                     Eigen::Matrix<double, 2, kNumIntrinsics>* J_uv_intrinsics) const {
  const bool with_jacobians = J_uv_p != nullptr || J_uv_intrinsics != nullptr;
  Eigen::Vector2d m;
  Eigen::Matrix<double, 2, 3> J_m_p;
  Eigen::Matrix2d J_m_params;
  if (!internal::ProjectToPlane(projection,
                                projection_params,
                                p_c,
                                &m,
                                J_uv_p != nullptr ? &J_m_p : nullptr,
                                J_uv_intrinsics != nullptr ? &J_m_params : nullptr)) {
    return false;
  }
  Eigen::Vector2d md;
  Eigen::Matrix2d J_md_m;
  Eigen::Matrix<double, 2, kNumDistortionCoeffs> J_md_d;
  internal::DistortWithJacobians(distortion,
                                 distortion_coeffs,
                                 m.x(),
                                 m.y(),
                                 &md,
                                 with_jacobians ? &J_md_m : nullptr,
                                 J_uv_intrinsics != nullptr ? &J_md_d : nullptr);
  if (uv != nullptr) *uv = Eigen::Vector2d(fu * md.x() + pu, fv * md.y() + pv);
  if (!with_jacobians) return true;
  const Eigen::Vector2d f(fu, fv);
  const Eigen::Matrix2d F = f.asDiagonal() * J_md_m;  // d uv / d m
  if (J_uv_p != nullptr) *J_uv_p = F * J_m_p;
  if (J_uv_intrinsics != nullptr) {
    J_uv_intrinsics->setZero();
    (*J_uv_intrinsics)(0, 0) = md.x();
    (*J_uv_intrinsics)(1, 1) = md.y();
    (*J_uv_intrinsics)(0, 2) = 1.0;
    (*J_uv_intrinsics)(1, 3) = 1.0;
    J_uv_intrinsics->middleCols<kNumProjectionParams>(kProjectionParamsIndex) = F * J_m_params;
    J_uv_intrinsics->middleCols<kNumDistortionCoeffs>(kDistortionCoeffsIndex) =
        f.asDiagonal() * J_md_d;
  }
  return true;
}

bool Camera::IsDistortionMonotonic(const Eigen::Vector3d& p_c) const {
  Eigen::Matrix<double, 2, 3> J;
  if (!Project(p_c, nullptr, &J)) return false;
  return TangentDeterminant(J, p_c) > 0.0;
}

bool Camera::UnprojectToBearing(const Eigen::Vector2d& uv, Eigen::Vector3d* unit_bearing) const {
  if (!(fu != 0.0 && fv != 0.0) || !uv.allFinite()) return false;
  const Eigen::Vector2d md((uv.x() - pu) / fu, (uv.y() - pv) / fv);
  Eigen::Vector2d m;
  if (!internal::Undistort(distortion, distortion_coeffs, md, &m)) return false;
  Eigen::Vector3d b;
  if (!internal::LiftToBearing(projection, projection_params, m, &b)) return false;
  // The check of the header comment: back onto uv, on a locally invertible branch.
  Eigen::Vector2d uv_back;
  Eigen::Matrix<double, 2, 3> J;
  if (!Project(b, &uv_back, &J)) return false;
  const Eigen::Vector2d error((uv_back.x() - uv.x()) / fu, (uv_back.y() - uv.y()) / fv);
  if (!(error.lpNorm<Eigen::Infinity>() < kUnprojectAcceptance)) return false;
  if (!(TangentDeterminant(J, b) > 0.0)) return false;
  *unit_bearing = b;
  return true;
}

bool Camera::Unproject(const Eigen::Vector2d& uv,
                       Eigen::Vector3d* ray,
                       Eigen::Matrix<double, 3, 2>* J_ray_uv,
                       Eigen::Matrix<double, 3, kNumIntrinsics>* J_ray_intrinsics) const {
  Eigen::Vector3d b;
  if (!UnprojectToBearing(uv, &b) || !(b.z() > 0.0)) return false;
  const Eigen::Vector3d r(b.x() / b.z(), b.y() / b.z(), 1.0);
  if (ray != nullptr) *ray = r;
  if (J_ray_uv == nullptr && J_ray_intrinsics == nullptr) return true;
  // Implicit function Project(r) = uv (header comment).
  Eigen::Matrix<double, 2, 3> J_uv_p;
  Eigen::Matrix<double, 2, kNumIntrinsics> J_uv_intrinsics;
  if (!Project(r, nullptr, &J_uv_p, J_ray_intrinsics != nullptr ? &J_uv_intrinsics : nullptr)) {
    return false;
  }
  const Eigen::Matrix2d A = J_uv_p.leftCols<2>();
  if (!(A.determinant() > 0.0)) return false;
  const Eigen::Matrix2d A_inv = A.inverse();
  if (J_ray_uv != nullptr) {
    J_ray_uv->setZero();
    J_ray_uv->topRows<2>() = A_inv;
  }
  if (J_ray_intrinsics != nullptr) {
    J_ray_intrinsics->setZero();
    J_ray_intrinsics->topRows<2>() = -A_inv * J_uv_intrinsics;
  }
  return true;
}

}  // namespace splinecal
