// Camera models (Kalibr's, docs/conventions.md "Camera models"): projection and unprojection with
// analytic Jacobians with respect to the point and to the intrinsics, valid-region checks, and
// the names used in camchain.yaml and on the command line.
//
// Every model is three stages, uv = K(D(P(p_c))):
//
//   m   = P(p_c; m0, m1) = (x, y) / den(p_c)     projection to the normalised plane
//                                                (camera/projection.h: den, valid region, lift)
//   m_d = D(m; d0..d4)                           lens distortion (camera/distortion.h)
//   uv  = (fu m_d,x + pu, fv m_d,y + pv)         [px]
//
// The 8 supported models (Kalibr's names; "projection-distortion" on the command line):
//
//   name            camchain.yaml camera_model, intrinsics   distortion_model, coeffs
//   pinhole-none    pinhole [fu fv pu pv]                  none []
//   pinhole-radtan  pinhole [fu fv pu pv]                  radtan [k1 k2 p1 p2] or [.. k3]
//   pinhole-equi    pinhole [fu fv pu pv]                  equidistant [k1 k2 k3 k4]
//   pinhole-fov     pinhole [fu fv pu pv]                  fov [w]
//   omni-none       omni [xi fu fv pu pv]                  none []
//   omni-radtan     omni [xi fu fv pu pv]                  radtan [k1 k2 p1 p2] or [.. k3]
//   eucm-none       eucm [alpha beta fu fv pu pv]          none []
//   ds-none         ds [xi alpha fu fv pu pv]              none []
//
// Intrinsics vector (the layout of every intrinsics Jacobian), 11 entries:
//   [fu fv pu pv | m0 m1 | d0 d1 d2 d3 d4]
//   (m0, m1) = omni (xi, 0), eucm (alpha, beta), ds (xi, alpha), pinhole (0, 0);
//   d = radtan (k1 k2 p1 p2 k3), equidistant (k1 k2 k3 k4 0), fov (w 0 0 0 0), none 0.
// Entries a model does not use have zero Jacobian columns; ActiveIntrinsics() lists the others.
//
// Jacobians (chain rule through the stages):
//   d uv / d p_c        = F J_m_p,                F = diag(fu, fv) dD/dm
//   d uv / d (fu fv pu pv) = [[m_d,x, 0, 1, 0], [0, m_d,y, 0, 1]]
//   d uv / d (m0, m1)   = F J_m_params
//   d uv / d d          = diag(fu, fv) dD/dd
// with J_m_p, J_m_params from camera/projection.h and dD/dm, dD/dd from camera/distortion.h.
//
// Validity. Project returns false outside the projection's valid region (camera/projection.h:
// pinhole z > kMinDepth; omni, eucm, ds the regions of [Usenko18]). A distortion polynomial may
// fold back beyond some radius (radtan with k1 < 0, a large equidistant theta), and an omni
// camera with xi > 1 folds at its region's border: IsDistortionMonotonic tells whether the whole
// projection is still locally invertible at a point,
//   det [d uv / d p_c ; p_c^T / |p_c|] > 0
// (the 2x2 Jacobian on the plane orthogonal to the ray, oriented so that it is fu fv / z^2 > 0
// on the optical axis). The simulator uses it with InImage for its field-of-view check.
//
// Unprojection. UnprojectToBearing undoes K, then D (camera/distortion.h: Newton for radtan and
// equidistant, closed form for fov), then P (closed form lift), and checks the result: the
// bearing must project back onto uv (to kUnprojectAcceptance in normalised units) on a locally
// invertible branch. It is valid for wide-angle (> 180 degree) cameras. Unproject returns the
// ray (x, y, 1) of the same bearing (z = 1, so a point at depth z is z * ray) and fails for
// bearings at or beyond 90 degrees from the axis. Its Jacobians follow from the implicit
// function Project((x, y, 1)) = uv, with A = d uv / d (x, y) at z = 1 (the first two columns of
// d uv / d p_c):
//   d (x, y) / d uv          = A^-1
//   d (x, y) / d intrinsics  = -A^-1 d uv / d intrinsics.
//
// References: camera/projection.h and camera/distortion.h; docs/conventions.md has the table
// with the formulas.
#ifndef SPLINECAL_CAMERA_CAMERA_MODEL_H_
#define SPLINECAL_CAMERA_CAMERA_MODEL_H_

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "splinecal/camera/distortion.h"
#include "splinecal/camera/projection.h"

