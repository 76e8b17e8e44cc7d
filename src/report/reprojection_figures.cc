#include "splinecal/report/reprojection_figures.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "splinecal/plot/plot_decimation.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

// Cameras take these in order (then repeat): distinct from the classes' colours below.
const char* const kCameraColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b"};
constexpr int kNumCameraColors = sizeof(kCameraColors) / sizeof(kCameraColors[0]);
// Error-size classes, small to large (one more than kErrorClassBoundsPx): light colours for the
// bulk, then increasingly alarming ones, drawn in this order so that large errors stay on top.
const char* const kClassColors[] = {"#d9d9d9", "#9ecae1", "#fd8d3c", "#e31a1c", "#54278f"};
constexpr int kNumClasses = sizeof(kClassColors) / sizeof(kClassColors[0]);
static_assert(kNumClasses == sizeof(kErrorClassBoundsPx) / sizeof(kErrorClassBoundsPx[0]) + 1);
// Black and drawn last, over the light points: the vectors are what to look at.
constexpr char kVectorColor[] = "#000000";
// The magnification of the cell means stays within these (a mean of 1e-6 px is not worth a
// million-fold arrow; one of 100 px is drawn shortened).
constexpr double kMinGain = 1e-3;
constexpr double kMaxGain = 1e3;
constexpr double kLongestVectorCells = 0.8;
// The gain is set by this quantile of the cells' mean errors, not by the longest one: a few cells
// at the image border with large errors would otherwise shrink every other vector to a dot (they
// are drawn longer than a cell instead, clipped at the plot's edge).
constexpr double kGainQuantile = 0.9;
// The image drawn with a margin of this share of its width on every side.
constexpr double kImageMarginRatio = 0.04;
// Arrowheads: barbs at this angle to the shaft, this share of its length, at most this share of
// a cell (a long vector keeps a head of readable size).
constexpr double kArrowheadDeg = 25.0;
constexpr double kArrowheadRatio = 0.3;
constexpr double kArrowheadCells = 0.25;
constexpr char kOutlineColor[] = "#555555";

int NumCameras(const ReprojectionData& r) {
  int n = static_cast<int>(r.image_sizes.size());
  for (const ReprojectionSample& s : (*r.samples)) n = std::max(n, s.cam_id + 1);
  return n;
}

// The samples of each camera, by index.
std::vector<std::vector<size_t>> SamplesPerCamera(const ReprojectionData& r) {
  std::vector<std::vector<size_t>> per_camera(NumCameras(r));
  for (size_t k = 0; k < (*r.samples).size(); ++k) {
    const int cam = (*r.samples)[k].cam_id;
    if (cam >= 0) per_camera[cam].push_back(k);
  }
  return per_camera;
}

// The largest 1, 2 or 5 x 10^k not above `value` (> 0).
double FloorToStep(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  const double mantissa = value / decade;
  return (mantissa >= 5.0 ? 5.0 : mantissa >= 2.0 ? 2.0 : 1.0) * decade;
}

std::string ClassLabel(int k) {
  if (k == 0) return StringPrintf("< %g px", kErrorClassBoundsPx[0]);
  if (k == kNumClasses - 1) return StringPrintf(">= %g px", kErrorClassBoundsPx[k - 1]);
  return StringPrintf("%g to %g px", kErrorClassBoundsPx[k - 1], kErrorClassBoundsPx[k]);
}

int ClassOf(double error_px) {
  int k = 0;
  while (k < kNumClasses - 1 && error_px >= kErrorClassBoundsPx[k]) ++k;
  return k;
}

// The image size of camera `cam` [px]: its resolution, or the extent of its observations.
Eigen::Vector2d ImageSize(const ReprojectionData& r, int cam, const std::vector<size_t>& samples) {
  if (cam < static_cast<int>(r.image_sizes.size()) && r.image_sizes[cam].minCoeff() > 0) {
    return r.image_sizes[cam].cast<double>();
  }
  Eigen::Vector2d size(1.0, 1.0);
  for (size_t k : samples) size = size.cwiseMax((*r.samples)[k].uv);
  return size;
}

// The mean observed pixel and mean error of one grid cell.
struct CellMean {
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
  Eigen::Vector2d error = Eigen::Vector2d::Zero();
  int count = 0;
};

