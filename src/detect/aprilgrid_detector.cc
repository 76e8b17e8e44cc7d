#include "aprilgrid_detector.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
}

#include "division_model.h"
#include "grid_prediction.h"
#include "grid_tag.h"
#include "splinecal/detect/saddle_point.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

// libapriltag reports p[0..3] at the tag-local corners (-1, 1), (1, 1), (1, -1), (-1, -1) of
// its own frame, whose y axis points down the printed tag, while Kalibr's target frame has y up
// the printed grid: p[k] is our corner k (grid_tag.h). (The EuRoC frame checks this: a wrong
// order puts the corners 30 px off the grid's homography, tests/detect/target_detector_test.cc.)

int64_t CornerId(const CalibrationTarget& target, int tag_id, int k) {
  const int tag_row = tag_id / target.grid_cols;
  const int tag_col = tag_id % target.grid_cols;
  const int64_t r = 2 * tag_row + kLocalY[k];
  const int64_t c = 2 * tag_col + kLocalX[k];
  return r * 2 * target.grid_cols + c;
}

cv::Point2d Centre(const GridTag& tag) {
  return 0.25 * (tag.corners[0] + tag.corners[1] + tag.corners[2] + tag.corners[3]);
}

// Keeps a tag only when its own corners predict another decoded tag of the grid where it was
// found: a tag decoded with a wrong id (a misread code, a tag on the wall that belongs to no
// grid) has no such neighbour, since its grid neighbours are elsewhere in the image. Prediction
// uses the tag's own homography (tag plane to image), so lens distortion only enters over the
// short distance to the neighbour.
void RejectInconsistentTags(const CalibrationTarget& target,
                            int neighbour_steps,
                            std::vector<GridTag>* tags) {
  const double pitch = 1.0 + target.tag_spacing_ratio;  // tag-to-tag step in tag sides
  std::vector<cv::Mat> homographies;
  for (const GridTag& tag : *tags) {
    std::vector<cv::Point2f> local, image;
    for (int k = 0; k < 4; ++k) {
      local.emplace_back(static_cast<float>(kLocalX[k]), static_cast<float>(kLocalY[k]));
      image.emplace_back(tag.corners[k]);
    }
    homographies.push_back(cv::getPerspectiveTransform(local, image));
  }
  std::vector<bool> supported(tags->size(), false);
  for (size_t i = 0; i < tags->size(); ++i) {
    const GridTag& a = (*tags)[i];
    const int ar = a.id / target.grid_cols, ac = a.id % target.grid_cols;
    const double tolerance = 0.3 * MeanSide(a);
    for (size_t j = 0; j < tags->size() && !supported[i]; ++j) {
      const GridTag& b = (*tags)[j];
      const int dr = b.id / target.grid_cols - ar, dc = b.id % target.grid_cols - ac;
      if (j == i || std::abs(dr) > neighbour_steps || std::abs(dc) > neighbour_steps) continue;
      std::vector<cv::Point2d> local, predicted;
      for (int k = 0; k < 4; ++k) {
        local.emplace_back(dc * pitch + kLocalX[k], dr * pitch + kLocalY[k]);
      }
      cv::perspectiveTransform(local, predicted, homographies[i]);
      bool agrees = true;
      for (int k = 0; k < 4; ++k) agrees &= cv::norm(predicted[k] - b.corners[k]) < tolerance;
      supported[i] = agrees;
    }
  }
  for (size_t i = 0; i < tags->size(); ++i) (*tags)[i].kept = supported[i];
}

// A tag found twice: by both searches at one place (the same tag: the first copy is kept), or at
// two places (an id decoded twice cannot be trusted in either place: both dropped, and counted).
// One place = centres within 0.3 of the tag's side, the neighbour check's tolerance.
void MergeSameTags(std::vector<GridTag>* tags, int* rejected) {
  std::map<int, std::vector<size_t>> by_id;
  for (size_t i = 0; i < tags->size(); ++i) by_id[(*tags)[i].id].push_back(i);
  std::vector<bool> drop(tags->size(), false);
  for (const auto& [id, copies] : by_id) {
    const GridTag& first = (*tags)[copies[0]];
    const cv::Point2d centre = Centre(first);
    bool one_place = true;
    for (size_t k = 1; k < copies.size(); ++k) {
      one_place &= cv::norm(Centre((*tags)[copies[k]]) - centre) < 0.3 * MeanSide(first);
    }
    for (size_t k = 0; k < copies.size(); ++k) {
      if (one_place) {
        drop[copies[k]] = k > 0;
      } else {
        drop[copies[k]] = true;
        ++*rejected;
      }
    }
  }
  std::vector<GridTag> merged;
  for (size_t i = 0; i < tags->size(); ++i) {
    if (!drop[i]) merged.push_back((*tags)[i]);
  }
  *tags = merged;
}

