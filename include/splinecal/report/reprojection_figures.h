// The reprojection-error figures of `splinecal calibrate`'s report.html
// (report/calibrate_report.h), one colour per camera:
//
//   ReprojectionErrorFigure  the errors (predicted - observed) as a u/v scatter, and their norm
//                            over time.
//   ReprojectionImageFigure  per camera, where in the image the errors are: every observed corner
//                            (decimated) coloured by its error's size, plus the mean error of each
//                            cell of a grid over the image drawn as a magnified arrow, and the
//                            image's outline (the panel shows a margin around it). Noise
//                            averages out in a cell's mean; a model that does not fit a region of
//                            the image (distortion, intrinsics, rolling shutter) leaves long,
//                            aligned vectors there.
#ifndef SPLINECAL_REPORT_REPROJECTION_FIGURES_H_
#define SPLINECAL_REPORT_REPROJECTION_FIGURES_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/plot/svg_plot.h"

namespace splinecal {

// What the figures draw: each camera's image size (0 x 0: the extent of its observations) and
// the errors (not owned).
struct ReprojectionData {
  std::vector<Eigen::Vector2i> image_sizes;
  const std::vector<ReprojectionSample>* samples = nullptr;
  int64_t t0_ns = 0;  // time zero of the plots over time
  std::string time_label = "time [s] (IMU spline)";  // x axis of the error norm over time
  // ReprojectionErrorFigure: a scatter and a norm-over-time panel per camera (else every camera
  // in one pair of panels, one colour each).
  bool one_panel_per_camera = false;
  // MakeReprojectionImageFigure: > 0 draws the arrows at this magnification (figures that must
  // compare, e.g. one per camera model) instead of the automatic one.
  double vector_gain = 0.0;
};
ReprojectionData ReprojectionDataOf(const CalibrationResult& result);

// The colour of camera `cam_id` in every reprojection figure ("#rrggbb").
std::string CameraColor(int cam_id);

// At most max_points points per camera and series (evenly decimated).
plot::Figure ReprojectionErrorFigure(const ReprojectionData& data, int max_points);

// Bounds [px] of the error-size classes of ReprojectionImageFigure: |error| below the first, from
// the first to the second, ..., and at least the last.
inline constexpr double kErrorClassBoundsPx[] = {0.5, 1.0, 2.0, 5.0};

struct ReprojectionImageFigure {
  plot::Figure figure;
  // The factor the cell mean errors are drawn magnified by: a 1-2-5 step chosen so that 90% of
  // them span at most 0.8 cell (the longest, when fewer than 10% are not 0; 1 when all are 0).
  double vector_gain = 1.0;
  // The key under the figure (HTML): the colours of the classes and the vectors' gain.
  std::string key_html;
};

// Cells of about 1/12 of the image width, square; a cell needs kMinCellObservations
// observations for its mean to be drawn. Image size from each camera's resolution (the data's
// extent when it has none).
inline constexpr int kImageCellsAcross = 12;
inline constexpr int kMinCellObservations = 10;
ReprojectionImageFigure MakeReprojectionImageFigure(const ReprojectionData& data,
                                                    int max_points);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_REPROJECTION_FIGURES_H_
