#include "splinecal/report/intrinsics_report.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/estimation/view_clusters.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/report/html_page.h"
#include "splinecal/report/report_inputs.h"
#include "splinecal/report/reprojection_figures.h"
#include "splinecal/report/target_points_figure.h"
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

// The target's deformation (IntrinsicsResult::target_deformation) as quantities a user reads,
// one list for result.yaml, report.html and the summary. The coefficients are c itself (out of
// plane heights at the target's edge, in plane ratios); the derived quantities are, out of plane,
// the surface's heights above the least-squares plane through the points, and in plane what the
// ratios make of the printed grid, to first order as the model is (target_deformation.h).
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct DeformationQuantity {
  std::string name;
  double value = 0.0;
  double std = kNaN;           // NaN: no covariance
  const char* unit = "ratio";  // or "mm", "deg"
  bool percent = false;        // a small ratio: shown in % (result.yaml writes it as is)
  double file = kNaN;          // the target file's, NaN: none
  std::string meaning;
};

struct DeformationSummary {
  std::vector<DeformationQuantity> coefficients;
  std::vector<DeformationQuantity> derived;
  // In-plane-per-view: the insets d_v over the timestamps (std with n - 1).
  int inset_count = 0;
  double inset_mean = 0.0, inset_std = 0.0, inset_min = 0.0, inset_max = 0.0;
};

// Every point free: how far the points moved from the file's layout, in the plane and along its
// normal (the target's z), and how well the offsets are determined.
void SummarisePointOffsets(const TargetDeformationResult& d, DeformationSummary* out) {
  double in_plane_sq = 0.0, normal_sq = 0.0, in_plane_max = 0.0, normal_max = 0.0;
  std::vector<double> stds;
  for (const auto& [id, c] : d.point_offsets_m) {
    in_plane_sq += c.head<2>().squaredNorm();
    normal_sq += c.z() * c.z();
    in_plane_max = std::max(in_plane_max, c.head<2>().norm());
    normal_max = std::max(normal_max, std::abs(c.z()));
  }
  for (const auto& [id, s] : d.point_offsets_std_m) stds.push_back(s.maxCoeff());
  const double n = std::max<double>(1.0, static_cast<double>(d.point_offsets_m.size()));
  const auto add = [out](const std::string& name, double value, const char* unit,
                         const std::string& meaning) {
    DeformationQuantity& q = out->derived.emplace_back();
    q.name = name;
    q.value = value;
    q.unit = unit;
    q.meaning = meaning;
  };
  add("free_points", static_cast<double>(d.point_offsets_m.size()), "count",
      "points estimated (seen in at least 10 used views); the others keep the file's position");
  add("offset_rms_in_plane_mm", 1e3 * std::sqrt(in_plane_sq / n), "mm",
      "RMS of the points' offsets in the target's plane, against the file's layout");
  add("offset_max_in_plane_mm", 1e3 * in_plane_max, "mm", "the largest of them");
  add("offset_rms_normal_mm", 1e3 * std::sqrt(normal_sq / n), "mm",
      "RMS of the offsets along the target's normal (z)");
  add("offset_max_normal_mm", 1e3 * normal_max, "mm", "the largest of them");
  if (!stds.empty()) {
    std::nth_element(stds.begin(), stds.begin() + stds.size() / 2, stds.end());
    add("offset_std_median_mm", 1e3 * stds[stds.size() / 2], "mm",
        "the median over the points of an offset's largest std (x, y or z)");
  }
}

