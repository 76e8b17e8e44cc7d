#include "splinecal/report/detect_report.h"

#include <algorithm>
#include <memory>
#include <mutex>
#include <sstream>

#include "splinecal/camera/target_layout_check.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/string_printf.h"

namespace splinecal {

std::string DetectResultYamlText(const DetectFoldersResult& result,
                                 const CalibrationTarget& target,
                                 const std::string& target_path,
                                 const std::string& effort) {
  YamlWriter yaml;
  yaml.Comment("splinecal detect: target corners found in the images (docs/detect.md)");
  yaml.BeginMap("target");
  yaml.Scalar("file", target_path);
  yaml.Scalar("type", target.type);
  yaml.Scalar("points", static_cast<int64_t>(target.points.size()));
  yaml.EndMap();
  yaml.Scalar("observations", "observations.csv");
  yaml.Scalar("effort", effort);
  yaml.Scalar("threads", result.threads);
  yaml.Scalar("wall_time_s", result.wall_time_s);
  yaml.BeginMap("cameras");
  for (const CameraDetectionSummary& camera : result.cameras) {
    yaml.BeginMap("cam" + std::to_string(camera.cam_id));
    yaml.Scalar("images", camera.dir);
    yaml.Vector("resolution", Eigen::Vector2d(camera.width, camera.height));
    yaml.Scalar("images_listed", camera.images_listed);
    yaml.Scalar("images_read", camera.images_read);
    yaml.Scalar("images_with_target", camera.images_with_target);
    yaml.Scalar("corners", camera.corners);
    yaml.Scalar("tags_rejected", camera.tags_rejected);
    yaml.Scalar("detection_time_s", camera.detection_time_s);
    yaml.EndMap();
  }
  yaml.EndMap();
  yaml.StringList("warnings", result.warnings);
  return yaml.str();
}

std::string DetectSummaryText(const DetectFoldersResult& result) {
  std::string text;
  for (const CameraDetectionSummary& camera : result.cameras) {
    text += StringPrintf("detect: cam%d %d x %d: %lld of %lld images read, %lld with the target, "
                         "%lld corners\n",
                         camera.cam_id, camera.width, camera.height,
                         static_cast<long long>(camera.images_read),
                         static_cast<long long>(camera.images_listed),
                         static_cast<long long>(camera.images_with_target),
                         static_cast<long long>(camera.corners));
  }
  const int64_t frames = [&] {
    int64_t n = 0;
    for (const CameraDetectionSummary& camera : result.cameras) n += camera.images_listed;
    return n;
  }();
  text += StringPrintf("detect: %lld frames in %.2f s on %d thread%s (%.1f frames/s)%s\n",
                       static_cast<long long>(frames), result.wall_time_s, result.threads,
                       result.threads == 1 ? "" : "s",
                       result.wall_time_s > 0 ? frames / result.wall_time_s : 0.0,
                       result.warnings.empty()
                           ? ""
                           : StringPrintf(", %zu warnings (result.yaml lists them)",
                                          result.warnings.size()).c_str());
  return text;
}

namespace {

// The AprilGrid numbering that `target` gave to the detector: corner id (2 tagCols) r + c of tag
// (r / 2) tagCols + c / 2, tag-local corner (c % 2, r % 2). When the corners contradict the file's
// tagCols, the decoded tag ids may still fit another one: the corners renumbered for every other
// tagCols up to the largest id, and the first numbering that camera/target_layout_check.h finds
// consistent is the board's. 0 when none fits (or the target is no aprilgrid).
int TagColumnsTheCornersFit(const std::vector<Observation>& observations,
                            const CalibrationTarget& target) {
  if (target.type != "aprilgrid" || target.grid_cols <= 0) return 0;
  const int64_t file_cols = 2 * static_cast<int64_t>(target.grid_cols);
  int64_t max_tag = 0;
  for (const Observation& o : observations) {
    max_tag = std::max(max_tag, (o.point_id / file_cols / 2) * target.grid_cols +
                                    (o.point_id % file_cols) / 2);
  }
  for (int cols = 1; cols <= max_tag + 1; ++cols) {
    if (cols == target.grid_cols) continue;
    const int rows = static_cast<int>(max_tag / cols + 1);
    const CalibrationTarget candidate =
        MakeAprilGrid(cols, rows, target.tag_size_m, target.tag_spacing_ratio);
    std::vector<Observation> renumbered = observations;
    for (Observation& o : renumbered) {
      const int64_t r = o.point_id / file_cols, c = o.point_id % file_cols;
      const int64_t tag = (r / 2) * target.grid_cols + c / 2;
      o.point_id = (2 * (tag / cols) + r % 2) * 2 * cols + 2 * (tag % cols) + c % 2;
    }
    const GridLayoutFit fit =
        FitGridLayout(LayoutCheckFrames(renumbered, candidate), GridLayout{true, 2 * cols});
    if (fit.fits) return cols;
  }
  return 0;
}

}  // namespace

std::vector<OutputFile> DetectOutputFiles(const DetectFoldersResult& result,
                                          const CalibrationTarget& target,
                                          const std::string& target_path,
                                 const std::string& effort) {
  if (result.observations.empty()) {
    int64_t read = 0;
    for (const CameraDetectionSummary& camera : result.cameras) read += camera.images_read;
    const std::string hint = target.type == "aprilgrid"
                                 ? "do tagCols and tagRows match the printed grid?"
                                 : "do targetCols and targetRows count the inner corners?";
    throw Error(target_path, 0,
                "this " + target.type + " was found in none of the " + std::to_string(read) +
                    " images read; nothing was written (" + hint + ")");
  }
  // A target file that does not describe the printed board (a 7 x 7 grid file for a 6 x 6
  // board) still numbers the tags it decodes, and most of them pass the detector's neighbour
  // check (tags in one row are neighbours in either numbering): refused here, as intrinsics and
  // calibrate refuse such observations, before a wrong observations.csv exists.
  try {
    CheckTargetLayout(result.observations, target, "the images", target_path);
  } catch (const Error&) {
    const int cols = TagColumnsTheCornersFit(result.observations, target);
    if (cols <= 0) throw;
    throw Error(target_path, 0,
                StringPrintf("the tags found in the images lie on an aprilgrid of %d tag columns, "
                             "not the %d of this file: set tagCols: %d (and check tagRows); "
                             "nothing was written",
                             cols, target.grid_cols, cols));
  }
  std::ostringstream csv;
  WriteObservationsCsv(result.observations, &csv);
  return {{"observations.csv", csv.str()},
          {"result.yaml", DetectResultYamlText(result, target, target_path, effort)}};
}

std::function<void(int, const ImageFrame&, const GrayImage&, const TargetDetection&)>
OverlayWriter(OutputDir* output) {
  auto staging = std::make_shared<std::mutex>();
  return [output, staging](int cam_id, const ImageFrame& frame, const GrayImage& image,
                           const TargetDetection& detection) {
    if (detection.corners.empty()) return;
    std::vector<OverlayCorner> corners;
    for (const CornerDetection& c : detection.corners) corners.push_back({c.point_id, c.uv});
    const std::string relative =
        "overlays/cam" + std::to_string(cam_id) + "/" + std::to_string(frame.t_ns) + ".png";
    std::string path;
    {
      std::lock_guard<std::mutex> lock(*staging);
      path = output->StagedPath(relative);
    }
    WriteOverlayPng(image.view(), corners,
                    StringPrintf("cam%d %lld: %zu corners", cam_id,
                                 static_cast<long long>(frame.t_ns), corners.size()),
                    path);
  };
}

}  // namespace splinecal
