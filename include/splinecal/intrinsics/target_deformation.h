// The calibration target's geometry as printed, estimated with the intrinsics (an option of
// `splinecal intrinsics`; docs/intrinsics.md, "Is the target flat?"): its out-of-plane shape, or
// its in-plane layout.
//
// Out of plane. A printed target glued to a board bows by a millimetre or more; a model that
// takes it as flat biases the focal length and principal point by an amount that depends on each
// view's distance and tilt (Strobl & Hirzinger, "More accurate pinhole camera calibration with
// imperfect planar target", ICCV workshops 2011, estimate the target's geometry with the camera;
// OpenCV's calibrateCameraRO does it point by point). Here the shape is a smooth surface shared by
// every view, so it adds 3 or 7 unknowns whatever the number of corners:
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
//
// In plane (AprilGrid only). A printer scales the sheet's two axes differently (0.1-1%), the sheet
// shears, and the printed tags may be larger or smaller relative to their pitch than the file
// says. With u = (x - x0, y - y0) the point's offset from the target's centre and o its offset
// from the centre of its own tag (every corner is a tag's corner, camera/target.h), the
// coefficients c = (e1, e2, d), all ratios, move the point within the plane:
//
//   x -> x + e1 u_x + e2 u_y + d o_x,   y -> y - e1 u_y + e2 u_x + d o_y
//
//   e1: anisotropy, x longer by 1 + e1 and y by 1 - e1 (the x/y scale ratio is 1 + 2 e1);
//   e2: pure shear, the diagonals x = y and x = -y longer by 1 + e2 and 1 - e2;
//   d:  every tag's side longer by 1 + d, its centre (the pitch) held: the printed tagSize /
//       pitch is (1 + d) times the file's.
// Gauge: of the 6 parameters of an affine map of the plane, each view's pose absorbs 4: a
// translation in the plane and a rotation about its normal directly, and a uniform scale because
// the target scaled by k seen at k times the distance projects alike (with several cameras the
// extrinsics' translations scale with it; with extrinsics held, the baseline would fix the scale,
// but the model keeps the file's pitch as the scale all the same). The two left, the traceless
// symmetric part [e1 e2; e2 -e1], are not absorbed by any pose: a view's pose moves the target
// rigidly. A simple shear x -> x + g y is e2 = g / 2 and a rotation by -g / 2. The tag side alone
// with the pitch held (d) is not an affine map of the plane, so no pose absorbs it either; a pitch
// changed with the tag side held is the same as d up to the uniform scale. The map is the
// linearisation (second-order terms such as e1 d dropped): exact enough for ratios of 1e-2.
//
// In plane, with a per-view inset ("in-plane-per-view"). On EuRoC d is not one number: views
// turning at 18 deg/s give d = -0.83 +- 0.10 %, at 82 deg/s -1.56 +- 0.13 % (docs/intrinsics.md,
// "In-plane layout"): motion blur pulls each detected corner toward its tag's centre, a property
// of the detection in each image, not of the print. This kind keeps (e1, e2) shared by every view
// (the print; c has 2 coefficients) and gives each timestamp its own inset d_v, the d column of D
// above (kInsetColumn) in a 1-coefficient block per timestamp (the cameras of a rig see the same
// motion). A d_v is not absorbed by its view's pose: a pose scales the target about the board's
// origin (the uniform scale of the gauge above, at the view's own distance), d_v every tag about
// its own centre, and the tags' centres stay where the pose puts them; so each view's tags, 4
// corners apiece, determine it, and the intrinsics lose only the information d_v and the pose
// share (docs/intrinsics.md, "A per-view corner inset", measures how little).
//
// Every point free ("points"). Each target point gets its own offset c_i (3 coefficients, its own
// parameter block): p_i -> p_i + c_i, D = I. This is the free target of photogrammetry (OpenCV's
// calibrateCameraRO, Strobl & Hirzinger 2011): it takes whatever the print, the board and the
// detector do to each corner's mean position, where the kinds above take only a smooth surface or
// an affine layout. On EuRoC's imu_april it is what brings the recording's halves together
// (docs/intrinsics.md, "Every point free"). The offsets share 7 directions with the views' poses
// (a rigid motion and a scale of the whole target); the inner constraints of
// intrinsics/target_points_gauge.h fix them: the offsets have no component of a similarity
// transform, so the refined target keeps the file's centroid, orientation and size (least
// squares). Points seen in fewer than kMinViewsPerFreePoint views keep the file's position.
// "points-in-plane" holds every point's z at the file's: a free layout on a flat board (the
// smooth out-of-plane kinds above trade with a lens model's radial terms; see the doc).
#ifndef SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_
#define SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/enum_names.h"
#include "splinecal/estimation/reprojection_cost.h"