DeformationSummary SummariseDeformation(const TargetDeformationResult& d) {
  const TargetShape& shape = d.shape;
  const int k = shape.size();
  DeformationSummary out;
  if (shape.per_point()) {
    SummarisePointOffsets(d, &out);
    return out;
  }
  if (k == 0 || d.coefficients.size() != k) return out;
  const auto std_of = [&](int i) {
    return d.covariance.rows() == k ? std::sqrt(d.covariance(i, i)) : kNaN;
  };
  const auto add = [](std::vector<DeformationQuantity>* list,
                      const std::string& name,
                      double value,
                      double std,
                      const char* unit,
                      const std::string& meaning,
                      double file = kNaN) {
    DeformationQuantity& q = list->emplace_back();
    q.name = name;
    q.value = value;
    q.std = std;
    q.unit = unit;
    q.meaning = meaning;
    q.file = file;
  };
  const std::vector<std::string> names = TargetDeformationCoefficientNames(shape.kind);
  if (shape.out_of_plane()) {
    for (int i = 0; i < k; ++i) {
      add(&out.coefficients,
          names[i],
          1e3 * d.coefficients(i),
          1e3 * std_of(i),
          "mm",
          "height at the target's edge of the basis function " + names[i] +
              " (s, t: the target's x, y scaled to [-1, 1])");
    }
    for (size_t r = 0; r < d.heights.names.size(); ++r) {
      const int row = static_cast<int>(r);
      add(&out.derived,
          "height_" + d.heights.names[r],
          1e3 * d.heights_m(row),
          d.heights_std_m.size() > row ? 1e3 * d.heights_std_m(row) : kNaN,
          "mm",
          StringPrintf("above the least-squares plane through the target's points, at "
                       "(%.4f, %.4f) m",
                       d.heights.xy[r].x(),
                       d.heights.xy[r].y()));
    }
    return out;
  }
  const char* meanings[] = {"x longer by 1 + e1, y by 1 - e1, about the target's centre",
                            "the diagonals x = y and x = -y longer by 1 + e2 and 1 - e2",
                            "each tag's side longer by 1 + d, the pitch held"};
  for (int i = 0; i < k; ++i) {
    add(&out.coefficients, names[i], d.coefficients(i), std_of(i), "ratio", meanings[i]);
    out.coefficients.back().percent = true;
  }
  const double e1 = d.coefficients(0), e2 = d.coefficients(1);
  add(&out.derived,
      "x_over_y_scale",
      1.0 + 2.0 * e1,
      2.0 * std_of(0),
      "ratio",
      "x's scale over y's, 1 + 2 e1",
      1.0);
  add(&out.derived,
      "axes_angle_deg",
      90.0 - kRadToDeg * 2.0 * e2,
      kRadToDeg * 2.0 * std_of(1),
      "deg",
      "the angle between the target's x and y axes, 90 deg - 2 e2 [rad]",
      90.0);
  double inset = 0.0, inset_std = kNaN;
  std::string at;
  if (shape.per_view_inset()) {
    out.inset_count = static_cast<int>(d.view_inset.size());
    double sum = 0.0, sum2 = 0.0;
    out.inset_min = kNaN;
    out.inset_max = kNaN;
    for (const auto& [t_ns, d_v] : d.view_inset) {
      sum += d_v;
      out.inset_min = std::isnan(out.inset_min) ? d_v : std::min(out.inset_min, d_v);
      out.inset_max = std::isnan(out.inset_max) ? d_v : std::max(out.inset_max, d_v);
    }
    out.inset_mean = out.inset_count > 0 ? sum / out.inset_count : kNaN;
    for (const auto& [t_ns, d_v] : d.view_inset) {
      sum2 += (d_v - out.inset_mean) * (d_v - out.inset_mean);
    }
    out.inset_std = out.inset_count > 1 ? std::sqrt(sum2 / (out.inset_count - 1)) : kNaN;
    inset = out.inset_mean;
    at = ", at the insets' mean";
  } else {
    inset = d.coefficients(TargetShape::kInsetColumn);
    inset_std = std_of(TargetShape::kInsetColumn);
  }
  // Only tagSize / pitch is measured (each view's distance takes the uniform scale): the tag side
  // with the file's pitch, and Kalibr's tagSpacing (pitch / tagSize - 1) of that ratio; the two
  // as aprilgrid.yaml's tagSize and tagSpacing keep the file's pitch. The file's tagSpacing to
  // 12 digits: pitch / side - 1 is 0.30000000000000004.
  const double ratio = shape.tag_pitch_m / shape.tag_size_m;
  const double spacing = std::stod(StringPrintf("%.12g", ratio - 1.0));
  add(&out.derived,
      "tag_size_mm",
      1e3 * shape.tag_size_m * (1.0 + inset),
      1e3 * shape.tag_size_m * inset_std,
      "mm",
      "a tag's side with the file's pitch, tagSize (1 + d)" + at,
      1e3 * shape.tag_size_m);
  add(&out.derived,
      "tag_spacing",
      ratio / (1.0 + inset) - 1.0,
      ratio / ((1.0 + inset) * (1.0 + inset)) * inset_std,
      "ratio",
      "Kalibr's tagSpacing, (1 + tagSpacing) / (1 + d) - 1: with tag_size_mm as tagSize the "
      "file's pitch" +
          at,
      spacing);
  return out;
}