// The tags of `found` that survive MergeSameTags and RejectInconsistentTags (`found` is left as
// it is); `dropped` counts the others.
std::vector<GridTag> KeepConsistentTags(const CalibrationTarget& target, int neighbour_steps,
                                        std::vector<GridTag> found, int* dropped) {
  MergeSameTags(&found, dropped);
  if (neighbour_steps > 0) RejectInconsistentTags(target, neighbour_steps, &found);
  std::vector<GridTag> kept;
  for (const GridTag& tag : found) {
    if (tag.kept) {
      kept.push_back(tag);
    } else {
      ++*dropped;
    }
  }
  return kept;
}

// True when `tags` is empty, or when a tag of the grid that was not found lies wholly inside the
// image (2 px from its border) where the homography fitted to the found tags' corners (through
// the lens's division model, division_model.h) places it: tags that a search at a finer scale may
// find. A tag cut by the image border is not missed.
bool MissesTagsInView(const CalibrationTarget& target, const cv::Size& size,
                      const DivisionModel& lens, const std::vector<GridTag>& tags) {
  if (tags.empty()) return true;
  const int tag_count = target.grid_cols * target.grid_rows;
  if (static_cast<int>(tags.size()) >= tag_count) return false;
  const double pitch = 1.0 + target.tag_spacing_ratio;
  std::vector<cv::Point2d> plane, image;
  std::vector<bool> found(tag_count, false);
  for (const GridTag& tag : tags) {
    found[tag.id] = true;
    for (int k = 0; k < 4; ++k) {
      plane.push_back(TagCorner(target, tag.id, k, pitch));
      image.push_back(tag.corners[k]);
    }
  }
  const cv::Rect2d inside(2.0, 2.0, size.width - 5.0, size.height - 5.0);
  for (int id = 0; id < tag_count; ++id) {
    if (found[id]) continue;
    std::vector<cv::Point2d> corners, predicted;
    for (int k = 0; k < 4; ++k) corners.push_back(TagCorner(target, id, k, pitch));
    if (!lens.Predict(plane, image, corners, &predicted)) return true;
    bool in_view = true;
    for (const cv::Point2d& p : predicted) in_view &= inside.contains(p);
    if (in_view) return true;
  }
  return false;
}

// The smallest limit on a corner's move in the final refinement [px]: libapriltag's corners of a
// blurred tag can be a pixel or so off the junction.
constexpr double kMinCornerShiftLimitPx = 1.5;

// libapriltag's decode_sharpening (its default) in the search of the frame as it is.
constexpr double kSharpening = 0.25;
// ... and in the upsampled searches, whose bilinear interpolation blurs the code bits: on the
// resampled EuRoC frames of tests/detect/aprilgrid_recall_test.cc, 0 / 0.25 / 0.5 / 1 / 1.5 found
// 63.7 / 79.4 / 83.7 / 87.3 / 88.5% of the corners of 15-20 px tags, never a wrong id.
constexpr double kUpsampledSharpening = 1.0;
// ... and in reading the code of a tag the grid predicts (grid_prediction.h), on the frame's own
// pixels: 0 / 0.25 / 0.5 / 1.0 confirmed tags holding 89.5 / 95.5 / 95.9 / 95.9% of the corners
// of 15-20 px tags and 50.7 / 53.9 / 57.3 / 58.8% of 10-15 px ones (the same copies), no wrong id.
constexpr double kPredictedSharpening = 1.0;