std::vector<CellMean> CellMeans(const ReprojectionData& r,
                                const std::vector<size_t>& samples,
                                const Eigen::Vector2d& image_size) {
  const double cell = image_size.x() / kImageCellsAcross;
  const int rows = std::max(1, static_cast<int>(std::ceil(image_size.y() / cell)));
  std::vector<CellMean> cells(static_cast<size_t>(kImageCellsAcross) * rows);
  for (size_t k : samples) {
    const ReprojectionSample& s = (*r.samples)[k];
    const int col = std::clamp(static_cast<int>(s.uv.x() / cell), 0, kImageCellsAcross - 1);
    const int row = std::clamp(static_cast<int>(s.uv.y() / cell), 0, rows - 1);
    CellMean& c = cells[static_cast<size_t>(row) * kImageCellsAcross + col];
    c.uv += s.uv;
    c.error += s.error;
    ++c.count;
  }
  std::vector<CellMean> kept;
  for (CellMean& c : cells) {
    if (c.count < kMinCellObservations) continue;
    c.uv /= c.count;
    c.error /= c.count;
    kept.push_back(c);
  }
  return kept;
}

}  // namespace

ReprojectionData ReprojectionDataOf(const CalibrationResult& result) {
  ReprojectionData data;
  for (const CameraEstimate& camera : result.cameras) {
    data.image_sizes.emplace_back(camera.calibration.camera.width,
                                  camera.calibration.camera.height);
  }
  data.samples = &result.reprojection_samples;
  data.t0_ns = result.layout.t0_ns;
  return data;
}

std::string CameraColor(int cam_id) {
  return kCameraColors[((cam_id % kNumCameraColors) + kNumCameraColors) % kNumCameraColors];
}

plot::Figure ReprojectionErrorFigure(const ReprojectionData& r, int max_points) {
  plot::Figure figure;
  figure.title = "Reprojection errors (predicted - observed)";
  figure.columns = 2;
  const std::vector<std::vector<size_t>> per_camera = SamplesPerCamera(r);
  plot::Panel* scatter = nullptr;
  plot::Panel* over_time = nullptr;
  for (size_t cam = 0; cam < per_camera.size(); ++cam) {
    if (scatter == nullptr || r.one_panel_per_camera) {
      const std::string prefix = r.one_panel_per_camera ? "cam" + std::to_string(cam) + ": " : "";
      scatter = &plot::AddPanel(&figure, prefix + "error scatter", "u error [px]", "v error [px]");
      scatter->equal_aspect = true;
      over_time =
          &plot::AddPanel(&figure, prefix + "error norm over time", r.time_label, "|error| [px]");
    }
    plot::Series& points = scatter->series.emplace_back();
    plot::Series& norms = over_time->series.emplace_back();
    for (plot::Series* series : {&points, &norms}) {
      series->label = "cam" + std::to_string(cam);
      series->color = CameraColor(static_cast<int>(cam));
      series->line = false;
      series->marker = plot::Marker::kCircle;
      series->marker_size = 1.2;
    }
    for (size_t i : plot::DecimatedIndices(per_camera[cam].size(), max_points, false)) {
      const ReprojectionSample& s = (*r.samples)[per_camera[cam][i]];
      points.x.push_back(s.error.x());
      points.y.push_back(s.error.y());
      norms.x.push_back(NanosecondsToSeconds(s.t_ns - r.t0_ns));
      norms.y.push_back(s.error.norm());
    }
  }
  return figure;
}

