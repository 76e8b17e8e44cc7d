#include "splinecal/report/intrinsics_report.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/estimation/view_clusters.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/report/html_page.h"
#include "splinecal/report/report_inputs.h"
#include "splinecal/report/reprojection_figures.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

Eigen::VectorXd Pick(const Eigen::Matrix<double, kNumIntrinsics, 1>& values,
                     const std::vector<int>& order) {
  Eigen::VectorXd picked(order.size());
  for (size_t i = 0; i < order.size(); ++i) picked(i) = values(order[i]);
  return picked;
}

std::string ModelName(const Camera& camera) {
  return CameraModelName(camera.projection, camera.distortion);
}

int CountStatus(const IntrinsicsResult& result, int cam_id, ViewStatus status) {
  return static_cast<int>(
      std::count_if(result.views.begin(), result.views.end(), [&](const ViewRecord& v) {
        return v.cam_id == cam_id && v.status == status;
      }));
}

constexpr ViewStatus kStatuses[] = {ViewStatus::kUsed,
                                    ViewStatus::kTooFewCorners,
                                    ViewStatus::kPnpFailed,
                                    ViewStatus::kRepeat,
                                    ViewStatus::kThinned,
                                    ViewStatus::kOutlier};

std::string ValueWithStd(double value, double std, const char* format) {
  std::string text = StringPrintf(format, value);
  if (std::isfinite(std)) text += " &plusmn; " + StringPrintf(format, std);
  return text;
}

plot::Figure ViewRmsFigure(const IntrinsicsResult& result) {
  plot::Figure figure;
  figure.columns = 1;
  figure.panel_width = 900;
  figure.panel_height = 260;
  int64_t t0 = result.views.empty() ? 0 : result.views.front().t_ns;
  for (const ViewRecord& v : result.views) t0 = std::min(t0, v.t_ns);
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    plot::Panel& panel = plot::AddPanel(&figure,
                                        StringPrintf("cam%zu: RMS of each used view", n),
                                        "time since the first view [s]",
                                        "view RMS [px]");
    plot::Series& used = panel.series.emplace_back();
    used.label = "used views";
    used.line = false;
    used.marker = plot::Marker::kCircle;
    used.color = CameraColor(static_cast<int>(n));
    for (const ViewRecord& v : result.views) {
      if (v.cam_id != static_cast<int>(n) || v.status != ViewStatus::kUsed) continue;
      used.x.push_back(NanosecondsToSeconds(v.t_ns - t0));
      used.y.push_back(v.rms_px);
    }
  }
  return figure;
}

std::string CameraTableHtml(const IntrinsicsResult& result) {
  std::string html =
      "<table><caption>Cameras (value &plusmn; std)</caption><tr><th>camera</th><th>model</th>"
      "<th>intrinsics</th><th>distortion</th><th>RMS [px]</th><th>views used / offered</th>"
      "<th>corners used / rejected</th></tr>\n";
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    const IntrinsicsCameraResult& c = result.cameras[n];
    const IntrinsicsVector values = c.camera.intrinsics();
    std::string intrinsics, distortion;
    for (int i : KalibrIntrinsicsOrder(c.camera)) {
      intrinsics += (intrinsics.empty() ? "" : "<br>") + IntrinsicName(c.camera, i) + " " +
                    ValueWithStd(values(i), c.intrinsics_std(i), i < 4 ? "%.3f" : "%.5f");
    }
    for (int i : KalibrDistortionOrder(c.camera)) {
      distortion += (distortion.empty() ? "" : "<br>") + IntrinsicName(c.camera, i) + " " +
                    ValueWithStd(values(i), c.intrinsics_std(i), "%.6f");
    }
    html += StringPrintf(
        "<tr><th>cam%zu</th><td>%s</td><td>%s</td><td>%s</td><td>%.3f</td><td>%d / %d</td>"
        "<td>%d / %d</td></tr>\n",
        n,
        ModelName(c.camera).c_str(),
        intrinsics.c_str(),
        distortion.empty() ? "none" : distortion.c_str(),
        c.reprojection_rms_px,
        c.views_used,
        c.views_offered,
        c.corners_used,
        c.corners_rejected);
  }
  return html + "</table>\n";
}