// The tags libapriltag decodes in `image` resampled by `scale` (1 = as it is), with the white
// grown first when `grow` > 0 (a `grow` x `grow` maximum), corners in `image`'s pixels. Ids
// outside the grid are counted in `foreign` and dropped.
std::vector<GridTag> SearchTags(apriltag_detector* detector, const CalibrationTarget& target,
                                const cv::Mat& image, double scale, double decimate, int grow,
                                double sharpening, int* foreign) {
  cv::Mat resampled = image;
  if (scale != 1.0) cv::resize(image, resampled, cv::Size(), scale, scale, cv::INTER_LINEAR);
  // In a Kalibr grid each tag's corners touch the small squares between tags, so a tag and its
  // four squares form one black region and the quad finder sees no square. Growing the white by
  // one pixel (a 2 x 2 maximum) cuts those contacts; the corners it shifts by a pixel are then
  // placed by the sub-pixel refinement on the original image.
  // (A new matrix: dilating into a header of `image` would write into the caller's pixels.)
  cv::Mat separated;
  if (grow > 0) {
    cv::dilate(resampled, separated, cv::Mat::ones(grow, grow, CV_8U));
  } else {
    separated = resampled;
  }
  image_u8_t frame = {separated.cols, separated.rows, static_cast<int32_t>(separated.step),
                      separated.data};
  detector->quad_decimate = static_cast<float>(decimate);
  detector->decode_sharpening = sharpening;
  zarray_t* detections = apriltag_detector_detect(detector, &frame);
  const int tag_count = target.grid_cols * target.grid_rows;
  std::vector<GridTag> tags;
  for (int i = 0; i < zarray_size(detections); ++i) {
    apriltag_detection_t* detection = nullptr;
    zarray_get(detections, i, &detection);
    if (detection->id < 0 || detection->id >= tag_count) {
      ++*foreign;  // a tag of another grid or on the wall
      continue;
    }
    GridTag tag;
    tag.id = detection->id;
    // libapriltag puts pixel centres at half-integers (a pixel spans [x, x + 1)); splinecal at
    // integers (detect/gray_image.h).
    for (int k = 0; k < 4; ++k) {
      tag.corners[k] = {detection->p[k][0] / scale - 0.5, detection->p[k][1] / scale - 0.5};
    }
    tags.push_back(tag);
  }
  apriltag_detections_destroy(detections);
  return tags;
}

}  // namespace

AprilGridDetector::AprilGridDetector(const CalibrationTarget& target,
                                     const DetectorOptions& options)
    : target_(target), options_(options) {
  if (target.type != "aprilgrid" || target.grid_cols < 1 || target.grid_rows < 1) {
    throw Error("aprilgrid detector: the target is not an aprilgrid");
  }
  if (target.grid_cols * target.grid_rows > 587) {
    throw Error("aprilgrid detector: " + std::to_string(target.grid_cols * target.grid_rows) +
                " tags need more than the 587 codes of tag family 36h11");
  }
  // Kalibr prints tag36h11 with a black border 2 bits wide: the black square is 10 bits across
  // (6 data bits, 2 border bits each side) and the quiet zone 1 bit more. The codes are
  // tag36h11's; the data bits sit one bit further in than in the standard 8-bit-wide tag.
  family_ = tag36h11_create();
  family_->width_at_border = 10;
  family_->total_width = 12;
  for (uint32_t i = 0; i < family_->nbits; ++i) {
    family_->bit_x[i] += 1;
    family_->bit_y[i] += 1;
  }
  detector_ = apriltag_detector_create();
  apriltag_detector_add_family_bits(detector_, family_, 2);
  detector_->quad_decimate = static_cast<float>(options.quad_decimate);
  detector_->quad_sigma = 0.0f;
  detector_->nthreads = 1;  // the caller parallelises over frames
  detector_->refine_edges = 1;
}

AprilGridDetector::~AprilGridDetector() {
  apriltag_detector_destroy(detector_);
  tag36h11_destroy(family_);
}

