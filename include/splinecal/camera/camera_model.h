// Pinhole camera with radial-tangential, equidistant or no distortion (Kalibr's `pinhole` camera
// model with `radtan`, `equidistant` or `none`, CONVENTIONS.md "Camera ..."): projection and
// unprojection with analytic Jacobians with respect to the point and to the intrinsics.
//
// Projection of a point p_c = (X, Y, Z) in the camera frame (Z > 0, in front of the camera):
//
//   x = X / Z,  y = Y / Z                                      (normalised image plane)
//   (x_d, y_d) = D(x, y; k)                                    (distortion, below)
//   u = fu x_d + pu,   v = fv y_d + pv                         [px]
//
// Distortion models (k = distortion_coeffs, r^2 = x^2 + y^2):
//   none         D(x, y) = (x, y)
//   radtan       (Brown-Conrady, k = [k1 k2 p1 p2], as OpenCV / Kalibr)
//                  x_d = x (1 + k1 r^2 + k2 r^4) + 2 p1 x y + p2 (r^2 + 2 x^2)
//                  y_d = y (1 + k1 r^2 + k2 r^4) + p1 (r^2 + 2 y^2) + 2 p2 x y
//   equidistant  (Kannala-Brandt, k = [k1 k2 k3 k4], as Kalibr / OpenCV fisheye)
//                  theta = atan(r),  theta_d = theta (1 + k1 theta^2 + k2 theta^4
//                                                      + k3 theta^6 + k4 theta^8)
//                  (x_d, y_d) = s (x, y),  s = theta_d / r
//                Near the optical axis (r^2 < 1e-10) s uses its series
//                  s = 1 + (k1 - 1/3) r^2     (first dropped term O(r^4) < 1e-20)
//                and ds/dr / r = 2 (k1 - 1/3): r = sqrt(x^2 + y^2) is never differentiated at 0
//                (sqrt'(0) is infinite for Jets).
//
// Intrinsics vector (the layout of every intrinsics Jacobian): [fu fv pu pv k_0 k_1 k_2 k_3],
// 8 entries; the distortion entries of `none` are zero and their Jacobian columns are zero.
//
// Unprojection inverts D by Newton's method (2-D for radtan, 1-D in theta for equidistant) and
// returns the ray (x, y, 1) (z = 1, so a point at depth Z is Z * ray). Its Jacobians come from
// the implicit function D(x; k) = x_d(u, intrinsics):
//   d(x, y)/d(u, v)       = J_D^-1 diag(1/fu, 1/fv)
//   d(x, y)/d intrinsics  = J_D^-1 (d x_d / d intrinsics - d D / d k),   J_D = dD/d(x, y).
//
// Validity. Project returns false for points with Z <= kMinDepth (behind or on the camera
// plane). A distortion polynomial folds back beyond some radius (radtan with k1 < 0, a large
// equidistant theta): IsDistortionMonotonic tells whether the radial map is still increasing at
// a point (det J_D > 0), the test the simulator uses with InImage for its field-of-view check.
#ifndef SPLINECAL_CAMERA_CAMERA_MODEL_H_
#define SPLINECAL_CAMERA_CAMERA_MODEL_H_

#include <Eigen/Core>
#include <cmath>
#include <string>

namespace splinecal {

enum class DistortionModel { kNone, kRadTan, kEquidistant };

// "none", "radtan", "equidistant" (Kalibr's spelling).
std::string DistortionModelName(DistortionModel model);

inline constexpr int kNumIntrinsics = 8;  // [fu fv pu pv k0 k1 k2 k3]
using IntrinsicsVector = Eigen::Matrix<double, kNumIntrinsics, 1>;

namespace internal {

// Below this r^2 the equidistant model uses its series (file comment).
inline constexpr double kEquidistantSeriesRSq = 1e-10;

// D(x, y; k) for any scalar (double or ceres::Jet). k points at 4 coefficients (ignored for
// kNone).
template <typename T>
Eigen::Matrix<T, 2, 1> Distort(DistortionModel model, const T* k, const T& x, const T& y) {
  using std::atan;
  using std::sqrt;
  if (model == DistortionModel::kNone) return Eigen::Matrix<T, 2, 1>(x, y);
  const T r2 = x * x + y * y;
  if (model == DistortionModel::kRadTan) {
    const T radial = T(1.0) + k[0] * r2 + k[1] * r2 * r2;
    const T xy = x * y;
    return Eigen::Matrix<T, 2, 1>(x * radial + T(2.0) * k[2] * xy + k[3] * (r2 + T(2.0) * x * x),
                                  y * radial + k[2] * (r2 + T(2.0) * y * y) + T(2.0) * k[3] * xy);
  }
  // Equidistant.
  T s;
  if (r2 < T(kEquidistantSeriesRSq)) {
    s = T(1.0) + (k[0] - T(1.0 / 3.0)) * r2;
  } else {
    const T r = sqrt(r2);
    const T theta = atan(r);
    const T t2 = theta * theta;
    const T theta_d = theta * (T(1.0) + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
    s = theta_d / r;
  }
  return Eigen::Matrix<T, 2, 1>(s * x, s * y);
}

}  // namespace internal

// A pinhole camera with its distortion and image size.
struct PinholeCamera {
  // Points closer to the camera plane than this [m] do not project (Z <= kMinDepth).
  static constexpr double kMinDepth = 1e-6;

