// Tags of a Kalibr AprilGrid that the grid's found tags predict (private to src/detect/).
//
// libapriltag must first find a tag's outline (a quad) before it reads the code. On tags under
// ~20 px, or narrower than that when seen obliquely, the outline is what fails: the white grown
// to cut the tags from their corner squares (aprilgrid_detector.cc) eats their black border, and
// without it the border joins the corner squares. The grid knows where such a tag must be: the
// homography of its found neighbours (a few tag sides away), fitted through the frame's lens
// model (division_model.h: a fisheye bends even that short way by pixels), places its 4 corners,
// the saddle fit (detect/saddle_point.h) moves them onto the X-junctions by at most half the
// small square beside them,
// and the tag is kept only when the code read inside those corners is its own id's within a few
// bits (detect/tag_code.h). The geometry names the id and the code confirms it, so the few bit
// errors that libapriltag would refuse from a lone quad cannot give a wrong id: tag36h11's codes
// differ in 11 bits or more, and a neighbour's code is never within kMaxPredictedCodeErrors.
#ifndef SPLINECAL_SRC_DETECT_GRID_PREDICTION_H_
#define SPLINECAL_SRC_DETECT_GRID_PREDICTION_H_

#include <vector>

#include <opencv2/core.hpp>

#include "division_model.h"
#include "grid_tag.h"
#include "splinecal/camera/target.h"
#include "splinecal/detect/saddle_point.h"

struct apriltag_family;

namespace splinecal {

// Saddle refinement at the scale of tags `side` px wide: a window of a twentieth of the side
// (2 px for EuRoC's 40 px tags), inside half of the small square between tags, and a blur of
// 0.75 of the window but at most an eighth of the small square's side.
SaddleOptions SaddleOptionsForTags(const CalibrationTarget& target, double side);

// Adds to `tags` (tags found and kept, each id once) every missing tag of the grid that a found
// tag within 2 grid steps places wholly inside `image` (CV_8UC1), whose 4 corners the saddle fit
// confirms and whose code read there is its id's within kMaxPredictedCodeErrors bits. Repeats
// from the tags it added until none is added. Returns how many it added.
// `lens` is the frame's (division_model.h).
int AddPredictedTags(const CalibrationTarget& target, const apriltag_family& family,
                     const cv::Mat& image, double sharpening, const DivisionModel& lens,
                     std::vector<GridTag>* tags);

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_GRID_PREDICTION_H_