TargetDetection AprilGridDetector::Detect(const cv::Mat& image) {
  // libapriltag 3.3 reads past a buffer for images of 4 rows or fewer and asserts on sides of
  // 32768 px or more (after decimation): refused here, as a problem of this frame.
  if (image.cols < 16 || image.rows < 16 || image.cols >= 32768 || image.rows >= 32768) {
    throw Error("image of " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                " pixels: the AprilGrid detector needs 16 to 32767 pixels per side");
  }
  TargetDetection result;
  // Tags decoded outside the grid are counted by the first search only (the others see the same
  // ones again).
  int foreign_again = 0;
  const int grow = options_.separate_corner_squares ? 2 : 0;
  std::vector<GridTag> found = SearchTags(detector_, target_, image, 1.0, options_.quad_decimate,
                                          grow, kSharpening, &result.tags_rejected);
  int dropped = 0;
  std::vector<GridTag> kept = KeepConsistentTags(target_, options_.neighbour_steps, found, &dropped);
  const bool predict = options_.effort != DetectEffort::kFast;
  // The lens from the tags found so far (division_model.h), fitted again when more are found;
  // only where a prediction needs it.
  const int tag_count = target_.grid_cols * target_.grid_rows;
  DivisionModel lens;
  if (predict && static_cast<int>(kept.size()) < tag_count) {
    lens = FitDivisionModel(target_, kept, image.size());
  }
  if (predict && MissesTagsInView(target_, image.size(), lens, kept)) {
    const size_t before = kept.size();
    AddPredictedTags(target_, *family_, image, kPredictedSharpening, lens, &kept);
    found.insert(found.end(), kept.begin() + before, kept.end());
  }
  const bool upsampled =
      options_.upsample > 1.0 &&
      (options_.effort == DetectEffort::kThorough ||
       (options_.effort == DetectEffort::kDefault &&
        MissesTagsInView(target_, image.size(), lens, kept)));
  if (upsampled) {
    // The white grown by 2 x 2 and by 3 x 3 upsampled pixels (half a pixel and one pixel of the
    // frame): the first keeps the code bits of the smallest tags, the second separates larger
    // blurred tags from their corner squares; together they found 98.4% of the corners of 20-25
    // px tags where either alone found 96.6% or 88.1% (docs/detect.md; measured with
    // libapriltag's default sharpening, before kUpsampledSharpening).
    for (const int upsampled_grow : {grow, grow > 0 ? 3 : -1}) {
      if (upsampled_grow < 0) continue;
      const std::vector<GridTag> more =
          SearchTags(detector_, target_, image, options_.upsample, options_.upsample,
                     upsampled_grow, kUpsampledSharpening, &foreign_again);
      found.insert(found.end(), more.begin(), more.end());
    }
    dropped = 0;
    kept = KeepConsistentTags(target_, options_.neighbour_steps, found, &dropped);
    if (predict && static_cast<int>(kept.size()) < tag_count) {
      lens = FitDivisionModel(target_, kept, image.size());
      AddPredictedTags(target_, *family_, image, kPredictedSharpening, lens, &kept);
    }
  }
  result.tags_rejected += dropped;
  if (kept.empty() || static_cast<int>(kept.size()) < options_.min_tags) return result;

  // Sub-pixel refinement at the scale of the tags in this frame.
  std::vector<double> sides;
  for (const GridTag& tag : kept) sides.push_back(MeanSide(tag));
  std::nth_element(sides.begin(), sides.begin() + sides.size() / 2, sides.end());
  const SaddleOptions saddle = SaddleOptionsForTags(target_, sides[sides.size() / 2]);

  std::vector<Eigen::Vector2d> points;
  std::vector<int64_t> ids;
  // How far each corner may move: half the small square beside it, at its own tag's size (the
  // frame's saddle options are for its median tag; a smaller tag's junctions are closer, and a
  // corner moved by more may sit on the square's far junction).
  std::vector<double> max_shift;
  for (const GridTag& tag : kept) {
    for (int k = 0; k < 4; ++k) {
      points.emplace_back(tag.corners[k].x, tag.corners[k].y);
      ids.push_back(CornerId(target_, tag.id, k));
      max_shift.push_back(
          std::max(kMinCornerShiftLimitPx, 0.5 * target_.tag_spacing_ratio * ShortestSide(tag)));
    }
  }
  const std::vector<Eigen::Vector2d> starts = points;
  const GrayImageView view{image.cols, image.rows, static_cast<std::ptrdiff_t>(image.step),
                           image.data};
  std::vector<bool> converged = RefineSaddlePoints(view, saddle, &points);
  // A corner refused at the frame's scale is tried once more with the smallest window and a
  // blur of 1 px instead of 0.75 of the window (1.5 px at the smallest): on tags under ~20 px,
  // or narrowed by an oblique view, the small squares are 4-6 px wide and that blur merges
  // their corners into one blob with no saddle. On the resampled copies of
  // tests/detect/aprilgrid_recall_test.cc this took 15-20 px tags from 95.9% to 98.1% of their
  // corners (a blur of 0.7 px: 98.2%), median error 0.043 px either way, no corner more than
  // 1 px off from 15 px, no wrong id.
  std::vector<size_t> retry;
  std::vector<Eigen::Vector2d> again;
  for (size_t i = 0; i < points.size(); ++i) {
    if (!converged[i]) {
      retry.push_back(i);
      again.push_back(points[i]);
    }
  }
  if (!retry.empty()) {
    SaddleOptions narrow = saddle;
    narrow.half_window = 2;
    narrow.blur_sigma = 1.0;
    const std::vector<bool> refined = RefineSaddlePoints(view, narrow, &again);
    for (size_t j = 0; j < retry.size(); ++j) {
      if (refined[j]) {
        points[retry[j]] = again[j];
        converged[retry[j]] = true;
      }
    }
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (converged[i] && (points[i] - starts[i]).norm() <= max_shift[i]) {
      result.corners.push_back({ids[i], points[i]});
    } else {
      ++result.corners_rejected;
    }
  }
  std::sort(result.corners.begin(), result.corners.end(),
            [](const CornerDetection& a, const CornerDetection& b) {
              return a.point_id < b.point_id;
            });
  result.tags_found = static_cast<int>(kept.size());
  return result;
}

}  // namespace splinecal
