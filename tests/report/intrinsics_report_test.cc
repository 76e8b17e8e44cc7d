// report/intrinsics_report.h and the per-camera reprojection figures it draws: Kalibr's parameter
// names for every model, one panel per camera (cam1 never drawn over cam0), the intrinsics' own
// time axis, arrowheads and the image outline on the error map, and every drawn coordinate
// inside its panel; and the target's deformation out of plane in result.yaml (heights in mm) and
// report.html.
#include "splinecal/report/intrinsics_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <sstream>
#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/report/reprojection_figures.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// cam0 pinhole-radtan, cam1 ds-none (752 x 480), corners on a lattice with small errors, and in
// each camera's top-left corner errors of 40 px pointing out of the image (drawn magnified, their
// arrows leave the image and the panel: the plot must clip them).
IntrinsicsResult TwoCameraResult() {
  IntrinsicsResult result;
  result.cameras.resize(2);
  Camera& radtan = result.cameras[0].camera;
  radtan.projection = ProjectionModel::kPinhole;
  radtan.distortion = DistortionModel::kRadTan;
  Camera& ds = result.cameras[1].camera;
  ds.projection = ProjectionModel::kDoubleSphere;
  ds.distortion = DistortionModel::kNone;
  for (int n = 0; n < 2; ++n) {
    IntrinsicsCameraResult& c = result.cameras[n];
    c.camera.width = 752;
    c.camera.height = 480;
    IntrinsicsVector values = IntrinsicsVector::Zero();
    values.head<4>() << 458.0 + n, 457.0 + n, 367.0, 248.0;
    if (n == 1) values.segment<2>(4) << -0.25, 0.56;
    c.camera.set_intrinsics(values);
    c.active = c.camera.ActiveIntrinsics();
    for (int j : c.active) c.intrinsics_std(j) = 0.01 * (j + 1);
  }
  int64_t t = 1000000000;
  for (int k = 0; k < 40; ++k, t += 50000000) {
    for (int n = 0; n < 2; ++n) {
      ViewRecord& view = result.views.emplace_back();
      view.t_ns = t;
      view.cam_id = n;
      view.rms_px = 0.3;
      for (int v = 10; v < 480; v += 40) {
        for (int u = 10; u < 752; u += 40) {
          ReprojectionSample s;
          s.t_ns = t;
          s.cam_id = n;
          s.uv = Eigen::Vector2d(u + k % 7, v + k % 5);
          s.error = Eigen::Vector2d(k % 2 == 0 ? 0.2 : -0.2, 0.1);
          if (u < 60 && v < 60) s.error = Eigen::Vector2d(-40.0, -30.0);
          result.residuals.push_back(s);
        }
      }
    }
  }
  return result;
}

// The figures' input for TwoCameraResult's residuals (both cameras 752 x 480).
ReprojectionData DataOf(const IntrinsicsResult& result) {
  ReprojectionData data;
  data.image_sizes = {{752, 480}, {752, 480}};
  data.samples = &result.residuals;
  return data;
}

TEST(IntrinsicsReport, KalibrParameterNamesForEveryModel) {
  const IntrinsicsResult result = TwoCameraResult();
  const std::string html = IntrinsicsReportHtml(result, {"obs.csv", "target.yaml", ""}, 2000);
  // radtan: fu fv pu pv, then k1 k2 p1 p2; ds: xi alpha fu fv pu pv (Kalibr's order).
  for (const char* entry : {"fu 458.000", "pv 248.000", "k1 0.000000", "p2 0.000000",
                            "xi -0.25000", "alpha 0.56000", "fu 459.000"}) {
    EXPECT_THAT(html, HasSubstr(entry)) << entry;
  }
  const std::string text = IntrinsicsSummaryText(result);
  EXPECT_THAT(text, HasSubstr("cam0 pinhole-radtan: fu 458.000"));
  EXPECT_THAT(text, HasSubstr("cam1 ds-none: xi -0.250 (0.05) alpha 0.560 (0.06) fu 459.000"));
  EXPECT_THAT(text, HasSubstr("distortion k1 0.000000"));
}

