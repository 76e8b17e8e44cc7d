// Corners outside the image: a wrong image size (--resolution 640x480 for a 752 x 480 camera, a
// camchain of another camera) calibrates without complaint, to a principal point in the wrong
// place and a wrong `resolution` in the written camchain. A detector finds corners only inside
// the image: under the pixel convention (docs/conventions.md, "Pixels": pixel centres at
// integers, the image spans [-0.5, w - 0.5] x [-0.5, h - 0.5]) a corner further out than
// kImageBoundsTolerancePx is impossible for that size.
#ifndef SPLINECAL_CAMERA_IMAGE_BOUNDS_CHECK_H_
#define SPLINECAL_CAMERA_IMAGE_BOUNDS_CHECK_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"

namespace splinecal {

// How far beyond the image border a corner may lie [px]: sub-pixel refinement moves a corner by
// well under a pixel, a wrong size by tens to hundreds.
constexpr double kImageBoundsTolerancePx = 1.0;

// The corners of one camera against its image size.
struct ImageBoundsSummary {
  int64_t corners = 0;
  int64_t outside = 0;                                 // beyond the tolerance
  Eigen::Vector2d min_uv = Eigen::Vector2d::Zero();    // smallest u and v seen
  Eigen::Vector2d max_uv = Eigen::Vector2d::Zero();    // largest u and v seen
  Eigen::Vector2i smallest_fitting_size = Eigen::Vector2i::Zero();  // [w h] holding them all
};

// One summary per camera (cameras[n] is cam_id n; observations of other ids are not counted).
std::vector<ImageBoundsSummary> SummariseImageBounds(const std::vector<Observation>& observations,
                                                     const std::vector<Camera>& cameras);

// Throws splinecal::Error, one line, for the first camera with a corner outside its image:
// names `observations_name`, the camera, how many corners, the largest u and v and the size
// that would hold them; `size_source` says where the size came from ("--resolution",
// "camchain.yaml"). Cameras with width or height 0 (size unknown) are not checked.
void CheckCornersInsideImages(const std::vector<Observation>& observations,
                              const std::vector<Camera>& cameras,
                              const std::string& observations_name = "observations",
                              const std::string& size_source = "the camera model");

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_IMAGE_BOUNDS_CHECK_H_
