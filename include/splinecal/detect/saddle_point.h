// Sub-pixel position of an X-junction (a saddle point of the image intensity): where a
// checkerboard's squares meet, or an AprilGrid tag corner touches the small square beside it.
//
// The intensity around the junction, smoothed by a Gaussian of `blur_sigma` px, is fitted in a
// (2 half_window + 1)^2 window, each pixel weighted by exp(-r^2 / (2 half_window^2)), with
//   I(x, y) = a x^2 + b x y + c y^2 + d x + e y + f          (x, y relative to the window centre)
// whose gradient vanishes at the saddle
//   [2a  b ] [x]   [-d]
//   [ b  2c] [y] = [-e],   a saddle when det = 4ac - b^2 < 0.
// The window moves toward the saddle, at most one pixel per step (far from the junction the
// quadratic is a poor model), and the fit repeats until the saddle lies within half a pixel of
// the window's centre: first with a window twice as wide (a start inside a black square sees no
// saddle in the small one), then with the given one. Unlike a gradient-orthogonality refinement (OpenCV's cornerSubPix), the
// fit uses every pixel's intensity, not only those on edges, and is unbiased for a symmetric
// junction under any smoothing. docs/detect.md compares the two on the EuRoC frame.
#ifndef SPLINECAL_DETECT_SADDLE_POINT_H_
#define SPLINECAL_DETECT_SADDLE_POINT_H_

#include <vector>

#include <Eigen/Core>

#include "splinecal/detect/gray_image.h"

namespace splinecal {

struct SaddleOptions {
  double blur_sigma = 1.5;  // [px]
  int half_window = 2;      // [px]
  int max_iterations = 20;
  // A point that moves farther than this from its start [px] is refused: it converged to another
  // junction, or to none.
  double max_shift = 3.0;
};

// Refines every point of `points` in place. Returns one flag per point: true when it converged to
// a saddle inside the image (the window and the blur's support inside it) within max_shift; a
// refused point keeps its input value.
std::vector<bool> RefineSaddlePoints(const GrayImageView& image,
                                     const SaddleOptions& options,
                                     std::vector<Eigen::Vector2d>* points);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_SADDLE_POINT_H_