TEST(IntrinsicsReport, OnePanelPerCameraWithTheViewsTimeAxis) {
  const IntrinsicsResult result = TwoCameraResult();
  const std::string html = IntrinsicsReportHtml(result, {"obs.csv", "target.yaml", ""}, 2000);
  EXPECT_THAT(html, Not(HasSubstr("IMU spline")));
  EXPECT_THAT(html, HasSubstr("time since the first view [s]"));
  ReprojectionData data = DataOf(result);
  data.one_panel_per_camera = true;
  const plot::Figure figure = ReprojectionErrorFigure(data, 2000);
  // A scatter and a norm-over-time panel per camera, each with its camera's series only.
  ASSERT_EQ(figure.panels.size(), 4u);
  for (size_t p = 0; p < 4; ++p) {
    const int cam = static_cast<int>(p / 2);
    ASSERT_EQ(figure.panels[p].series.size(), 1u);
    EXPECT_EQ(figure.panels[p].series[0].color, CameraColor(cam));
    EXPECT_THAT(figure.panels[p].title, HasSubstr("cam" + std::to_string(cam)));
  }
  const ReprojectionImageFigure map = MakeReprojectionImageFigure(data, 2000);
  ASSERT_EQ(map.figure.panels.size(), 2u);
  EXPECT_EQ(map.figure.panels[0].title, "cam0");
  EXPECT_EQ(map.figure.panels[1].title, "cam1");
}

TEST(IntrinsicsReport, QuadraticTargetDeformationInMillimetres) {
  IntrinsicsResult result = TwoCameraResult();
  // The flat default: the kind alone.
  YAML::Node yaml = YAML::Load(IntrinsicsResultYaml(result));
  EXPECT_EQ(yaml["target_deformation"]["kind"].as<std::string>(), "none");
  EXPECT_FALSE(yaml["target_deformation"]["coefficients"]);

  // A bowl h = 1 mm (s^2 + t^2) with stds 0.1, 0.2, 0.3 mm on EuRoC's grid.
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  TargetDeformationResult& d = result.target_deformation;
  d.shape = MakeTargetShape(target, TargetDeformationKind::kQuadratic);
  d.heights = MakeTargetDeformationHeights(target, d.shape);
  d.coefficients = Eigen::Vector3d(1e-3, 0.0, 1e-3);
  d.covariance = Eigen::Vector3d(1e-4, 2e-4, 3e-4).cwiseAbs2().asDiagonal();
  d.heights_m = d.heights.M * d.coefficients;
  d.heights_std_m = (d.heights.M * d.covariance * d.heights.M.transpose()).diagonal().cwiseSqrt();
  yaml = YAML::Load(IntrinsicsResultYaml(result));
  const YAML::Node block = yaml["target_deformation"];
  EXPECT_EQ(block["kind"].as<std::string>(), "quadratic");
  const std::vector<std::string> names = {"ss", "st", "tt"};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(block["coefficients"][k]["name"].as<std::string>(), names[k]);
    EXPECT_EQ(block["coefficients"][k]["unit"].as<std::string>(), "mm");
    EXPECT_DOUBLE_EQ(block["coefficients"][k]["value"].as<double>(), 1e3 * d.coefficients(k));
    EXPECT_DOUBLE_EQ(block["coefficients"][k]["std"].as<double>(), 0.1 * (k + 1));
  }
  ASSERT_EQ(block["derived"].size(), 5u);
  for (int r = 0; r < 5; ++r) {
    EXPECT_EQ(block["derived"][r]["name"].as<std::string>(), "height_" + d.heights.names[r]);
    EXPECT_DOUBLE_EQ(block["derived"][r]["value"].as<double>(), 1e3 * d.heights_m(r));
    EXPECT_DOUBLE_EQ(block["derived"][r]["std"].as<double>(), 1e3 * d.heights_std_m(r));
  }
  // The bowl rises to the corners: each corner the same height above the centre.
  EXPECT_LT(block["derived"][0]["value"].as<double>(), 0.0);
  EXPECT_GT(block["derived"][1]["value"].as<double>(), 0.0);
  const std::string html = IntrinsicsReportHtml(result, {"obs.csv", "target.yaml", ""}, 2000);
  EXPECT_THAT(html, HasSubstr("Target deformation: quadratic"));
  EXPECT_THAT(html, HasSubstr("<th>height_corner_+x+y</th>"));
  EXPECT_THAT(IntrinsicsSummaryText(result),
              HasSubstr("target deformation quadratic: ss 1.000 mm"));
}