// A quantity's value (or std) in its unit, ratios in %.
std::string DeformationNumber(const DeformationQuantity& q, double value) {
  if (q.percent) return StringPrintf("%.3f%%", 100.0 * value);
  if (std::string(q.unit) == "mm") return StringPrintf("%.3f mm", value);
  if (std::string(q.unit) == "deg") return StringPrintf("%.4f deg", value);
  if (std::string(q.unit) == "count") return StringPrintf("%.0f", value);
  return StringPrintf("%.5f", value);
}

void WriteDeformationYaml(const TargetDeformationResult& d, YamlWriter* yaml) {
  yaml->BeginMap("target_deformation");
  yaml->Scalar("kind", TargetDeformationName(d.shape.kind));
  if (d.shape.size() == 0) {
    yaml->EndMap();
    return;
  }
  yaml->Comment(
      "--target-deformation (docs/intrinsics.md, \"Is the target flat?\"): coefficients c, "
      "out of plane heights at the target's edge [mm], in plane ratios (e1 x/y anisotropy, e2 "
      "shear, d tag side to pitch); derived: what they make of the target, `file` the target "
      "file's value. calibrate reads the target file it is given (with points: target.yaml)");
  yaml->Vector("centre_m", d.shape.centre);
  yaml->Scalar("half_extent_m", d.shape.half_extent);
  const DeformationSummary summary = SummariseDeformation(d);
  for (const auto& [key, list] : {std::make_pair("coefficients", &summary.coefficients),
                                  std::make_pair("derived", &summary.derived)}) {
    yaml->BeginList(key);
    for (const DeformationQuantity& q : *list) {
      yaml->BeginListItem();
      yaml->Scalar("name", q.name);
      yaml->Scalar("value", q.value);
      yaml->Scalar("std", q.std);
      yaml->Scalar("unit", q.unit);
      if (std::isfinite(q.file)) yaml->Scalar("file", q.file);
      yaml->EndListItem();
    }
    yaml->EndList();
  }
  if (d.shape.per_point()) {
    yaml->Comment(
        "every point free: each point's offset and std in target_points.csv; target.yaml is the "
        "refined target, for calibrate --target");
    yaml->Scalar("refined_target", "target.yaml");
    yaml->Scalar("points_file", "target_points.csv");
  }
  if (d.shape.per_view_inset()) {
    yaml->BeginMap("view_inset");
    yaml->Comment("each timestamp's d in view_inset.csv, without stds");
    yaml->Scalar("count", summary.inset_count);
    yaml->Scalar("mean", summary.inset_mean);
    yaml->Scalar("std", summary.inset_std);
    yaml->Scalar("min", summary.inset_min);
    yaml->Scalar("max", summary.inset_max);
    yaml->Scalar("file", "view_inset.csv");
    yaml->EndMap();
  }
  yaml->EndMap();
}

std::string DeformationTableHtml(const TargetDeformationResult& d) {
  if (d.shape.size() == 0) return "";
  const DeformationSummary summary = SummariseDeformation(d);
  std::string html = std::string("<table><caption>Target deformation: ") +
                     TargetDeformationName(d.shape.kind) +
                     " (value &plusmn; std)</caption><tr><th>quantity</th><th>value</th>"
                     "<th>target file</th><th>meaning</th></tr>\n";
  for (const std::vector<DeformationQuantity>* list : {&summary.coefficients, &summary.derived}) {
    for (const DeformationQuantity& q : *list) {
      std::string value = DeformationNumber(q, q.value);
      if (std::isfinite(q.std)) value += " &plusmn; " + DeformationNumber(q, q.std);
      html += "<tr><th>" + q.name + "</th><td>" + value + "</td><td>" +
              (std::isfinite(q.file) ? DeformationNumber(q, q.file) : "") + "</td><td>" +
              plot::EscapeXml(q.meaning) + "</td></tr>\n";
    }
  }
  if (d.shape.per_view_inset()) {
    html += StringPrintf(
        "<tr><th>d per view</th><td>mean %.3f%%, std %.3f%%, min %.3f%%, max %.3f%%</td>"
        "<td></td><td>%d timestamps (view_inset.csv)</td></tr>\n",
        100.0 * summary.inset_mean,
        100.0 * summary.inset_std,
        100.0 * summary.inset_min,
        100.0 * summary.inset_max,
        summary.inset_count);
  }
  return html + "</table>\n";
}