std::string RigTableHtml(const IntrinsicsResult& result) {
  if (result.cameras.size() < 2) return "";
  std::string html =
      "<table><caption>Rig: T_cn_cnm1 (camera n-1 into camera n)</caption><tr><th>camera</th>"
      "<th>translation [mm]</th><th>baseline [mm]</th><th>rotation std [deg]</th>"
      "<th>translation std [mm]</th></tr>\n";
  for (size_t n = 1; n < result.cameras.size(); ++n) {
    const IntrinsicsCameraResult& c = result.cameras[n];
    const Eigen::Vector3d t = 1e3 * c.T_cn_cnm1.translation();
    const Eigen::Matrix<double, 6, 1>& s = c.T_cn_cnm1_std;
    html += StringPrintf(
        "<tr><th>cam%zu</th><td>%.3f, %.3f, %.3f</td><td>%.3f</td><td>%.4f, %.4f, %.4f</td>"
        "<td>%.3f, %.3f, %.3f</td></tr>\n",
        n,
        t.x(),
        t.y(),
        t.z(),
        t.norm(),
        kRadToDeg * s(3),
        kRadToDeg * s(4),
        kRadToDeg * s(5),
        1e3 * s(0),
        1e3 * s(1),
        1e3 * s(2));
  }
  return html + "</table>\n";
}