TEST(MakeReprojectionImageFigure, ArrowheadsAndTheImageOutline) {
  const IntrinsicsResult result = TwoCameraResult();
  ReprojectionData data = DataOf(result);
  const ReprojectionImageFigure map = MakeReprojectionImageFigure(data, 2000);
  const plot::Panel& panel = map.figure.panels[0];
  // 5 error classes, the vectors, their dots, the arrowheads, the outline.
  ASSERT_EQ(panel.series.size(), 9u);
  const plot::Series& vectors = panel.series[5];
  const plot::Series& heads = panel.series[7];
  const size_t arrows = vectors.x.size() / 3;
  ASSERT_GT(arrows, 0u);
  // Two barbs per arrow (left, tip, right, break), meeting at the vector's tip and shorter than
  // the shaft.
  ASSERT_EQ(heads.x.size(), 4 * arrows);
  for (size_t a = 0; a < arrows; ++a) {
    const Eigen::Vector2d start(vectors.x[3 * a], vectors.y[3 * a]);
    const Eigen::Vector2d tip(vectors.x[3 * a + 1], vectors.y[3 * a + 1]);
    EXPECT_EQ(heads.x[4 * a + 1], tip.x());
    EXPECT_EQ(heads.y[4 * a + 1], tip.y());
    for (size_t barb : {4 * a, 4 * a + 2}) {
      const Eigen::Vector2d end(heads.x[barb], heads.y[barb]);
      EXPECT_LT((end - tip).norm(), (tip - start).norm());
      // The barb points back along the shaft.
      EXPECT_LT((end - tip).dot(tip - start), 0.0);
    }
  }
  const plot::Series& outline = panel.series[8];
  EXPECT_EQ(outline.x, (std::vector<double>{0.0, 752.0, 752.0, 0.0, 0.0}));
  EXPECT_EQ(outline.y, (std::vector<double>{0.0, 0.0, 480.0, 480.0, 0.0}));
  // The panel shows a margin around the image, so the outline is not hidden by the frame.
  EXPECT_LT(panel.x.min, 0.0);
  EXPECT_GT(panel.x.max, 752.0);
  EXPECT_LT(panel.y.min, 0.0);
  EXPECT_GT(panel.y.max, 480.0);
}

// The values of every attribute `name="..."` in `text`.
std::vector<std::string> AttributeValues(const std::string& text, const std::string& name) {
  std::vector<std::string> values;
  const std::string key = " " + name + "=\"";
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const size_t from = at + key.size();
    values.push_back(text.substr(from, text.find('"', from) - from));
  }
  return values;
}

// Every coordinate the SVG draws inside the panels' clipped groups (polyline points and the
// absolute start of each path, "Mx y") lies inside its own panel: the 40 px errors, magnified,
// point far out of the image, and cam1's panel must not receive cam0's drawing or spill into it.
// (Parsed by hand: std::regex recurses per character and overflows the stack on these paths.)
TEST(MakeReprojectionImageFigure, NothingDrawnOutsideItsPanel) {
  const IntrinsicsResult result = TwoCameraResult();
  const ReprojectionImageFigure map = MakeReprojectionImageFigure(DataOf(result), 2000);
  ASSERT_GT(map.vector_gain, 1.0);  // the corner's arrows are drawn longer than the image allows
  const std::string svg = plot::RenderSvg(map.figure);
  const std::string panel_start = "<g transform=\"translate(";
  std::vector<size_t> groups;
  for (size_t at = svg.find(panel_start); at != std::string::npos;
       at = svg.find(panel_start, at + 1)) {
    groups.push_back(at);
  }
  ASSERT_EQ(groups.size(), 2u);
  int checked = 0;
  auto expect_inside = [&](double x, double y, size_t g) {
    EXPECT_GE(x, 0.0) << "panel " << g;
    EXPECT_LE(x, map.figure.panel_width) << "panel " << g;
    EXPECT_GE(y, 0.0) << "panel " << g;
    EXPECT_LE(y, map.figure.panel_height) << "panel " << g;
    ++checked;
  };
  for (size_t g = 0; g < groups.size(); ++g) {
    const size_t to = g + 1 < groups.size() ? groups[g + 1] : svg.size();
    const std::string body = svg.substr(groups[g], to - groups[g]);
    const size_t clipped = body.find("<g clip-path=");
    ASSERT_NE(clipped, std::string::npos);
    const std::string content = body.substr(clipped, body.find("</g>", clipped) - clipped);
    // Panel-local coordinates (the group translates them): within the panel's box.
    for (const std::string& points : AttributeValues(content, "points")) {
      std::istringstream pairs(points);
      std::string pair;
      while (pairs >> pair) {
        const size_t comma = pair.find(',');
        ASSERT_NE(comma, std::string::npos) << pair;
        expect_inside(std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1)), g);
      }
    }
    for (const std::string& path : AttributeValues(content, "d")) {
      for (size_t m = path.find('M'); m != std::string::npos; m = path.find('M', m + 1)) {
        std::istringstream start(path.substr(m + 1, 40));
        double x = 0.0, y = 0.0;
        ASSERT_TRUE(start >> x >> y) << path.substr(m, 40);
        expect_inside(x, y, g);
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace splinecal
