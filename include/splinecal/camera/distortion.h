// Lens distortion on the normalised image plane, the second stage of every camera model of
// camera/camera_model.h: m = (x, y) -> m_d = D(m; d), d = the 5 distortion entries of the
// intrinsics vector (d0..d4). r^2 = x^2 + y^2 throughout.
//
//   none         D(m) = m
//   radtan       Brown-Conrady as OpenCV's projectPoints and Kalibr (d = [k1 k2 p1 p2 k3], k3 is
//                OpenCV's 5th coefficient, 0 unless given) [Brown66], [OpenCV]:
//                  radial = 1 + k1 r^2 + k2 r^4 + k3 r^6
//                  x_d = x radial + 2 p1 x y + p2 (r^2 + 2 x^2)
//                  y_d = y radial + p1 (r^2 + 2 y^2) + 2 p2 x y
//   equidistant  Kannala-Brandt with 4 coefficients after the pinhole division (Kalibr's
//                `equidistant`, OpenCV's fisheye module; d = [k1 k2 k3 k4 0]) [Kannala06]:
//                  theta = atan(r),  theta_d = theta (1 + k1 theta^2 + k2 theta^4 + k3 theta^6
//                                                     + k4 theta^8)
//                  m_d = s m,  s = theta_d / r
//   fov          Devernay-Faugeras field of view (d = [w 0 0 0 0], w [rad]) [Devernay01]:
//                  r_d = atan(2 r tan(w/2)) / w,   m_d = s m,  s = r_d / r
//
// Jacobians (double, DistortWithJacobians). Radial models (equidistant, fov) have m_d = s(r) m,
// so dD/dm = s I + (s'(r) / r) m m^T and dD/dd = m ds/dd^T. radtan:
//   d x_d / d x = radial + g x^2 + 2 p1 y + 6 p2 x,   d x_d / d y = g x y + 2 p1 x + 2 p2 y,
//   d y_d / d x = g x y + 2 p1 x + 2 p2 y,            d y_d / d y = radial + g y^2 + 6 p1 y + 2 p2
//   x, g = 2 k1 + 4 k2 r^2 + 6 k3 r^4  (d radial / dx = g x); d m_d / d [k1 k2 p1 p2 k3] = [[x r^2,
//   x r^4, 2 x y, r^2 + 2 x^2, x r^6],
//                                [y r^2, y r^4, r^2 + 2 y^2, 2 x y, y r^6]].
// equidistant: s' = (theta_d'(theta) / (1 + r^2) - s) / r, with
//   theta_d' = 1 + 3 k1 theta^2 + 5 k2 theta^4 + 7 k3 theta^6 + 9 k4 theta^8, and
//   ds / dk_i = theta^(2i+1) / r.
// fov, a = 2 tan(w/2), da/dw = 1 + a^2/4:
//   s'(r) / r = (a r / (1 + a^2 r^2) - atan(a r)) / (w r^3),
//   ds/dw = (da/dw) / (w (1 + a^2 r^2)) - s / w.
//
// Series near singular points (r = 0 is never differentiated through sqrt, whose derivative is
// infinite there for Jets; w = 0 is a removable 0/0):
//   equidistant, r^2 < kEquidistantSeriesRSq: s = 1 + (k1 - 1/3) r^2, s'/r = 2 (k1 - 1/3)
//                (first dropped term O(r^4) < 1e-20);
//   fov, w^2 < kFovSeriesW2:  s = 1 + w^2 (1/12 - r^2/3), ds/dw = 2 w (1/12 - r^2/3),
//                s'/r = -2 w^2 / 3 (first dropped term O(w^4 (1 + r^4)) < 1e-20 (1 + r^4));
//   fov, r^2 < kFovSeriesRSq: s = (a/w) (1 - a^2 r^2 / 3), s'/r = -2 a^3 / (3 w)
//                (first dropped term (a/w) a^4 r^4 / 5 < 1e-20 a^4).
// Above the thresholds the closed forms cancel (s'(r)/r ~ eps / r^2 absolute error, ds/dw ~
// eps / w), but s'/r multiplies m m^T (|.| <= r^2) and ds/dw multiplies m, so the Jacobians stay
// accurate to ~1e-11 absolute.
//
// Undistortion (Undistort, for unprojection) inverts D: 2-D Newton for radtan, 1-D Newton in theta
// for equidistant (theta < pi/2: the pinhole division before it allows no more), closed form for
// fov, r = tan(w r_d) / (2 tan(w/2)) for w r_d < pi/2 [Devernay01]. Callers check the result
// by distorting it again (camera/camera_model.h).
//
// References: [Brown66] D. C. Brown, "Decentering distortion of lenses", Photogrammetric
// Engineering 1966; [OpenCV] OpenCV calib3d documentation (projectPoints, fisheye); [Kannala06]
// J. Kannala, S. Brandt, PAMI 2006; [Devernay01] F. Devernay, O. Faugeras, "Straight lines have
// to be straight", Machine Vision and Applications 2001 (docs/references.md).
#ifndef SPLINECAL_CAMERA_DISTORTION_H_
#define SPLINECAL_CAMERA_DISTORTION_H_

