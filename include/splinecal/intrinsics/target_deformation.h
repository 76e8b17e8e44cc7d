// The calibration target's out-of-plane shape, estimated with the intrinsics (an option of
// `splinecal intrinsics`; docs/intrinsics.md, "Is the target flat?").
//
// A printed target glued to a board bows by a millimetre or more; a model that takes it as flat
// biases the focal length and principal point by an amount that depends on each view's distance
// and tilt (Strobl & Hirzinger, "More accurate pinhole camera calibration with imperfect planar
// target", ICCV workshops 2011, estimate the target's geometry with the camera; OpenCV's
// calibrateCameraRO does it point by point). Here the shape is a smooth surface shared by every
// view, so it adds 3 or 7 unknowns whatever the number of corners:
//
//   p_t = (x, y, 0)  ->  (x, y, h(x, y)),   h = sum_k c_k b_k(s, t) [m],
//   s = (x - x0) / a,  t = (y - y0) / a
//
// with (x0, y0) the centre of the target's points and a half the larger side of their bounding
// box (s, t within [-1, 1]), so c_k is a height in metres at the target's edge.
//   quadratic: b = (s^2, s t, t^2)                          3 coefficients
//   cubic:     b = (s^2, s t, t^2, s^3, s^2 t, s t^2, t^3)  7 coefficients
// Gauge: the constant, s and t terms are left out: every view's pose absorbs them (a shift along
// the target's normal and a tilt), and with them the problem would be singular. h is therefore
// defined relative to the plane tangent to the surface at the centre; what the data determine is
// the surface up to a plane, and the report gives it relative to the least-squares plane through
// the target's points (TargetDeformationHeights), which no choice of gauge changes.
#ifndef SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_
#define SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/estimation/reprojection_cost.h"

namespace splinecal {

enum class TargetDeformationKind { kNone, kQuadratic, kCubic };

inline constexpr int kMaxTargetDeformationSize = 7;

// "none", "quadratic", "cubic".
const char* TargetDeformationName(TargetDeformationKind kind);

// The number of coefficients c_k: 0, 3 or 7.
int TargetDeformationSize(TargetDeformationKind kind);

// The surface's basis on one target: its kind and the normalisation (x0, y0, a).
struct TargetShape {
  TargetDeformationKind kind = TargetDeformationKind::kNone;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // (x0, y0) [m]
  double half_extent = 1.0;                          // a [m]

  int size() const { return TargetDeformationSize(kind); }
  // The basis values b_k at target point (x, y), the first size() entries used.
  Eigen::Matrix<double, kMaxTargetDeformationSize, 1> Basis(double x, double y) const;
  // The point (x, y, z + h(x, y)) for coefficients c (size() of them).
  Eigen::Vector3d Deform(const Eigen::Vector3d& p_t, const double* c) const;
};

// The normalisation of `target`'s points (the centre and half the larger side of their bounding
// box); throws splinecal::Error for a target whose points are not all at z = 0.
TargetShape MakeTargetShape(const CalibrationTarget& target, TargetDeformationKind kind);

// The corners with their target points moved onto the surface c (a copy; the pixels unchanged).
std::vector<TargetCornerObservation> DeformedCorners(
    const std::vector<TargetCornerObservation>& corners, const TargetShape& shape,
    const double* c);

// The surface relative to the least-squares plane through the target's points, at its centre
// and its four corners (the bounding box's: (-a, -a), (a, -a), (a, a), (-a, a) from the
// centre), as a linear map of c: heights = M c [m], so that their covariance is M C M^T.
struct TargetDeformationHeights {
  std::vector<std::string> names;  // "centre", "corner_-x-y", "corner_+x-y", ...
  std::vector<Eigen::Vector2d> xy;  // where, target frame [m]
  Eigen::MatrixXd M;                // rows: names; columns: the shape's coefficients
};
TargetDeformationHeights MakeTargetDeformationHeights(const CalibrationTarget& target,
                                                      const TargetShape& shape);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_