std::string ViewsTableHtml(const IntrinsicsResult& result) {
  std::string html = "<table><caption>Views</caption><tr><th>camera</th>";
  for (ViewStatus status : kStatuses)
    html += std::string("<th>") + ViewStatusName(status) + "</th>";
  html += "</tr>\n";
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    html += StringPrintf("<tr><th>cam%zu</th>", n);
    for (ViewStatus status : kStatuses) {
      html += StringPrintf("<td>%d</td>", CountStatus(result, static_cast<int>(n), status));
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

// --compare-models: the table, then each model's error map, all at the magnification of the
// model whose errors need the smallest (its arrows fit; the others' are then comparable).
void AppendModelComparison(const std::vector<ModelFit>& fits, int max_points, HtmlPage* page) {
  std::string html =
      "<table><caption>Models fitted to the same corners (exact least squares)</caption><tr>"
      "<th>camera</th><th>model</th><th>RMS [px]</th><th>sum of squares [px&sup2;]</th>"
      "<th>corners</th><th>parameters</th></tr>\n";
  std::vector<ReprojectionData> maps;
  double gain = 0.0;
  for (const ModelFit& fit : fits) {
    if (!fit.failure.empty()) {
      html += "<tr><td></td><td>" + fit.model + "</td><td colspan=\"4\">failed: " +
              plot::EscapeXml(fit.failure) + "</td></tr>\n";
      continue;
    }
    for (size_t n = 0; n < fit.cameras.size(); ++n) {
      const IntrinsicsCameraResult& c = fit.cameras[n];
      const IntrinsicsVector values = c.camera.intrinsics();
      std::string parameters;
      for (const std::vector<int>& order :
           {KalibrIntrinsicsOrder(c.camera), KalibrDistortionOrder(c.camera)}) {
        for (int i : order) {
          parameters += StringPrintf("%s%s %.*f",
                                     parameters.empty() ? "" : "<br>",
                                     IntrinsicName(c.camera, i).c_str(),
                                     i < 4 ? 3 : 6,
                                     values(i));
        }
      }
      html += StringPrintf(
          "<tr><th>cam%zu</th><td>%s</td><td>%.4f</td><td>%.3f</td><td>%d</td><td>%s</td></tr>\n",
          n,
          fit.model.c_str(),
          c.reprojection_rms_px,
          fit.sum_of_squares_px2[n],
          c.corners_used,
          parameters.c_str());
    }
    ReprojectionData& data = maps.emplace_back();
    for (const IntrinsicsCameraResult& c : fit.cameras) {
      data.image_sizes.emplace_back(c.camera.width, c.camera.height);
    }
    data.samples = &fit.residuals;
    const double automatic = MakeReprojectionImageFigure(data, max_points).vector_gain;
    gain = gain > 0.0 ? std::min(gain, automatic) : automatic;
  }
  page->Append(html + "</table>\n");
  size_t m = 0;
  for (const ModelFit& fit : fits) {
    if (!fit.failure.empty()) continue;
    ReprojectionData& data = maps[m++];
    data.vector_gain = gain;
    ReprojectionImageFigure map = MakeReprojectionImageFigure(data, max_points);
    map.figure.title = fit.model + ": errors by image position";
    page->FigureSection("Errors by image position, " + fit.model, std::move(map.figure));
    page->Append(map.key_html);
  }
}

}  // namespace

std::string IntrinsicsResultYaml(const IntrinsicsResult& result,
                                 const std::vector<ModelFit>* model_comparison) {
  YamlWriter yaml;
  yaml.Comment(
      "splinecal intrinsics: per camera its model in Kalibr's names and order, stds "
      "beside the values (NaN: held)");
  yaml.BeginList("cameras");
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    const IntrinsicsCameraResult& c = result.cameras[n];
    const IntrinsicsVector values = c.camera.intrinsics();
    yaml.BeginListItem();
    yaml.Scalar("camera", StringPrintf("cam%zu", n));
    yaml.Scalar("camera_model", ModelName(c.camera));
    yaml.Vector("intrinsics", Pick(values, KalibrIntrinsicsOrder(c.camera)));
    yaml.Vector("intrinsics_std", Pick(c.intrinsics_std, KalibrIntrinsicsOrder(c.camera)));
    yaml.Vector("distortion_coeffs", Pick(values, KalibrDistortionOrder(c.camera)));
    yaml.Vector("distortion_std", Pick(c.intrinsics_std, KalibrDistortionOrder(c.camera)));
    yaml.Vector("resolution", Eigen::Vector2d(c.camera.width, c.camera.height));
    yaml.Scalar("reprojection_rms_px", c.reprojection_rms_px);
    yaml.Scalar("pixel_sigma_px", c.pixel_sigma_px);
    yaml.Scalar("views_offered", c.views_offered);
    yaml.Scalar("views_used", c.views_used);
    yaml.BeginMap("views_not_used");
    for (ViewStatus status : kStatuses) {
      if (status == ViewStatus::kUsed) continue;
      yaml.Scalar(ViewStatusKey(status), CountStatus(result, static_cast<int>(n), status));
    }
    yaml.EndMap();
    yaml.Scalar("corners_used", c.corners_used);
    yaml.Scalar("corners_rejected", c.corners_rejected);
    if (n > 0) {
      yaml.Matrix("T_cn_cnm1", c.T_cn_cnm1.matrix());
      yaml.BeginMap("T_cn_cnm1_std");
      yaml.Vector("rotation_deg", kRadToDeg * c.T_cn_cnm1_std.tail<3>());
      yaml.Vector("translation_m", c.T_cn_cnm1_std.head<3>());
      yaml.EndMap();
      yaml.Scalar("baseline_m", c.T_cn_cnm1.translation().norm());
      yaml.Scalar("extrinsic_estimated", c.extrinsic_estimated);
    }
    yaml.Scalar("initialisation", c.initialisation);
    if (c.covariance.matrix.size() > 0) {
      yaml.StringList("std_from", c.std_from);  // per intrinsic of splinecal_covariance.parameters
      WriteParameterCovariance(c.covariance, &yaml);
    }
    yaml.EndListItem();
  }
  yaml.EndList();
  yaml.BeginMap("covariance");
  yaml.Comment(StringPrintf(
      "each std is the largest of the noise model's and, where significantly larger, the "
      "cluster-robust ones over time blocks of block_seconds (2 correlation lengths of the "
      "residuals' scores, at most 1/20 of the recording) and over view_clusters kinds of view "
      "(image region x tilt direction, used from %d); std_from says which",
      kMinViewClusters));
  yaml.Scalar("block_seconds", result.time_blocks.block_s);
  yaml.Scalar("correlation_length_s", result.time_blocks.correlation_length_s);
  yaml.Scalar("blocks", result.time_blocks_count);
  yaml.Scalar("limited_by_min_blocks", result.time_blocks.limited_by_min_blocks);
  yaml.Scalar("view_clusters", result.view_clusters_count);
  yaml.EndMap();
  yaml.BeginMap("solver");
  yaml.Scalar("rounds", result.solve.rounds);
  yaml.Scalar("iterations", result.solve.iterations);
  yaml.Scalar("initial_cost", result.solve.initial_cost);
  yaml.Scalar("final_cost", result.solve.final_cost);
  yaml.Scalar("solve_time_s", result.solve.solve_time_s);
  yaml.Scalar("linear_solver", result.solve.linear_solver);
  yaml.Scalar("termination", result.solve.termination);
  yaml.EndMap();
  yaml.StringList("warnings", result.warnings);
  if (model_comparison != nullptr) {
    yaml.Comment("--compare-models: each model fitted to the same corners, exact least squares");
    yaml.BeginList("model_comparison");
    for (const ModelFit& fit : *model_comparison) {
      for (size_t n = 0; n < std::max<size_t>(fit.cameras.size(), 1); ++n) {
        yaml.BeginListItem();
        yaml.Scalar("model", fit.model);
        if (!fit.failure.empty()) {
          yaml.Scalar("failure", fit.failure);
          yaml.EndListItem();
          break;
        }
        const IntrinsicsCameraResult& c = fit.cameras[n];
        yaml.Scalar("camera", StringPrintf("cam%zu", n));
        yaml.Scalar("reprojection_rms_px", c.reprojection_rms_px);
        yaml.Scalar("sum_of_squares_px2", fit.sum_of_squares_px2[n]);
        yaml.Scalar("corners_used", c.corners_used);
        yaml.Scalar("views_used", c.views_used);
        const IntrinsicsVector values = c.camera.intrinsics();
        yaml.Vector("intrinsics", Pick(values, KalibrIntrinsicsOrder(c.camera)));
        yaml.Vector("distortion_coeffs", Pick(values, KalibrDistortionOrder(c.camera)));
        yaml.EndListItem();
      }
    }
    yaml.EndList();
  }
  return yaml.str();
}

