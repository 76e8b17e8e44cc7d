#include "splinecal/report/fit_report.h"

#include <string>
#include <vector>

#include "splinecal/axis_name.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/plot_decimation.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/report/html_page.h"
#include "splinecal/report/option_names.h"
#include "splinecal/report/report_inputs.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

void Append3(const Eigen::Vector3d& v, std::string* row) {
  for (int a = 0; a < 3; ++a) *row += "," + FormatDouble(v[a]);
}

std::string Fixed(double value, int digits) { return StringPrintf("%.*g", digits, value); }

std::string VectorText(const Eigen::Vector3d& v, int digits) {
  return "[" + Fixed(v[0], digits) + ", " + Fixed(v[1], digits) + ", " + Fixed(v[2], digits) + "]";
}

const char* const kAxisColors[3] = {"#d62728", "#2ca02c", "#1f77b4"};

// One series per axis x, y, z on `panel` (kAxisColors, otherwise drawn as `style`): value(sample,
// axis) against seconds(sample.t_ns), for the samples at the indices `keep`.
template <typename Sample, typename Seconds, typename Value>
void AddAxisSeries(const plot::Series& style,
                   const std::vector<Sample>& samples,
                   const std::vector<size_t>& keep,
                   const Seconds& seconds,
                   const Value& value,
                   plot::Panel* panel) {
  for (int a = 0; a < 3; ++a) {
    plot::Series& series = panel->series.emplace_back(style);
    series.label = AxisName(a);
    series.color = kAxisColors[a];
    for (size_t i : keep) {
      series.x.push_back(seconds(samples[i].t_ns));
      series.y.push_back(value(samples[i], a));
    }
  }
}

}  // namespace