namespace splinecal {

// "pinhole", "omni", "eucm", "ds" (Kalibr's camera_model).
std::string ProjectionModelName(ProjectionModel model);
// "none", "radtan", "equidistant", "fov" (Kalibr's distortion_model).
std::string DistortionModelName(DistortionModel model);
// "pinhole-radtan", "pinhole-equi", "omni-none", ... (Kalibr's command-line names; the
// equidistant model is "equi" here). Unsupported pairs are named the same way.
std::string CameraModelName(ProjectionModel projection, DistortionModel distortion);
// True for the 8 supported pairs (file comment).
bool IsSupportedCameraModel(ProjectionModel projection, DistortionModel distortion);
// Accepts exactly the 8 names of the file comment; false (outputs untouched) for anything else.
bool ParseCameraModelName(const std::string& name,
                          ProjectionModel* projection,
                          DistortionModel* distortion);
// The 8 names, comma-separated, for messages.
std::string SupportedCameraModelNames();

// Intrinsics layout (file comment).
inline constexpr int kNumIntrinsics = 11;
inline constexpr int kProjectionParamsIndex = 4;  // m0, m1
inline constexpr int kDistortionCoeffsIndex = 6;  // d0..d4
using IntrinsicsVector = Eigen::Matrix<double, kNumIntrinsics, 1>;

// A camera: its projection and distortion models, their parameters and the image size.
struct Camera {
  // Points closer to a pinhole camera's plane than this [m] do not project (z <= kMinDepth).
  static constexpr double kMinDepth = internal::kPinholeMinDepth;
  // An unprojected bearing must project back onto its pixel within this, in normalised units
  // (|uv error| / f; 1e-9 is ~1e-6 px at f = 1000 px, far above the 1e-14 the inversions reach).
  static constexpr double kUnprojectAcceptance = 1e-9;

  ProjectionModel projection = ProjectionModel::kPinhole;
  DistortionModel distortion = DistortionModel::kNone;
  double fu = 1.0;  // focal lengths [px]
  double fv = 1.0;
  double pu = 0.0;  // principal point [px]
  double pv = 0.0;
  Eigen::Vector2d projection_params = Eigen::Vector2d::Zero();    // (m0, m1), file comment
  DistortionCoeffs distortion_coeffs = DistortionCoeffs::Zero();  // d0..d4, file comment
  // radtan only: k3 (d4) is estimated too (camchain.yaml gave 5 coefficients). Without it k3 is
  // held at its value (0 unless given).
  bool radtan_k3 = false;
  int width = 0;   // [px]
  int height = 0;  // [px] (rows; the rolling shutter reads them top to bottom)

  // "pinhole-radtan" etc.
  std::string model_name() const { return CameraModelName(projection, distortion); }

  IntrinsicsVector intrinsics() const;
  void set_intrinsics(const IntrinsicsVector& intrinsics);

  // Indices into the intrinsics vector that this model uses and an estimator may vary, in
  // increasing order: fu fv pu pv, the projection's parameters, the distortion's coefficients
  // (radtan's k3 only with radtan_k3). Every other entry is held constant by estimators.
  std::vector<int> ActiveIntrinsics() const;

  // True when the parameters are in the models' domains: a supported pair, finite values,
  // fu, fv > 0; omni xi >= 0; eucm alpha in [0, 1], beta > 0; ds alpha in [0, 1], xi in (-1, 1];
  // fov w in [0, pi). Otherwise false with the problem in words in *error (if not null).
  bool IsValid(std::string* error = nullptr) const;

  // Pixel of p_c; false (outputs untouched) outside the valid region. Outputs optional
  // (nullptr): J_uv_p = d uv / d p_c (2x3), J_uv_intrinsics = d uv / d intrinsics (2x11).
  bool Project(const Eigen::Vector3d& p_c,
               Eigen::Vector2d* uv,
               Eigen::Matrix<double, 2, 3>* J_uv_p = nullptr,
               Eigen::Matrix<double, 2, kNumIntrinsics>* J_uv_intrinsics = nullptr) const;

  // The unit bearing whose projection is uv, for any field of view; false when uv has no
  // preimage in the valid region on a locally invertible branch (file comment).
  bool UnprojectToBearing(const Eigen::Vector2d& uv, Eigen::Vector3d* unit_bearing) const;

  // The ray (x, y, 1) whose projection is uv; false when UnprojectToBearing fails or the bearing
  // is at or beyond 90 degrees from the optical axis. Outputs optional: J_ray_uv (3x2, last row
  // 0), J_ray_intrinsics (3x11, last row 0).
  bool Unproject(const Eigen::Vector2d& uv,
                 Eigen::Vector3d* ray,
                 Eigen::Matrix<double, 3, 2>* J_ray_uv = nullptr,
                 Eigen::Matrix<double, 3, kNumIntrinsics>* J_ray_intrinsics = nullptr) const;

  // 0 <= u <= width - 1 and 0 <= v <= height - 1 (pixel centres at integers, Kalibr/OpenCV).
  bool InImage(const Eigen::Vector2d& uv) const {
    return uv.x() >= 0.0 && uv.y() >= 0.0 && uv.x() <= width - 1.0 && uv.y() <= height - 1.0;
  }

  // The projection is valid and still locally invertible (has not folded back) at p_c:
  // det [d uv / d p_c ; p_c^T / |p_c|] > 0 (file comment).
  bool IsDistortionMonotonic(const Eigen::Vector3d& p_c) const;
  // The same at the point (x, y, 1) (normalised pinhole coordinates).
  bool IsDistortionMonotonic(double x, double y) const {
    return IsDistortionMonotonic(Eigen::Vector3d(x, y, 1.0));
  }
};

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_CAMERA_MODEL_H_
