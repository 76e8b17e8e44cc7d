// Reading a tag's code bits where its four corners say it is (private to src/detect/): the check
// that confirms a tag the grid predicts (detect/grid_prediction.h) when libapriltag's own quad
// search missed it.
#ifndef SPLINECAL_SRC_DETECT_TAG_CODE_H_
#define SPLINECAL_SRC_DETECT_TAG_CODE_H_

#include <opencv2/core.hpp>

#include "grid_tag.h"

struct apriltag_family;

namespace splinecal {

// The number of code bits of `tag` (its id and 4 corners in `image`, CV_8UC1) that differ from
// its id's code in `family`, read as libapriltag reads them: each cell of the family's bit grid
// sampled at its centre (bilinear), sharpened by `sharpening` times the cell's 4-neighbour
// Laplacian (libapriltag's decode_sharpening), and called white above the midpoint between the
// tag's black border and the white just outside it. -1 when a sample leaves the image or the
// border is not darker than the white around it.
int TagCodeErrors(const apriltag_family& family, const cv::Mat& image, const GridTag& tag,
                  double sharpening);

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_TAG_CODE_H_