#include <Eigen/Core>
#include <cmath>

namespace splinecal {

// Kalibr's distortion models (docs/conventions.md, "Camera models").
enum class DistortionModel { kNone, kRadTan, kEquidistant, kFov };

inline constexpr int kNumDistortionCoeffs = 5;  // d0..d4 of the intrinsics vector
using DistortionCoeffs = Eigen::Matrix<double, kNumDistortionCoeffs, 1>;

namespace internal {

// Series thresholds (file comment).
inline constexpr double kEquidistantSeriesRSq = 1e-10;
inline constexpr double kFovSeriesRSq = 1e-10;
inline constexpr double kFovSeriesW2 = 1e-10;

// D(x, y; d) for any scalar (double or ceres::Jet); d points at 5 coefficients.
template <typename T>
Eigen::Matrix<T, 2, 1> Distort(DistortionModel model, const T* d, const T& x, const T& y) {
  using std::atan;
  using std::sqrt;
  using std::tan;
  const T r2 = x * x + y * y;
  switch (model) {
    case DistortionModel::kNone:
      return Eigen::Matrix<T, 2, 1>(x, y);
    case DistortionModel::kRadTan: {
      const T radial = T(1.0) + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
      const T xy = x * y;
      return Eigen::Matrix<T, 2, 1>(x * radial + T(2.0) * d[2] * xy + d[3] * (r2 + T(2.0) * x * x),
                                    y * radial + d[2] * (r2 + T(2.0) * y * y) + T(2.0) * d[3] * xy);
    }
    case DistortionModel::kEquidistant: {
      T s;
      if (r2 < T(kEquidistantSeriesRSq)) {
        s = T(1.0) + (d[0] - T(1.0 / 3.0)) * r2;
      } else {
        const T r = sqrt(r2);
        const T theta = atan(r);
        const T t2 = theta * theta;
        s = theta * (T(1.0) + t2 * (d[0] + t2 * (d[1] + t2 * (d[2] + t2 * d[3])))) / r;
      }
      return Eigen::Matrix<T, 2, 1>(s * x, s * y);
    }
    case DistortionModel::kFov: {
      const T& w = d[0];
      T s;
      if (w * w < T(kFovSeriesW2)) {
        s = T(1.0) + w * w * (T(1.0 / 12.0) - r2 / T(3.0));
      } else {
        const T a = T(2.0) * tan(w / T(2.0));
        if (r2 < T(kFovSeriesRSq)) {
          s = a / w * (T(1.0) - a * a * r2 / T(3.0));
        } else {
          const T r = sqrt(r2);
          s = atan(a * r) / (w * r);
        }
      }
      return Eigen::Matrix<T, 2, 1>(s * x, s * y);
    }
  }
  return Eigen::Matrix<T, 2, 1>(x, y);
}

// D and its Jacobians (double): J_md_m = dD/d(x, y) (2x2), J_md_d = dD/dd (2x5; zero columns for
// coefficients a model does not use). Outputs optional (nullptr).
void DistortWithJacobians(DistortionModel model,
                          const DistortionCoeffs& d,
                          double x,
                          double y,
                          Eigen::Vector2d* md,
                          Eigen::Matrix2d* J_md_m,
                          Eigen::Matrix<double, 2, kNumDistortionCoeffs>* J_md_d);

// m with D(m; d) = md (file comment); false when the iteration fails or md lies beyond the model's
// invertible range (equidistant theta >= pi/2, fov w r_d >= pi/2). The caller checks the result.
bool Undistort(DistortionModel model,
               const DistortionCoeffs& d,
               const Eigen::Vector2d& md,
               Eigen::Vector2d* m);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_DISTORTION_H_