std::string FitResultYaml(const FitResult& r, const FitReportInputs& inputs) {
  YamlWriter yaml;
  yaml.Comment("splinecal fit: IMU biases, gravity, time offset and extrinsic from IMU + poses");
  yaml.Scalar("imu", inputs.imu_path);
  yaml.Scalar("poses", inputs.poses_path);
  yaml.Scalar(
      "imu_yaml",
      inputs.imu_yaml_path.empty() ? std::string("(ADIS16448 defaults)") : inputs.imu_yaml_path);
  yaml.Scalar("bias_model", NameOf(kBiasModelNames, r.bias_model));
  if (r.bias_model == BiasModel::kSpline) {
    yaml.Comment("bias spline: gyro_bias / accel_bias are its time averages over the IMU samples");
  }
  yaml.Vector("gyro_bias", r.gyro_bias);
  yaml.Vector("gyro_bias_std", r.gyro_bias_std);
  yaml.Vector("accel_bias", r.accel_bias);
  yaml.Vector("accel_bias_std", r.accel_bias_std);
  yaml.Comment("gravity in the pose source's world frame (points down, norm g)");
  yaml.Vector("gravity_w", r.gravity_w);
  yaml.Vector("gravity_w_std", r.gravity_w_std);
  yaml.Scalar("gravity_direction_std_deg", r.gravity_direction_std_deg);
  yaml.Comment("t_imu = t_pose + time_offset_s");
  yaml.Scalar("time_offset_s", r.time_offset_s);
  yaml.Scalar("time_offset_estimated", r.time_offset_estimated);
  if (r.time_offset_estimated) yaml.Scalar("time_offset_s_std", r.time_offset_std_s);
  if (r.extrinsic_estimated) {
    yaml.Comment("T_pose_imu = T_m_s maps IMU-frame points into the pose source's body frame");
    yaml.Matrix("T_pose_imu", r.T_m_s.matrix());
    yaml.BeginMap("T_pose_imu_std");
    yaml.Comment("right tangent of T_pose_imu: T Exp([rho; phi])");
    yaml.Vector("translation_m", r.T_m_s_translation_std_m);
    yaml.Vector("rotation_rad", r.T_m_s_rotation_std_rad);
    yaml.EndMap();
  }
  yaml.Scalar("covariance_ok", r.covariance_ok);
  // The largest factor by which a reported std exceeds the noise model's (docs/fit.md).
  yaml.Scalar("std_inflation", r.std_inflation);
  yaml.Scalar("robust_clusters", r.robust_clusters);
  yaml.StringList("not_determined", r.not_determined);
  yaml.Comment("per-axis RMS of the residuals, and the per-axis noise std the weights assumed");
  yaml.BeginMap("residual_rms");
  yaml.Scalar("gyro_rad_s", r.residual_rms.gyro_rad_s);
  yaml.Scalar("accel_m_s2", r.residual_rms.accel_m_s2);
  yaml.Scalar("position_m", r.residual_rms.position_m);
  yaml.Scalar("rotation_rad", r.residual_rms.rotation_rad);
  yaml.EndMap();
  WriteImuNoiseYaml(r.imu_noise, &yaml);
  yaml.BeginMap("noise_std");
  yaml.Scalar("gyro_rad_s", r.noise_std.gyro_rad_s);
  yaml.Scalar("accel_m_s2", r.noise_std.accel_m_s2);
  yaml.Scalar("position_m", r.noise_std.position_m);
  yaml.Scalar("rotation_rad", r.noise_std.rotation_rad);
  yaml.EndMap();
  yaml.Scalar("iterations", r.solve.iterations);
  yaml.Scalar("initial_cost", r.solve.initial_cost);
  yaml.Scalar("final_cost", r.solve.final_cost);
  yaml.Scalar("solve_time_s", r.solve.solve_time_s);
  yaml.Scalar("covariance_time_s", r.covariance_time_s);
  yaml.Scalar("termination", r.solve.termination);
  yaml.Scalar("linear_solver", r.solve.linear_solver);
  yaml.Scalar("covariance_method", r.covariance_method);
  yaml.Scalar("knot_spacing_s", r.knot_spacing_s);
  yaml.Scalar("knot_spacing_rule", r.knot_spacing_rule);
  yaml.Scalar("trajectory", TrajectoryModelName(r.trajectory));
  yaml.Scalar("num_control_poses", r.layout.num_control_poses);
  yaml.Scalar("spline_t0_ns", r.layout.t0_ns);
  yaml.Scalar("imu_rate_hz", r.imu_rate_hz);
  yaml.Scalar("num_imu_samples", r.num_imu_samples);
  yaml.Scalar("num_poses", r.num_poses);
  yaml.StringList("warnings", r.warnings);
  return yaml.str();
}

std::string FitResidualsCsv(const FitResult& r) {
  std::string csv =
      "#t_ns,gyro_res_x,gyro_res_y,gyro_res_z,accel_res_x,accel_res_y,accel_res_z,"
      "gyro_meas_x,gyro_meas_y,gyro_meas_z,gyro_fit_x,gyro_fit_y,gyro_fit_z,"
      "accel_meas_x,accel_meas_y,accel_meas_z,accel_fit_x,accel_fit_y,accel_fit_z,"
      "gyro_bias_x,gyro_bias_y,gyro_bias_z,accel_bias_x,accel_bias_y,accel_bias_z\n";
  csv.reserve(csv.size() + r.imu_samples.size() * 25 * 24);
  for (const FitImuSample& s : r.imu_samples) {
    std::string row = std::to_string(s.t_ns);
    Append3(s.gyro_fitted - s.gyro_measured, &row);
    Append3(s.accel_fitted - s.accel_measured, &row);
    Append3(s.gyro_measured, &row);
    Append3(s.gyro_fitted, &row);
    Append3(s.accel_measured, &row);
    Append3(s.accel_fitted, &row);
    Append3(s.gyro_bias, &row);
    Append3(s.accel_bias, &row);
    csv += row + "\n";
  }
  return csv;
}

std::string FitPoseResidualsCsv(const FitResult& r) {
  std::string csv =
      "#t_ns,position_err_x,position_err_y,position_err_z,"
      "rotation_err_x,rotation_err_y,rotation_err_z\n";
  for (const FitPoseSample& s : r.pose_samples) {
    std::string row = std::to_string(s.t_ns);
    Append3(s.position_error_m, &row);
    Append3(s.rotation_error_rad, &row);
    csv += row + "\n";
  }
  return csv;
}