  double fu = 1.0;  // focal lengths [px]
  double fv = 1.0;
  double pu = 0.0;  // principal point [px]
  double pv = 0.0;
  DistortionModel distortion = DistortionModel::kNone;
  Eigen::Vector4d distortion_coeffs = Eigen::Vector4d::Zero();  // radtan k1 k2 p1 p2; equi k1..k4
  int width = 0;                                                // [px]
  int height = 0;  // [px] (rows; the rolling shutter reads them top to bottom)

  IntrinsicsVector intrinsics() const;
  void set_intrinsics(const IntrinsicsVector& intrinsics);

  // Pixel of p_c; false (outputs untouched) when Z <= kMinDepth. Outputs optional (nullptr):
  // J_uv_p = d uv / d p_c (2x3), J_uv_intrinsics = d uv / d intrinsics (2x8).
  bool Project(const Eigen::Vector3d& p_c,
               Eigen::Vector2d* uv,
               Eigen::Matrix<double, 2, 3>* J_uv_p = nullptr,
               Eigen::Matrix<double, 2, kNumIntrinsics>* J_uv_intrinsics = nullptr) const;

  // The ray (x, y, 1) whose projection is uv; false when Newton's method does not converge
  // (a pixel outside the invertible part of the distortion). Outputs optional:
  // J_ray_uv (3x2, last row 0), J_ray_intrinsics (3x8, last row 0).
  bool Unproject(const Eigen::Vector2d& uv,
                 Eigen::Vector3d* ray,
                 Eigen::Matrix<double, 3, 2>* J_ray_uv = nullptr,
                 Eigen::Matrix<double, 3, kNumIntrinsics>* J_ray_intrinsics = nullptr) const;

  // 0 <= u <= width - 1 and 0 <= v <= height - 1 (pixel centres at integers, Kalibr/OpenCV).
  bool InImage(const Eigen::Vector2d& uv) const {
    return uv.x() >= 0.0 && uv.y() >= 0.0 && uv.x() <= width - 1.0 && uv.y() <= height - 1.0;
  }

  // det dD/d(x, y) > 0 at the normalised point (x, y): the distortion has not folded back.
  bool IsDistortionMonotonic(double x, double y) const;

  // The same projection for any scalar (ceres::Jet in automatic differentiation tests):
  // intrinsics[8] in the layout above. Returns false for Z <= kMinDepth.
  template <typename T>
  static bool ProjectT(DistortionModel model,
                       const T* intrinsics,
                       const Eigen::Matrix<T, 3, 1>& p_c,
                       Eigen::Matrix<T, 2, 1>* uv) {
    if (!(p_c.z() > T(kMinDepth))) return false;
    const T x = p_c.x() / p_c.z();
    const T y = p_c.y() / p_c.z();
    const Eigen::Matrix<T, 2, 1> d = internal::Distort(model, intrinsics + 4, x, y);
    (*uv)(0) = intrinsics[0] * d(0) + intrinsics[2];
    (*uv)(1) = intrinsics[1] * d(1) + intrinsics[3];
    return true;
  }
};

namespace internal {

// D and its Jacobians (double): J_d_xy = dD/d(x, y) (2x2), J_d_k = dD/dk (2x4, zero for kNone).
void DistortWithJacobians(DistortionModel model,
                          const Eigen::Vector4d& k,
                          double x,
                          double y,
                          Eigen::Vector2d* d,
                          Eigen::Matrix2d* J_d_xy,
                          Eigen::Matrix<double, 2, 4>* J_d_k);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_CAMERA_MODEL_H_
