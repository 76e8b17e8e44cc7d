#include "grid_prediction.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
}

#include "tag_code.h"

namespace splinecal {
namespace {

// Code bits a predicted tag may have wrong (of 36). Its id comes from the grid, so the code only
// has to confirm it: a tag of another id read there differs from this id's code in at least
// 11 - 4 = 7 of the remaining bits, and a patch that is no tag matches 36 random bits to within 4
// with a probability of about 1e-6. On the resampled EuRoC copies of
// tests/detect/aprilgrid_recall_test.cc, 4 and 6 gave the same 95.9% of the corners of 15-20 px
// tags (6: 59.3% instead of 58.8% of 10-15 px ones), both without a wrong id: 4 keeps the margin.
constexpr int kMaxPredictedCodeErrors = 4;
// A predicted tag narrower than this [px] is not tried: the junctions of its small squares are
// under 3 px apart, and at 8 px two corners of the resampled copies slid onto a neighbouring
// junction (wrong ids in tests/detect/aprilgrid_recall_test.cc); none at 10.
constexpr double kMinPredictedSide = 10.0;
// The saddle refinement's blur is at most the small square's side over this (SaddleOptionsForTags).
constexpr double kSmallSquarePerBlur = 8.0;

}  // namespace

SaddleOptions SaddleOptionsForTags(const CalibrationTarget& target, double side) {
  const double gap = target.tag_spacing_ratio * side;
  SaddleOptions saddle;
  saddle.half_window = std::clamp(static_cast<int>(std::lround(side / 20.0)), 2, 6);
  saddle.half_window = std::max(2, std::min(saddle.half_window, static_cast<int>(0.35 * gap)));
  // The blur at most an eighth of the small square's side: the saddle of a junction blurred
  // wider feels the square's far edges and moves. On tags of 15-20 px, 0.75 of the smallest
  // window (1.5 px) put rendered fisheye corners 0.17 px RMS off; capped, 0.023 px
  // (docs/detect.md, "Small and oblique tags"). EuRoC's 40 px tags keep their 1.5 px.
  saddle.blur_sigma = std::min(0.75 * saddle.half_window, gap / kSmallSquarePerBlur);
  saddle.max_shift = std::max(2.0, 0.1 * side);
  return saddle;
}

int AddPredictedTags(const CalibrationTarget& target, const apriltag_family& family,
                     const cv::Mat& image, double sharpening, const DivisionModel& lens,
                     std::vector<GridTag>* tags) {
  const int tag_count = target.grid_cols * target.grid_rows;
  const double pitch = 1.0 + target.tag_spacing_ratio;
  const GrayImageView view{image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step),
                           image.data};
  const cv::Rect2d inside(2.0, 2.0, image.cols - 5.0, image.rows - 5.0);
  int added = 0;
  for (;;) {
    std::map<int, const GridTag*> found;
    for (const GridTag& tag : *tags) found[tag.id] = &tag;
    std::vector<GridTag> candidates;
    for (int id = 0; id < tag_count; ++id) {
      if (found.count(id)) continue;
      const int row = id / target.grid_cols, col = id % target.grid_cols;
      std::vector<cv::Point2d> plane, pixels;
      for (const auto& [other, tag] : found) {
        if (std::abs(other / target.grid_cols - row) > 2 ||
            std::abs(other % target.grid_cols - col) > 2) {
          continue;
        }
        for (int k = 0; k < 4; ++k) {
          plane.push_back(TagCorner(target, other, k, pitch));
          pixels.push_back(tag->corners[k]);
        }
      }
      std::vector<cv::Point2d> corners, predicted;
      for (int k = 0; k < 4; ++k) corners.push_back(TagCorner(target, id, k, pitch));
      if (!lens.Predict(plane, pixels, corners, &predicted)) continue;
      GridTag candidate;
      candidate.id = id;
      bool usable = cv::isContourConvex(std::vector<cv::Point2f>(predicted.begin(), predicted.end()));
      for (int k = 0; k < 4; ++k) {
        candidate.corners[k] = predicted[k];
        usable &= inside.contains(predicted[k]) &&
                  cv::norm(predicted[k] - predicted[(k + 1) % 4]) >= kMinPredictedSide;
      }
      if (usable) candidates.push_back(candidate);
    }
    if (candidates.empty()) return added;
    // One refinement for all candidates (it blurs the image once), at their median side.
    std::vector<double> sides;
    std::vector<Eigen::Vector2d> points;
    for (const GridTag& tag : candidates) {
      sides.push_back(MeanSide(tag));
      for (int k = 0; k < 4; ++k) points.emplace_back(tag.corners[k].x, tag.corners[k].y);
    }
    std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
    // A predicted corner may move by half the small square's side at most: the square's other
    // corners, the nearest other junctions, are a side away, so it cannot slide onto one of them.
    const double side = sides[sides.size() / 2];
    SaddleOptions saddle = SaddleOptionsForTags(target, side);
    saddle.max_shift = 0.5 * target.tag_spacing_ratio * side;
    const std::vector<bool> converged = RefineSaddlePoints(view, saddle, &points);
    int added_now = 0;
    for (size_t i = 0; i < candidates.size(); ++i) {
      GridTag tag = candidates[i];
      // ... and by half of its own small square, along its shortest side (the median tag's
      // squares may be larger).
      const double own_shift = 0.5 * target.tag_spacing_ratio * ShortestSide(candidates[i]);
      bool refined = true;
      for (int k = 0; k < 4; ++k) {
        tag.corners[k] = {points[4 * i + k].x(), points[4 * i + k].y()};
        refined &= converged[4 * i + k] &&
                   cv::norm(tag.corners[k] - candidates[i].corners[k]) <= own_shift;
      }
      if (!refined) continue;
      const int errors = TagCodeErrors(family, image, tag, sharpening);
      if (errors < 0 || errors > kMaxPredictedCodeErrors) continue;
      tags->push_back(tag);
      ++added_now;
    }
    if (added_now == 0) return added;
    added += added_now;
  }
}

}  // namespace splinecal