std::string DeformationSummaryText(const TargetDeformationResult& d) {
  if (d.shape.size() == 0) return "";
  const DeformationSummary summary = SummariseDeformation(d);
  const auto line = [](const std::vector<DeformationQuantity>& quantities) {
    std::string text;
    for (const DeformationQuantity& q : quantities) {
      text += " " + q.name + " " + DeformationNumber(q, q.value);
      if (std::isfinite(q.std)) text += " (" + DeformationNumber(q, q.std) + ")";
      if (std::isfinite(q.file)) text += " [file " + DeformationNumber(q, q.file) + "]";
    }
    return text;
  };
  std::string text = std::string("target deformation ") + TargetDeformationName(d.shape.kind) +
                     ":" + line(summary.coefficients) + "\n " + line(summary.derived) + "\n";
  if (d.shape.per_view_inset()) {
    text += StringPrintf(
        "  d per view: %d timestamps, mean %.3f%%, std %.3f%%, min %.3f%%, "
        "max %.3f%%\n",
        summary.inset_count,
        100.0 * summary.inset_mean,
        100.0 * summary.inset_std,
        100.0 * summary.inset_min,
        100.0 * summary.inset_max);
  }
  return text;
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
  WriteDeformationYaml(result.target_deformation, &yaml);
  if (result.target_points_check.points > 0) {
    const TargetPointsCheck& check = result.target_points_check;
    yaml.BeginMap("target_points_check");
    yaml.Comment(StringPrintf(
        "every point seen in %d views against its file's position, the others held "
        "(target_points_check.h): chi_square over dof is about 1 when the file is right; above "
        "%.0f a warning names --target-deformation points",
        kMinViewsPerFreePoint, kTargetPointsWarnRatio));
    yaml.Scalar("points", check.points);
    yaml.Scalar("chi_square", check.chi_square);
    yaml.Scalar("dof", check.dof);
    yaml.Scalar("rms_offset_m", check.rms_offset_m);
    yaml.Scalar("max_offset_m", check.max_offset_m);
    yaml.EndMap();
  }
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
  page.Append(DeformationTableHtml(result.target_deformation));
  if (result.target_deformation.shape.per_point()) {
    page.FigureSection("Target points", TargetPointsFigure(result.target_deformation));
  } else if (!TargetPointsWarning(result.target_points_check).empty()) {
    page.FigureSection("Target points against the file",
                       TargetPointsFigure(result.target_points_check));
  }
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
  text += DeformationSummaryText(result.target_deformation);
  for (const std::string& w : result.warnings) text += "warning: " + w + "\n";
  return text;
}

std::string IntrinsicsTargetPointsCsv(const IntrinsicsResult& result) {
  const TargetDeformationResult& d = result.target_deformation;
  std::string csv = "#point_id,x,y,z,dx_mm,dy_mm,dz_mm,std_x_mm,std_y_mm,std_z_mm\n";
  for (const auto& [id, p] : d.refined_target.points) {
    const auto offset = d.point_offsets_m.find(id);
    const auto std = d.point_offsets_std_m.find(id);
    const Eigen::Vector3d c = offset != d.point_offsets_m.end() ? offset->second : Eigen::Vector3d::Zero();
    const Eigen::Vector3d s = std != d.point_offsets_std_m.end()
                                  ? std->second
                                  : Eigen::Vector3d::Constant(kNaN);
    csv += std::to_string(id) + "," + FormatDouble(p.x()) + "," + FormatDouble(p.y()) + "," +
           FormatDouble(p.z());
    for (int i = 0; i < 3; ++i) csv += "," + FormatDouble(1e3 * c(i));
    for (int i = 0; i < 3; ++i) csv += "," + FormatDouble(1e3 * s(i));
    csv += "\n";
  }
  return csv;
}

std::string IntrinsicsViewInsetCsv(const IntrinsicsResult& result) {
  std::string csv = "#t_ns,d\n";
  for (const auto& [t_ns, d_v] : result.target_deformation.view_inset) {
    csv += std::to_string(t_ns) + "," + FormatDouble(d_v) + "\n";
  }
  return csv;
}

}  // namespace splinecal