namespace splinecal {

enum class TargetDeformationKind {
  kNone,
  kQuadratic,
  kCubic,
  kInPlane,
  kInPlanePerView,
  kPoints,
  kPointsInPlane
};

// A point seen in fewer views keeps the file's position (its offset would rest on too little).
inline constexpr int kMinViewsPerFreePoint = 10;

inline constexpr int kMaxTargetDeformationSize = 7;

// The kinds by name (`splinecal intrinsics --target-deformation`, result.yaml), the default
// first, with the number of shared coefficients c_k each has.
struct TargetDeformationRow {
  TargetDeformationKind value;
  const char* name;
  int size;
};
inline constexpr std::array<TargetDeformationRow, 7> kTargetDeformationKinds = {{
    {TargetDeformationKind::kNone, "none", 0},
    {TargetDeformationKind::kQuadratic, "quadratic", 3},
    {TargetDeformationKind::kCubic, "cubic", 7},
    {TargetDeformationKind::kInPlane, "in-plane", 3},
    {TargetDeformationKind::kInPlanePerView, "in-plane-per-view", 2},
    {TargetDeformationKind::kPoints, "points", 3},
    {TargetDeformationKind::kPointsInPlane, "points-in-plane", 3},
}};

// A target point's displacement per coefficient (TargetShape::Displacement).
using TargetDisplacement = Eigen::Matrix<double, 3, kMaxTargetDeformationSize>;

// "none", "quadratic", "cubic", "in-plane", "in-plane-per-view", "points".
const char* TargetDeformationName(TargetDeformationKind kind);

// The number of shared coefficients c_k: 0, 3, 7, 3 (in-plane) or 2 (in-plane-per-view: e1, e2;
// each view's d_v is its own); points: 3, the size of each point's own block.
int TargetDeformationSize(TargetDeformationKind kind);

// The shared coefficients' names in c's order: out of plane the basis functions' (ss, st, tt;
// cubic + sss, sst, stt, ttt), in plane e1, e2, d (per view e1, e2).
std::vector<std::string> TargetDeformationCoefficientNames(TargetDeformationKind kind);

// The geometry's basis on one target: its kind, the normalisation (x0, y0, a) and, in plane, the
// AprilGrid's layout.
struct TargetShape {
  TargetDeformationKind kind = TargetDeformationKind::kNone;
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // (x0, y0) [m]
  double half_extent = 1.0;                          // a [m]
  double tag_size_m = 0.0;                           // in-plane: a tag's side [m]
  double tag_pitch_m = 0.0;                          // in-plane: tag centre to tag centre [m]

  int size() const { return TargetDeformationSize(kind); }
  // Quadratic or cubic: the coefficients are heights along the target's normal.
  bool out_of_plane() const {
    return kind == TargetDeformationKind::kQuadratic || kind == TargetDeformationKind::kCubic;
  }
  // In plane, the layout's map (header comment) with d shared or per view.
  bool in_plane() const {
    return kind == TargetDeformationKind::kInPlane ||
           kind == TargetDeformationKind::kInPlanePerView;
  }
  // In-plane-per-view: each view has its own inset d_v, column kInsetColumn of Displacement.
  bool per_view_inset() const { return kind == TargetDeformationKind::kInPlanePerView; }
  // Points: every point its own offset block (D = I); in plane, its z held at the file's.
  bool per_point() const {
    return kind == TargetDeformationKind::kPoints || kind == TargetDeformationKind::kPointsInPlane;
  }
  static constexpr int kInsetColumn = 2;
  // The out-of-plane basis values b_k at target point (x, y), the first size() entries used.
  Eigen::Matrix<double, kMaxTargetDeformationSize, 1> Basis(double x, double y) const;
  // The point's displacement per coefficient, D with Deform(p_t, c) = p_t + D c (the first
  // size() columns used): e_z b^T out of plane, the columns of the header's map in plane.
  TargetDisplacement Displacement(const Eigen::Vector3d& p_t) const;
  // The point p_t + D c for coefficients c (size() of them), plus inset D_d d_v with a per-view
  // inset (ignored otherwise).
  Eigen::Vector3d Deform(const Eigen::Vector3d& p_t, const double* c, double inset = 0.0) const;
};

// The normalisation of `target`'s points (the centre and half the larger side of their bounding
// box) and, in plane, its tag size and pitch; throws splinecal::Error for a target whose points
// are not all at z = 0, and in plane for a target that is not an AprilGrid with tags apart
// (tagSpacing > 0, so that each corner has one tag).
TargetShape MakeTargetShape(const CalibrationTarget& target, TargetDeformationKind kind);

// The corners with their target points moved onto the surface c (a copy; the pixels unchanged),
// with a per-view inset by the view's `inset`.
std::vector<TargetCornerObservation> DeformedCorners(
    const std::vector<TargetCornerObservation>& corners,
    const TargetShape& shape,
    const double* c,
    double inset = 0.0);

// The surface relative to the least-squares plane through the target's points, at its centre
// and its four corners (the bounding box's: (-a, -a), (a, -a), (a, a), (-a, a) from the
// centre), as a linear map of c: heights = M c [m], so that their covariance is M C M^T. In
// plane the target stays flat: no names and M with no rows.
struct TargetDeformationHeights {
  std::vector<std::string> names;  // "centre", "corner_-x-y", "corner_+x-y", ...
  std::vector<Eigen::Vector2d> xy;  // where, target frame [m]
  Eigen::MatrixXd M;                // rows: names; columns: the shape's coefficients
};
TargetDeformationHeights MakeTargetDeformationHeights(const CalibrationTarget& target,
                                                      const TargetShape& shape);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TARGET_DEFORMATION_H_