ReprojectionImageFigure MakeReprojectionImageFigure(const ReprojectionData& r, int max_points) {
  ReprojectionImageFigure out;
  plot::Figure& figure = out.figure;
  figure.title = "Reprojection errors by image position";
  figure.columns = 2;
  figure.panel_width = 480.0;
  figure.panel_height = 360.0;
  const std::vector<std::vector<size_t>> per_camera = SamplesPerCamera(r);
  // One gain for all cameras, so that their vectors compare.
  std::vector<std::vector<CellMean>> cells(per_camera.size());
  std::vector<Eigen::Vector2d> sizes(per_camera.size());
  std::vector<double> lengths_cells;  // every cell's mean error, in cells of its camera
  for (size_t cam = 0; cam < per_camera.size(); ++cam) {
    sizes[cam] = ImageSize(r, static_cast<int>(cam), per_camera[cam]);
    cells[cam] = CellMeans(r, per_camera[cam], sizes[cam]);
    const double cell = sizes[cam].x() / kImageCellsAcross;
    for (const CellMean& c : cells[cam]) lengths_cells.push_back(c.error.norm() / cell);
  }
  if (r.vector_gain > 0.0) {
    out.vector_gain = r.vector_gain;
  } else if (!lengths_cells.empty()) {
    std::sort(lengths_cells.begin(), lengths_cells.end());
    double reference =
        lengths_cells[static_cast<size_t>(kGainQuantile * (lengths_cells.size() - 1))];
    if (!(reference > 0.0)) reference = lengths_cells.back();  // most cells without a mean error
    if (reference > 0.0 && std::isfinite(reference)) {
      out.vector_gain =
          std::clamp(FloorToStep(kLongestVectorCells / reference), kMinGain, kMaxGain);
    }
  }
  for (size_t cam = 0; cam < per_camera.size(); ++cam) {
    plot::Panel& panel =
        plot::AddPanel(&figure, "cam" + std::to_string(cam), "u [px]", "v [px] (down)");
    // A margin around the image, so that its outline shows and vectors that leave the image
    // are drawn up to the panel's edge (the plot clips there).
    const double margin = kImageMarginRatio * sizes[cam].x();
    panel.x.min = -margin;
    panel.x.max = sizes[cam].x() + margin;
    panel.y.min = -margin;
    panel.y.max = sizes[cam].y() + margin;
    panel.y.reversed = true;
    panel.equal_aspect = true;
    panel.grid = false;
    panel.legend = plot::LegendPosition::kNone;  // the key is under the figure
    std::vector<plot::Series*> classes;
    for (int k = 0; k < kNumClasses; ++k) {
      plot::Series& series = panel.series.emplace_back();
      series.color = kClassColors[k];
      series.line = false;
      series.marker = plot::Marker::kCircle;
      series.marker_size = k < 2 ? 0.9 : 1.5;
      classes.push_back(&series);
    }
    for (size_t i : plot::DecimatedIndices(per_camera[cam].size(), max_points, false)) {
      const ReprojectionSample& s = (*r.samples)[per_camera[cam][i]];
      plot::Series* series = classes[ClassOf(s.error.norm())];
      series->x.push_back(s.uv.x());
      series->y.push_back(s.uv.y());
    }
    // Each cell's vector from its mean pixel, the segments separated by NaN (a broken line).
    plot::Series& vectors = panel.series.emplace_back();
    vectors.color = kVectorColor;
    vectors.line_width = 1.6;
    plot::Series& origins = panel.series.emplace_back();
    origins.color = kVectorColor;
    origins.line = false;
    origins.marker = plot::Marker::kCircle;
    origins.marker_size = 1.3;
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    // Arrowheads: two barbs at each tip, kArrowheadDeg off the shaft, kArrowheadRatio of its
    // length but at most kArrowheadCells of a cell (a broken line, like the vectors).
    plot::Series& heads = panel.series.emplace_back();
    heads.color = kVectorColor;
    heads.line_width = 1.6;
    const double cell = sizes[cam].x() / kImageCellsAcross;
    for (const CellMean& c : cells[cam]) {
      const Eigen::Vector2d tip = c.uv + out.vector_gain * c.error;
      vectors.x.insert(vectors.x.end(), {c.uv.x(), tip.x(), kNaN});
      vectors.y.insert(vectors.y.end(), {c.uv.y(), tip.y(), kNaN});
      origins.x.push_back(c.uv.x());
      origins.y.push_back(c.uv.y());
      const Eigen::Vector2d shaft = tip - c.uv;
      const double length = shaft.norm();
      if (!(length > 0.0) || !std::isfinite(length)) continue;
      const double barb = std::min(kArrowheadRatio * length, kArrowheadCells * cell);
      const Eigen::Vector2d back = -shaft / length * barb;
      const Eigen::Rotation2Dd turn(kArrowheadDeg * kPi / 180.0);
      const Eigen::Vector2d left = tip + turn * back;
      const Eigen::Vector2d right = tip + turn.inverse() * back;
      heads.x.insert(heads.x.end(), {left.x(), tip.x(), right.x(), kNaN});
      heads.y.insert(heads.y.end(), {left.y(), tip.y(), right.y(), kNaN});
    }
    // The image's outline.
    plot::Series& outline = panel.series.emplace_back();
    outline.color = kOutlineColor;
    outline.line_width = 1.0;
    outline.x = {0.0, sizes[cam].x(), sizes[cam].x(), 0.0, 0.0};
    outline.y = {0.0, 0.0, sizes[cam].y(), sizes[cam].y(), 0.0};
  }
  std::string key = "<p>Points: observed corners (at most " + std::to_string(max_points) +
                    " per camera) by |error|:";
  for (int k = 0; k < kNumClasses; ++k) {
    key += std::string(" <span style=\"color:") + kClassColors[k] + "\">&#9679;</span> " +
           plot::EscapeXml(ClassLabel(k)) + (k + 1 < kNumClasses ? "," : ".");
  }
  key += StringPrintf(
      " <span style=\"color:%s\">Arrows</span>: the mean error (predicted - observed) of each "
      "cell of 1/%d image width with at least %d corners, magnified x%g (from the dot at the "
      "cell's mean corner; the factor makes 90%% of them shorter than 0.8 cell). Noise averages "
      "out; long aligned arrows show a region the camera model does not fit. The grey rectangle "
      "is the image's outline.</p>\n",
      kVectorColor,
      kImageCellsAcross,
      kMinCellObservations,
      out.vector_gain);
  out.key_html = key;
  return out;
}

}  // namespace splinecal
