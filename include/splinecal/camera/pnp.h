// Pose of a calibration target in the camera from one image (perspective-n-point), the initial
// guess of `splinecal calibrate`'s target poses.
//
//   1. Every pixel is unprojected to its unit bearing b (camera/camera_model.h,
//      UnprojectToBearing), so the closed form is free of the camera model and works for
//      wide-angle (> 180 degree) cameras as for pinhole ones. A pixel without a bearing (noise
//      can push a corner seen at a fisheye's rim beyond the image of the model's valid region)
//      is left out of the closed form and kept in the refinement.
//   2. Closed form. Planar targets (every point at z = 0): the homography H ~ [r1 r2 t] from
//      (X, Y, 1) to b by the direct linear transform b x (H a) = 0 (Hartley's scaling of the
//      target points; unit bearings need none; smallest right singular vector), then
//      R = closest rotation to [r1 r2 r1 x r2] (SVD), t = h3 / mean(|h1|, |h2|), the sign chosen
//      so that the points lie along their bearings, sum_i b_i . (H a_i) > 0 [Zhang00].
//      Non-planar targets: the 3x4 projection [R | t] by the same DLT on (X, Y, Z, 1), R the
//      closest rotation to its left block, the scale from its singular values, the same sign
//      rule. A nearly flat one (a board whose points were measured or refined, up to a tenth of
//      its extent off its least-squares plane) also gets the planar form on that plane, with the
//      points' distances from it ignored: the DLT needs depth that such a target barely has.
//   3. Levenberg-Marquardt on the pixel reprojection error (distortion included) over T_c_t with
//      the RIGHT perturbation T_c_t Exp(d): d x_c / d d = R_c_t [I, -[p_t]x], from each
//      closed-form candidate; the lowest sum of squares wins.
// Rolling shutter is ignored here (the calibration models it); the result is an initial guess.
//
// References: [Zhang00] Z. Zhang, "A flexible new technique for camera calibration", PAMI 2000;
// [Hartley04] R. Hartley, A. Zisserman, Multiple View Geometry, 2nd ed. (normalised DLT).
#ifndef SPLINECAL_CAMERA_PNP_H_
#define SPLINECAL_CAMERA_PNP_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

struct PnpOptions {
  int max_iterations = 30;
  // A planar target needs at least 4 points, a non-planar one at least 6; more are required for
  // a pose worth using (detector noise averages out): min_points.
  int min_points = 6;
};

struct PnpResult {
  bool ok = false;
  std::string message;  // why it failed, in words
  SE3d T_c_t;           // target pose in the camera
  double rms_px = 0.0;  // RMS of the 2-D pixel error norms after refinement [px]
  int iterations = 0;
};

// p_t[i] (target frame) is seen at uv[i]. Returns ok = false with a message for too few
// points (or too few whose pixels unproject), degenerate geometry (collinear points, singular
// DLT) or a closed-form pose that puts points outside the camera model's valid region.
PnpResult SolvePnp(const Camera& camera,
                   const std::vector<Eigen::Vector3d>& p_t,
                   const std::vector<Eigen::Vector2d>& uv,
                   const PnpOptions& options = PnpOptions());

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_PNP_H_