std::string IntrinsicsReportHtml(const IntrinsicsResult& result,
                                 const IntrinsicsReportInputs& inputs,
                                 int max_points) {
  HtmlPage page("splinecal intrinsics", kCalibrationReportCss);
  page.Append(InputFilesHtml({{"observations", inputs.observations_path},
                              {"target", inputs.target_path},
                              {"camchain", inputs.camchain_path}}));
  page.Append(CameraTableHtml(result));
  page.Append(RigTableHtml(result));
  page.ListSection("Warnings", result.warnings);
  page.Append(ViewsTableHtml(result));
  ReprojectionData data;
  for (const IntrinsicsCameraResult& c : result.cameras) {
    data.image_sizes.emplace_back(c.camera.width, c.camera.height);
  }
  data.samples = &result.residuals;
  if (!result.views.empty()) data.t0_ns = result.views.front().t_ns;  // sorted by time
  data.time_label = "time since the first view [s]";
  data.one_panel_per_camera = true;  // cam1's errors never hide cam0's
  page.FigureSection("Reprojection errors", ReprojectionErrorFigure(data, max_points));
  ReprojectionImageFigure by_position = MakeReprojectionImageFigure(data, max_points);
  // The corners the outlier pass removed, as squares on their camera's panel: whether they
  // cluster where the model misfits (the border) or scatter like gross errors.
  constexpr char kRemovedColor[] = "#d62728";
  for (size_t n = 0; n < by_position.figure.panels.size(); ++n) {
    plot::Series& removed = by_position.figure.panels[n].series.emplace_back();
    removed.color = kRemovedColor;
    removed.line = false;
    removed.marker = plot::Marker::kSquare;
    removed.marker_size = 2.0;
    for (const ReprojectionSample& s : result.removed_corners) {
      if (s.cam_id != static_cast<int>(n)) continue;
      removed.x.push_back(s.uv.x());
      removed.y.push_back(s.uv.y());
    }
  }
  by_position.key_html += StringPrintf(
      "<p><span style=\"color:%s\">&#9632;</span> corners removed as outliers (%zu).</p>\n",
      kRemovedColor,
      result.removed_corners.size());
  page.FigureSection("Errors and coverage by image position", std::move(by_position.figure));
  page.Append(by_position.key_html);
  page.FigureSection("Views", ViewRmsFigure(result));
  if (inputs.model_comparison != nullptr) {
    AppendModelComparison(*inputs.model_comparison, max_points, &page);
  }
  return page.str();
}

std::string IntrinsicsSummaryText(const IntrinsicsResult& result) {
  std::string text;
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    const IntrinsicsCameraResult& c = result.cameras[n];
    const IntrinsicsVector values = c.camera.intrinsics();
    text += StringPrintf("cam%zu %s:", n, ModelName(c.camera).c_str());
    for (int i : KalibrIntrinsicsOrder(c.camera)) {
      text += StringPrintf(
          " %s %.3f (%.2g)", IntrinsicName(c.camera, i).c_str(), values(i), c.intrinsics_std(i));
    }
    text += "\n  distortion";
    if (KalibrDistortionOrder(c.camera).empty()) text += " none";
    for (int i : KalibrDistortionOrder(c.camera)) {
      text += StringPrintf(
          " %s %.6f (%.2g)", IntrinsicName(c.camera, i).c_str(), values(i), c.intrinsics_std(i));
    }
    text += StringPrintf("\n  reprojection RMS %.3f px, %d of %d views, %d corners (%d rejected)\n",
                         c.reprojection_rms_px,
                         c.views_used,
                         c.views_offered,
                         c.corners_used,
                         c.corners_rejected);
    if (n > 0) {
      const Eigen::Vector3d t = 1e3 * c.T_cn_cnm1.translation();
      text += StringPrintf("  T_cn_cnm1 translation [%.3f %.3f %.3f] mm, baseline %.3f mm\n",
                           t.x(),
                           t.y(),
                           t.z(),
                           t.norm());
    }
  }
  for (const std::string& w : result.warnings) text += "warning: " + w + "\n";
  return text;
}

}  // namespace splinecal