std::string FitReportHtml(const FitResult& r, const FitReportInputs& inputs, int max_points) {
  const std::vector<FitImuSample>& imu = r.imu_samples;
  const int64_t t_ref = imu.empty() ? r.layout.t0_ns : imu.front().t_ns;
  auto seconds = [t_ref](int64_t t_ns) { return NanosecondsToSeconds(t_ns - t_ref); };
  const std::vector<size_t> keep =
      plot::DecimatedIndices(imu.size(), max_points, /*keep_last=*/true);

  // Measured against fitted, one panel per axis.
  auto measured_vs_fitted = [&](bool gyro) {
    plot::Figure figure;
    figure.title = gyro ? "Gyroscope: measured and fitted" : "Accelerometer: measured and fitted";
    figure.columns = 1;
    figure.panel_width = 900.0;
    figure.panel_height = 220.0;
    for (int a = 0; a < 3; ++a) {
      plot::Panel& panel = plot::AddPanel(
          &figure,
          "",
          "time since the first IMU sample [s]",
          std::string(gyro ? "gyro " : "accel ") + AxisName(a) + (gyro ? " [rad/s]" : " [m/s^2]"));
      plot::Series& measured = panel.series.emplace_back();
      measured.label = "measured";
      measured.color = "#999999";
      measured.line_width = 1.0;
      plot::Series& fitted = panel.series.emplace_back();
      fitted.label = "fitted";
      fitted.color = kAxisColors[a];
      for (size_t i : keep) {
        const FitImuSample& s = imu[i];
        measured.x.push_back(seconds(s.t_ns));
        measured.y.push_back(gyro ? s.gyro_measured[a] : s.accel_measured[a]);
        fitted.x.push_back(seconds(s.t_ns));
        fitted.y.push_back(gyro ? s.gyro_fitted[a] : s.accel_fitted[a]);
      }
    }
    return figure;
  };

  // Residuals over time.
  plot::Figure residuals;
  residuals.title = "Residuals (fitted - measured) over time";
  residuals.columns = 1;
  residuals.panel_width = 900.0;
  residuals.panel_height = 240.0;
  plot::Series thin_line;
  thin_line.line_width = 1.0;
  for (int sensor = 0; sensor < 2; ++sensor) {
    plot::Panel& panel =
        plot::AddPanel(&residuals,
                       "",
                       "time since the first IMU sample [s]",
                       sensor == 0 ? "gyro residual [rad/s]" : "accel residual [m/s^2]");
    AddAxisSeries(
        thin_line,
        imu,
        keep,
        seconds,
        [sensor](const FitImuSample& s, int a) {
          return sensor == 0 ? s.gyro_fitted[a] - s.gyro_measured[a]
                             : s.accel_fitted[a] - s.accel_measured[a];
        },
        &panel);
  }
  const std::vector<size_t> keep_poses =
      plot::DecimatedIndices(r.pose_samples.size(), max_points, /*keep_last=*/true);
  plot::Series dots;
  dots.line = false;
  dots.marker = plot::Marker::kCircle;
  dots.marker_size = 1.5;
  for (int kind = 0; kind < 2; ++kind) {
    plot::Panel& panel =
        plot::AddPanel(&residuals,
                       "",
                       "pose time, shifted like the IMU axis [s]",
                       kind == 0 ? "pose position error [m]" : "pose rotation error [deg]");
    AddAxisSeries(
        dots,
        r.pose_samples,
        keep_poses,
        seconds,
        [kind](const FitPoseSample& s, int a) {
          return kind == 0 ? s.position_error_m[a] : kRadToDeg * s.rotation_error_rad[a];
        },
        &panel);
  }

  // Biases over time (with +-1 std bands for the constant model).
  plot::Figure biases;
  biases.title = std::string("Biases (") + NameOf(kBiasModelNames, r.bias_model) + " model)";
  biases.columns = 2;
  biases.panel_width = 450.0;
  biases.panel_height = 260.0;
  for (int sensor = 0; sensor < 2; ++sensor) {
    plot::Panel& panel = plot::AddPanel(&biases,
                                        "",
                                        "time since the first IMU sample [s]",
                                        sensor == 0 ? "gyro bias [rad/s]" : "accel bias [m/s^2]");
    AddAxisSeries(
        plot::Series(),
        imu,
        keep,
        seconds,
        [sensor](const FitImuSample& s, int a) {
          return sensor == 0 ? s.gyro_bias[a] : s.accel_bias[a];
        },
        &panel);
  }

  std::string html = InputFilesHtml({{"IMU", inputs.imu_path}, {"poses", inputs.poses_path}});
  html += ImuNoiseTableHtml(r.imu_noise, inputs.imu_yaml_path);
  html += "<table><tr><th>quantity</th><th>estimate</th><th>std</th></tr>\n";
  auto row = [&html](const std::string& name, const std::string& value, const std::string& std) {
    html += "<tr><td>" + plot::EscapeXml(name) + "</td><td>" + plot::EscapeXml(value) +
            "</td><td>" + plot::EscapeXml(std) + "</td></tr>\n";
  };
  row("gyro bias [rad/s]", VectorText(r.gyro_bias, 6), VectorText(r.gyro_bias_std, 3));
  row("accel bias [m/s^2]", VectorText(r.accel_bias, 6), VectorText(r.accel_bias_std, 3));
  row("gravity_w [m/s^2]",
      VectorText(r.gravity_w, 6),
      Fixed(r.gravity_direction_std_deg, 3) + " deg (direction)");
  if (r.time_offset_estimated) {
    row("time offset [ms]", Fixed(1e3 * r.time_offset_s, 6), Fixed(1e3 * r.time_offset_std_s, 3));
  }
  if (r.extrinsic_estimated) {
    row("T_pose_imu translation [m]",
        VectorText(r.T_m_s.translation(), 6),
        VectorText(r.T_m_s_translation_std_m, 3));
    row("T_pose_imu rotation vector [deg]",
        VectorText(kRadToDeg * r.T_m_s.so3().Log(), 6),
        VectorText(kRadToDeg * r.T_m_s_rotation_std_rad, 3));
  }
  row("residual RMS gyro [rad/s]",
      Fixed(r.residual_rms.gyro_rad_s, 4),
      "noise " + Fixed(r.noise_std.gyro_rad_s, 4));
  row("residual RMS accel [m/s^2]",
      Fixed(r.residual_rms.accel_m_s2, 4),
      "noise " + Fixed(r.noise_std.accel_m_s2, 4));
  row("residual RMS position [m]",
      Fixed(r.residual_rms.position_m, 4),
      "noise " + Fixed(r.noise_std.position_m, 4));
  row("residual RMS rotation [rad]",
      Fixed(r.residual_rms.rotation_rad, 4),
      "noise " + Fixed(r.noise_std.rotation_rad, 4));
  row("knot spacing [s]", Fixed(r.knot_spacing_s, 6), r.knot_spacing_rule);
  row("trajectory model", TrajectoryModelName(r.trajectory), "");
  row("solver",
      std::to_string(r.solve.iterations) + " iterations, " + Fixed(r.solve.solve_time_s, 3) + " s",
      r.solve.termination);
  html += "</table>\n";
  HtmlPage page("splinecal fit",
                "body{max-width:960px;margin:auto}td,th{padding:2px 8px;text-align:left}"
                ".warn{color:#a00}");
  page.Append(html);
  page.ListSection("Warnings", r.warnings, "warn");
  if (!imu.empty()) {
    page.FigureSection("Gyroscope", measured_vs_fitted(true));
    page.FigureSection("Accelerometer", measured_vs_fitted(false));
    page.FigureSection("Residuals", residuals);
    page.FigureSection("Biases", biases);
  }
  return page.str();
}

}  // namespace splinecal
