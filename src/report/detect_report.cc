#include "splinecal/report/detect_report.h"

#include <sstream>

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

std::vector<OutputFile> DetectOutputFiles(const DetectFoldersResult& result,
                                          const CalibrationTarget& target,
                                          const std::string& target_path,
                                          const std::string& effort) {
  std::ostringstream csv;
  WriteObservationsCsv(result.observations, &csv);
  return {{"observations.csv", csv.str()},
          {"result.yaml", DetectResultYamlText(result, target, target_path, effort)}};
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

}  // namespace splinecal
