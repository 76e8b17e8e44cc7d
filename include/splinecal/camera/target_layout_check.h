// Does the target file describe the board the corners were detected on? A wrong tagCols (a 7 x 7
// grid file for a 6 x 6 board) or tagSpacing still lets a calibration converge, to a confident
// wrong answer (RMS 82 px, fx 14,344 instead of 458 on EuRoC imu_april), so the check decides
// from the board's geometry alone, before any camera model or solve, and independent of the lens:
//
// A cell is 2 x 2 corners of the grid the ids number: an AprilGrid tag (its 4 corners), or a
// checkerboard square pair at even (row, col). Its 4 image corners fix the homography H from the
// cell's own plane coordinates (corners at (0,0), (1,0), (1,1), (0,1), in cell sides) to the
// image; H^-1 carries the corners of the next cell to the right (2 grid columns on) and the next
// cell up into the cell's plane, where the grid puts them at
//     x = 1 + s + b,  y = a       (right neighbour, its corner (a, b))
//     y = 1 + s + a,  x = b       (up neighbour)
// s being the AprilGrid's tagSpacing ratio (checkerboard: s = 1, the squares touch). Over one
// such short step even a fisheye's distortion bends the plane very little, so with the right
// numbering every sample's "along" offset (x - 1 - b, resp. y - 1 - a) is s and its "across"
// offset (y - a, resp. x - b) is 0, up to the corner noise. With a wrong column count the ids map
// to corners elsewhere on the board: cells come out degenerate or the neighbours land whole tag
// sides away, and the "along" offsets of the two directions disagree (a grid of twice the
// columns numbers every second row as the next one). The measured s is the board's spacing ratio
// (the homography is in units of the tag's own side, so s does not depend on the one the file
// gives). Measurements (docs/reliability.md): EuRoC imu_april, 6 x 6 tags, tagSpacing 0.3.
//
// What cannot be judged from pixels: a metric tagSize or checkerboard square size (a homography
// has no scale; calibrate judges it against the IMU), a checkerboard's row-to-column spacing
// ratio (a homography absorbs it), a tagRows or targetRows larger than the board (its extra ids
// are never seen, harmless), and `points` targets (no grid).
#ifndef SPLINECAL_CAMERA_TARGET_LAYOUT_CHECK_H_
#define SPLINECAL_CAMERA_TARGET_LAYOUT_CHECK_H_

#include <string>
#include <vector>

#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"

namespace splinecal {

// One numbering of the ids: id = row * corner_cols + col.
struct GridLayout {
  bool aprilgrid = true;  // false: checkerboard (s = 1)
  int corner_cols = 0;    // aprilgrid: 2 tagCols; checkerboard: targetCols
};

// How well the corners fit one GridLayout.
struct GridLayoutFit {
  int samples = 0;  // neighbour corners predicted (failed predictions included)
  int failed = 0;   // of them: degenerate cell or a corner beyond the cell's horizon
  // Per direction the median of |(along - s_dir, across)| [cell sides] (a failed prediction
  // counts as infinite), the larger of the two directions.
  double residual = 0.0;
  // Per direction the share of predictions beyond half a cell side or failed, the larger one.
  double gross_fraction = 0.0;
  int directions = 0;            // directions (right, up) with enough predictions to judge
  double spacing_right = 0.0;    // median "along" offset towards the right neighbour
  double spacing_up = 0.0;       // ... towards the upper neighbour
  double spacing = 0.0;          // median over both directions: the board's s
  bool fits = false;  // enough samples, both directions seen, small residual, they agree
};

// Evaluates `layout` on up to kMaxFrames frames spread over the observations. Observations whose
// id is negative are ignored.
GridLayoutFit FitGridLayout(const std::vector<ObservationFrame>& frames, const GridLayout& layout);

// The frames the check uses: the observations whose id `target` has (other ids are landmarks or
// are reported by the calibration itself), grouped, at most kMaxFrames spread evenly over them.
std::vector<ObservationFrame> LayoutCheckFrames(const std::vector<Observation>& observations,
                                                const CalibrationTarget& target);

// Throws splinecal::Error, one line naming `observations_name` and `target_name`, when the
// corners contradict an aprilgrid's or checkerboard's column count or an aprilgrid's tagSpacing,
// with the layout the corners do fit, if any. Silent for `points` targets and when too few
// neighbouring cells are seen to judge.
void CheckTargetLayout(const std::vector<Observation>& observations,
                       const CalibrationTarget& target,
                       const std::string& observations_name = "observations",
                       const std::string& target_name = "the target");

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_TARGET_LAYOUT_CHECK_H_
