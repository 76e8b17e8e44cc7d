#include "splinecal/report/calibrate_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/axis_name.h"
#include "splinecal/calib/imu_covariance.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/lie/so3.h"
#include "splinecal/plot/plot_decimation.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/report/html_page.h"
#include "splinecal/report/imu_model_report.h"
#include "splinecal/report/option_names.h"
#include "splinecal/report/report_inputs.h"
#include "splinecal/report/reprojection_figures.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/string_printf.h"
#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/report/intrinsics_report.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

// A standard deviation; a quantity that was held fixed has none: "fixed", not NaN.
void WriteStdOrFixed(const std::string& key, bool estimated, double std_value, YamlWriter* yaml) {
  if (estimated) {
    yaml->Scalar(key, std_value);
  } else {
    yaml->Scalar(key, "fixed");
  }
}

void WriteCameraYaml(const CameraEstimate& c, YamlWriter* yaml) {
  yaml->Matrix("T_cam_imu", c.calibration.T_cam_imu.matrix());
  yaml->Vector("rotation_std_deg", c.rotation_std_deg);
  yaml->Vector("translation_std_m", c.translation_std_m);
  if (std::isfinite(c.baseline_m)) yaml->Scalar("baseline_m", c.baseline_m);
  if (std::isfinite(c.baseline_std_m)) yaml->Scalar("baseline_std_m", c.baseline_std_m);
  yaml->Scalar("timeshift_cam_imu", c.calibration.time_offset_s);
  yaml->Scalar("timeshift_estimated", c.time_offset_estimated);
  WriteStdOrFixed("timeshift_std_s", c.time_offset_estimated, c.time_offset_std_s, yaml);
  yaml->Scalar("line_delay", c.calibration.line_delay_s);
  yaml->Scalar("line_delay_estimated", c.line_delay_estimated);
  WriteStdOrFixed("line_delay_std", c.line_delay_estimated, c.line_delay_std_s, yaml);
  // The intrinsics used: how (held / prior / free), before (the camchain's) and after, the
  // prior's std and the estimate's, in Kalibr's order as camchain-imucam.yaml and `splinecal
  // intrinsics` write them.
  yaml->Scalar("intrinsics_mode", ParameterModeName(c.intrinsics_mode));
  yaml->Scalar("intrinsics_estimated", c.intrinsics_estimated);
  const Camera& camera = c.calibration.camera;
  const IntrinsicsVector values = camera.intrinsics();
  for (const auto& [key, order] :
       {std::pair<std::string, std::vector<int>>{"intrinsics", KalibrIntrinsicsOrder(camera)},
        std::pair<std::string, std::vector<int>>{"distortion_coeffs",
                                                 KalibrDistortionOrder(camera)}}) {
    auto pick = [&order = order](const IntrinsicsVector& v) {
      Eigen::VectorXd picked(order.size());
      for (size_t i = 0; i < order.size(); ++i) picked(i) = v(order[i]);
      return picked;
    };
    yaml->Vector(key, pick(values));
    yaml->Vector(key + "_before", pick(c.intrinsics_before));
    if (c.intrinsics_mode == ParameterMode::kPrior ||
        c.intrinsics_mode == ParameterMode::kConsider) {
      yaml->Vector(key + "_prior_std", pick(c.intrinsics_prior_std));
    }
    if (c.intrinsics_estimated) yaml->Vector(key + "_std", pick(c.intrinsics_std));
  }
  yaml->Scalar("reprojection_rms_px", c.reprojection_rms_px);
  yaml->Scalar("num_frames", c.num_frames);
  yaml->Scalar("num_observations", c.num_observations);
}

// "(std 0.0123 ms)" for an estimated quantity, "(fixed)" for one held at its given value (it has
// no standard deviation). An empty unit gives "std 0.0123" / "fixed" (table cells).
std::string StdText(bool estimated, double std_value, const std::string& unit) {
  if (unit.empty()) return estimated ? StringPrintf("std %.4f", std_value) : "fixed";
  return estimated ? StringPrintf("(std %.4f %s)", std_value, unit.c_str()) : "(fixed)";
}

// "a, b, c" with one printf format per component.
std::string Components(const char* format, const Eigen::Vector3d& v) {
  return StringPrintf(format, v.x()) + ", " + StringPrintf(format, v.y()) + ", " +
         StringPrintf(format, v.z());
}

// Two panels, gyro and accelerometer, of x, y, z series over the IMU samples' time (at most
// max_points of them): value(sample, sensor, axis), sensor 0 the gyro.
template <typename Value>
plot::Figure ImuAxesFigure(const CalibrationResult& r,
                           int max_points,
                           const std::string& gyro_label,
                           const std::string& accel_label,
                           Value value) {
  plot::Figure figure;
  const std::vector<size_t> keep = plot::DecimatedIndices(r.imu_samples.size(), max_points, true);
  for (int sensor = 0; sensor < 2; ++sensor) {
    plot::Panel& panel = plot::AddPanel(
        &figure, "", "time [s] (IMU spline)", sensor == 0 ? gyro_label : accel_label);
    for (int a = 0; a < 3; ++a) {
      plot::Series& series = panel.series.emplace_back();
      series.label = AxisName(a);
      series.line_width = 0.8;
      for (size_t k : keep) {
        const ImuResidualRecord& s = r.imu_samples[k];
        series.x.push_back(NanosecondsToSeconds(s.t_ns - r.layout.t0_ns));
        series.y.push_back(value(s, sensor, a));
      }
    }
  }
  return figure;
}

// Gyro and accelerometer residuals over time.
plot::Figure ImuFigure(const CalibrationResult& r, int max_points) {
  plot::Figure figure = ImuAxesFigure(r,
                                      max_points,
                                      "gyro residual [rad/s]",
                                      "accel residual [m/s^2]",
                                      [](const ImuResidualRecord& s, int sensor, int a) {
                                        return sensor == 0 ? s.gyro_error[a] : s.accel_error[a];
                                      });
  figure.title = "IMU residuals (predicted - measured)";
  figure.columns = 1;
  figure.panel_width = 880.0;
  figure.panel_height = 260.0;
  return figure;
}

// The biases over time (the bias spline's course), or their means as flat lines when the result
// carries no course (ImuResidualRecord::gyro_bias NaN).
plot::Figure BiasFigure(const CalibrationResult& r, int max_points, bool* course_recorded) {
  *course_recorded =
      std::any_of(r.imu_samples.begin(), r.imu_samples.end(), [](const ImuResidualRecord& s) {
        return s.gyro_bias.allFinite();
      });
  const bool course = *course_recorded;
  plot::Figure figure = ImuAxesFigure(r,
                                      max_points,
                                      "gyro bias [rad/s]",
                                      "accel bias [m/s^2]",
                                      [&r, course](const ImuResidualRecord& s, int sensor, int a) {
                                        if (!course)
                                          return sensor == 0 ? r.gyro_bias[a] : r.accel_bias[a];
                                        return sensor == 0 ? s.gyro_bias[a] : s.accel_bias[a];
                                      });
  figure.title = course ? "IMU biases over time" : "IMU biases (means only)";
  figure.columns = 2;
  figure.panel_width = 440.0;
  figure.panel_height = 260.0;
  return figure;
}

// The spline's position: top view and over time (about 3000 evaluations).
plot::Figure TrajectoryFigure(const CalibrationResult& r) {
  plot::Figure figure;
  figure.title = "IMU trajectory in the gravity-aligned world (spline.csv)";
  figure.columns = 2;
  plot::Panel& top = plot::AddPanel(&figure, "top view", "x [m]", "y [m]");
  top.equal_aspect = true;
  top.legend = plot::LegendPosition::kNone;
  plot::Panel& height =
      plot::AddPanel(&figure, "position over time", "time [s] (IMU spline)", "position [m]");
  const SE3Splined spline = r.MakeSpline();
  plot::Series& xy = top.series.emplace_back();
  std::vector<plot::Series> components(3);
  for (int a = 0; a < 3; ++a) components[a].label = AxisName(a);
  const int64_t step = std::max<int64_t>(1, (spline.end_time_ns() - spline.start_time_ns()) / 3000);
  for (int64_t t = spline.start_time_ns(); t <= spline.end_time_ns(); t += step) {
    const Eigen::Vector3d p = spline.PoseNs(t).translation();
    xy.x.push_back(p.x());
    xy.y.push_back(p.y());
    for (int a = 0; a < 3; ++a) {
      components[a].x.push_back(NanosecondsToSeconds(t - r.layout.t0_ns));
      components[a].y.push_back(p[a]);
    }
  }
  for (plot::Series& s : components) height.series.push_back(std::move(s));
  return figure;
}

// How the calibration ran: the command line and what it did with the camchain and the target.
std::string RunHtml(const CalibrationResult& r, const CalibrateOptions& options) {
  std::ostringstream html;
  html << "<h2>Run</h2>\n";
  if (!options.command_line.empty()) {
    html << "<p><code>" << plot::EscapeXml(options.command_line) << "</code></p>\n";
  }
  html << "<table>\n<tr><th>camera chain (T_cn_cnm1)</th><td>" << ParameterModeName(r.camera_chain)
       << "</td></tr>\n<tr><th>intrinsics</th><td>";
  for (size_t c = 0; c < r.cameras.size(); ++c) {
    html << (c > 0 ? ", " : "") << "cam" << c << " " << ParameterModeName(r.cameras[c].intrinsics_mode);
  }
  html << "</td></tr>\n<tr><th>target scale</th><td>" << TargetScaleModeName(r.target_scale_mode);
  if (std::isfinite(r.target_scale)) {
    html << StringPrintf(": %.4f (std %.4f) against the IMU", r.target_scale, r.target_scale_std)
         << (r.target_scale_mode == TargetScaleMode::kCheck ? ", then held at 1" : "");
  }
  html << "</td></tr>\n</table>\n";
  return html.str();
}

// The intrinsics used per camera: before (the camchain's) -> after with std, and the prior's std.
std::string IntrinsicsTable(const CalibrationResult& r) {
  std::ostringstream html;
  html << "<h2>Intrinsics</h2>\n<table>\n";
  for (size_t c = 0; c < r.cameras.size(); ++c) {
    const CameraEstimate& e = r.cameras[c];
    const Camera& camera = e.calibration.camera;
    html << "<tr><th colspan=4>cam" << c << " " << camera.model_name() << ": "
         << ParameterModeName(e.intrinsics_mode) << "</th></tr>\n"
         << "<tr><th>parameter</th><th>camchain (prior std)</th><th>used (std)</th><th>change"
            " [prior std]</th></tr>\n";
    std::vector<int> order = KalibrIntrinsicsOrder(camera);
    for (int i : KalibrDistortionOrder(camera)) order.push_back(i);
    const IntrinsicsVector after = camera.intrinsics();
    for (int i : order) {
      const char* format = i < kDistortionCoeffsIndex ? "%.4f" : "%.6g";
      html << "<tr><th>" << IntrinsicName(camera, i) << "</th><td>"
           << StringPrintf(format, e.intrinsics_before(i));
      if (std::isfinite(e.intrinsics_prior_std(i))) {
        html << " (" << StringPrintf("%.3g", e.intrinsics_prior_std(i)) << ")";
      }
      html << "</td><td>" << StringPrintf(format, after(i));
      if (std::isfinite(e.intrinsics_std(i))) {
        html << " (" << StringPrintf("%.3g", e.intrinsics_std(i)) << ")";
      }
      html << "</td><td>";
      if (std::isfinite(e.intrinsics_prior_std(i))) {
        html << StringPrintf("%+.2f", (after(i) - e.intrinsics_before(i)) / e.intrinsics_prior_std(i));
      } else {
        html << (e.intrinsics_estimated ? StringPrintf("%+.3g", after(i) - e.intrinsics_before(i))
                                        : std::string("held"));
      }
      html << "</td></tr>\n";
    }
  }
  html << "</table>\n";
  return html.str();
}

// The estimates: one block of rows per camera, then the IMU, the pixel noise and the model.
std::string EstimatesTable(const CalibrationResult& r, const CalibrateOptions& options) {
  std::ostringstream html;
  html << "<table>\n";
  for (size_t c = 0; c < r.cameras.size(); ++c) {
    const CameraEstimate& e = r.cameras[c];
    const Eigen::Vector3d rpy = e.calibration.T_cam_imu.so3().Log() * 180.0 / kPi;
    const Eigen::Vector3d t = e.calibration.T_cam_imu.translation();
    html << "<tr><th colspan=3>cam" << c << "</th></tr>\n";
    html << "<tr><th>T_cam_imu rotation vector [deg]</th><td>" << Components("%.4f", rpy)
         << "</td><td>std " << Components("%.4f", e.rotation_std_deg) << "</td></tr>\n";
    html << "<tr><th>T_cam_imu translation [mm]</th><td>" << Components("%.2f", 1e3 * t)
         << "</td><td>std " << Components("%.2f", 1e3 * e.translation_std_m) << "</td></tr>\n";
    html << "<tr><th>timeshift_cam_imu [ms]</th><td>"
         << StringPrintf("%.4f", 1e3 * e.calibration.time_offset_s) << "</td><td>"
         << StdText(e.time_offset_estimated, 1e3 * e.time_offset_std_s, "") << "</td></tr>\n";
    html << "<tr><th>line_delay [us/row]</th><td>"
         << StringPrintf("%.4f", 1e6 * e.calibration.line_delay_s) << "</td><td>"
         << StdText(e.line_delay_estimated, 1e6 * e.line_delay_std_s, "") << "</td></tr>\n";
    html << "<tr><th>reprojection RMS [px]</th><td>" << StringPrintf("%.3f", e.reprojection_rms_px)
         << "</td><td>" << e.num_observations << " points in " << e.num_frames
         << " frames</td></tr>\n";
  }
  html << "<tr><th>gyro bias [rad/s]</th><td colspan=2>" << Components("%.3e", r.gyro_bias)
       << "</td></tr>\n";
  html << "<tr><th>accel bias [m/s^2]</th><td colspan=2>" << Components("%.3e", r.accel_bias)
       << "</td></tr>\n";
  html << "<tr><th>IMU residual RMS</th><td colspan=2>gyro " << StringPrintf("%.3e", r.gyro_rms)
       << " rad/s, accel " << StringPrintf("%.3e", r.accel_rms) << " m/s^2</td></tr>\n";
  html << "<tr><th>pixel sigma [px]</th><td colspan=2>" << StringPrintf("%.3f", r.pixel_sigma_px)
       << (r.pixel_sigma_estimated ? " (estimated)" : " (given)") << "</td></tr>\n";
  html << "<tr><th>model</th><td colspan=2>"
       << (options.model.bias_model == BiasModel::kSpline ? "bias spline" : "constant biases")
       << ", knots every "
       << StringPrintf(
              "%.4g",
              r.knot_spacing_s > 0.0 ? r.knot_spacing_s : NanosecondsToSeconds(r.layout.dt_ns))
       << " s, Huber " << StringPrintf("%g", options.huber_px) << " px"
       << (options.rolling_shutter ? ", rolling shutter" : "") << ", trajectory "
       << TrajectoryModelName(r.trajectory) << "</td></tr>\n";
  html << "</table>\n";
  return html.str();
}

// The estimated IMU model with its standard deviations (Kalibr's imu-*.yaml keys; the stds per
// entry, NaN where an entry is not a parameter; C_gyro_i's as its rotation vector per axis).
void WriteImuModelEntries(const ImuCalibration& imu, const ImuModelStd& s, YamlWriter* yaml) {
  const ImuIntrinsicsd& p = imu.intrinsics;
  yaml->BeginMap("accelerometers");
  yaml->Matrix("M", p.M_a);
  yaml->Matrix("M_std", s.M_a);
  if (imu.model == ImuModelKind::kScaleMisalignmentSizeEffect) {
    yaml->Vector("ry_i", p.ry_i);
    yaml->Vector("ry_i_std", s.ry_i);
    yaml->Vector("rz_i", p.rz_i);
    yaml->Vector("rz_i_std", s.rz_i);
  }
  yaml->EndMap();
  yaml->BeginMap("gyroscopes");
  yaml->Matrix("M", p.M_g);
  yaml->Matrix("M_std", s.M_g);
  yaml->Matrix("A", p.A);
  yaml->Matrix("A_std", s.A);
  yaml->Matrix("C_gyro_i", p.C_gyro_i);
  yaml->Vector("C_gyro_i_std_deg", s.C_gyro_i_deg);
  yaml->EndMap();
}

// The joint covariance of an IMU's estimated parameters (calib/imu_covariance.h): `entries`, the
// names of its rows in order, and `matrix`, SI units, rotation vectors in radians. Nothing when
// empty.
void WriteImuCovarianceYaml(const ImuCovariance& covariance, YamlWriter* yaml) {
  if (covariance.empty()) return;
  std::vector<std::string> names;
  for (const ImuCovarianceEntry& entry : covariance.entries) {
    names.push_back(ImuCovarianceEntryName(entry));
  }
  yaml->BeginMap("covariance");
  yaml->StringList("entries", names);
  yaml->Matrix("matrix", covariance.matrix);
  yaml->EndMap();
}

void WriteImuModelYaml(const CalibrationResult& r, YamlWriter* yaml) {
  yaml->BeginMap("imu_model");
  yaml->Scalar("model", ImuModelName(r.imu_model.model));
  WriteImuModelEntries(r.imu_model, r.imu_model_std, yaml);
  WriteImuCovarianceYaml(r.imu_model_covariance, yaml);
  yaml->EndMap();
}

// The further IMUs (several IMUs), imu1, imu2, ...: Kalibr's T_i_b and time_offset with their
// stds (C_i_b's in its right tangent, b axes; r_b per axis), the biases and residuals.
void WriteFurtherImusYaml(const CalibrationResult& r, YamlWriter* yaml) {
  for (size_t i = 0; i < r.further_imus.size(); ++i) {
    const FurtherImuEstimate& e = r.further_imus[i];
    const ImuIntrinsicsd& p = e.calibration.intrinsics;
    Eigen::Matrix4d T_i_b = Eigen::Matrix4d::Identity();
    T_i_b.topLeftCorner<3, 3>() = p.C_i_b;
    T_i_b.topRightCorner<3, 1>() = -p.C_i_b * p.r_b;  // T_i_b = [C_i_b, -C_i_b r_b]
    yaml->BeginMap("imu" + std::to_string(i + 1));
    yaml->Scalar("name", e.name);
    yaml->Scalar("model", ImuModelName(e.calibration.model));
    yaml->Matrix("T_i_b", T_i_b);
    yaml->Vector("C_i_b_std_deg", e.rotation_std_deg);
    yaml->Vector("r_b", p.r_b);
    yaml->Vector("r_b_std_m", e.r_b_std_m);
    yaml->Scalar("lever_arm_held", e.lever_arm_held);
    yaml->Scalar("time_offset", e.calibration.time_offset_s);
    yaml->Scalar("time_offset_std_s", e.time_offset_std_s);
    yaml->Scalar("initial_time_offset", e.initial_time_offset_s);
    if (e.calibration.model != ImuModelKind::kCalibrated) {
      WriteImuModelEntries(e.calibration, e.model_std, yaml);
    }
    yaml->Vector("gyro_bias", e.gyro_bias);
    yaml->Vector("accel_bias", e.accel_bias);
    yaml->Scalar("gyro_rms", e.gyro_rms);
    yaml->Scalar("accel_rms", e.accel_rms);
    yaml->Scalar("num_samples", e.num_samples);
    yaml->Scalar("rate_hz", e.rate_hz);
    yaml->Scalar("gyroscope_noise_density", e.noise.gyroscope_noise_density);
    yaml->Scalar("gyroscope_random_walk", e.noise.gyroscope_random_walk);
    yaml->Scalar("accelerometer_noise_density", e.noise.accelerometer_noise_density);
    yaml->Scalar("accelerometer_random_walk", e.noise.accelerometer_random_walk);
    WriteImuCovarianceYaml(e.covariance, yaml);
    yaml->EndMap();
  }
}

// The further IMUs' lines of the summary and the report.
std::string FurtherImusText(const CalibrationResult& r) {
  std::string text;
  for (size_t i = 0; i < r.further_imus.size(); ++i) {
    const FurtherImuEstimate& e = r.further_imus[i];
    const Eigen::Vector3d phi = SO3d::FromMatrix(e.calibration.intrinsics.C_i_b).Log() * kRadToDeg;
    const Eigen::Vector3d r_b = 1e3 * e.calibration.intrinsics.r_b;
    text += StringPrintf("imu%zu (%s): C_i_b rotation vector [%.4f %.4f %.4f] deg, std [%.4f %.4f %.4f] deg\n",
                         i + 1, e.name.c_str(), phi.x(), phi.y(), phi.z(), e.rotation_std_deg.x(),
                         e.rotation_std_deg.y(), e.rotation_std_deg.z());
    text += StringPrintf("  r_b [%.2f %.2f %.2f] mm, std [%.2f %.2f %.2f] mm%s\n", r_b.x(), r_b.y(),
                         r_b.z(), 1e3 * e.r_b_std_m.x(), 1e3 * e.r_b_std_m.y(),
                         1e3 * e.r_b_std_m.z(), e.lever_arm_held ? " (held)" : "");
    text += StringPrintf("  time_offset %.6f ms, std %.6f ms\n", 1e3 * e.calibration.time_offset_s,
                         1e3 * e.time_offset_std_s);
    text += StringPrintf("  gyro RMS %.3e rad/s, accel RMS %.3e m/s^2 over %d samples\n",
                         e.gyro_rms, e.accel_rms, e.num_samples);
  }
  return text;
}

}  // namespace

std::string CalibrateResultYaml(const CalibrationResult& r, const CalibrateOptions& options) {
  YamlWriter yaml;
  yaml.Comment(
      "splinecal calibrate: cam0's estimates at the top level (every camera under "
      "cameras); T_cam_imu maps IMU points into the camera; t_imu = t_cam + "
      "timeshift_cam_imu; row r is exposed at t_frame + r * line_delay; stds in the "
      "right tangent of T_cam_imu (rotation, IMU frame) and of t_cam_imu (camera frame)");
  WriteCameraYaml(r.cameras[0], &yaml);
  yaml.Vector("gyro_bias", r.gyro_bias);
  yaml.Vector("gyro_bias_std", r.gyro_bias_std);
  yaml.Vector("accel_bias", r.accel_bias);
  yaml.Vector("accel_bias_std", r.accel_bias_std);
  // spline.csv is T_w_s in the gravity-aligned world w; T_w_target maps the target's frame (the
  // one solved in) into it, and gravity_target is the estimated gravity there.
  yaml.Scalar("spline_frame", "gravity-aligned world w: z up, yaw from the target (T_w_target)");
  yaml.Vector("gravity_w", r.gravity_w);
  yaml.Vector("gravity_target", r.gravity_target);
  yaml.Matrix("T_w_target", r.T_w_target.matrix());
  // cam0's reprojection_rms_px is above; this one pools every camera.
  yaml.Scalar("reprojection_rms_px_all_cameras", r.reprojection_rms_px);
  yaml.Scalar("pixel_sigma_px", r.pixel_sigma_px);
  yaml.Scalar("pixel_sigma_estimated", r.pixel_sigma_estimated);
  WriteImuNoiseYaml(r.imu_noise, &yaml);
  // The largest factor by which a reported std exceeds the noise model's (docs/calibrate.md,
  // "How much to trust the numbers").
  yaml.Scalar("std_inflation", r.std_inflation);
  yaml.Scalar("robust_clusters", r.robust_clusters);
  yaml.Scalar("view_clusters", r.view_clusters);
  yaml.Scalar("gyro_rms", r.gyro_rms);
  yaml.Scalar("accel_rms", r.accel_rms);
  yaml.Scalar("num_imu_samples", r.num_imu_samples);
  yaml.Scalar("imu_rate_hz", r.imu_rate_hz);
  yaml.Scalar("num_landmarks", r.num_landmarks);
  yaml.Scalar("knot_spacing_s", NanosecondsToSeconds(r.layout.dt_ns));
  yaml.Scalar("knot_spacing_rule", r.knot_spacing_rule);
  yaml.Scalar("trajectory", TrajectoryModelName(r.trajectory));
  yaml.Scalar("bias_model", NameOf(kBiasModelNames, options.model.bias_model));
  yaml.Scalar("rolling_shutter", options.rolling_shutter);
  yaml.Scalar("huber_px", options.huber_px);
  yaml.Scalar("iterations", r.solve.iterations);
  yaml.Scalar("rounds", r.solve.rounds);
  yaml.Scalar("initialisation_time_s", r.initialisation_time_s);
  yaml.Scalar("solve_time_s", r.solve.solve_time_s);
  yaml.Scalar("covariance_time_s", r.covariance_time_s);
  yaml.Scalar("covariance_ok", r.covariance_ok);
  yaml.Scalar("termination", r.solve.termination);
  // How the camchain and the target were used (docs/calibrate.md, "Intrinsics and camera chain",
  // "The target's scale").
  yaml.Scalar("camera_chain", ParameterModeName(r.camera_chain));
  yaml.Scalar("target_scale_mode", TargetScaleModeName(r.target_scale_mode));
  yaml.Scalar("target_scale", r.target_scale);
  yaml.Scalar("target_scale_std", r.target_scale_std);
  yaml.Scalar("target_scale_used", r.target_scale_used);
  if (!options.command_line.empty()) yaml.Scalar("command_line", options.command_line);
  if (r.imu_model.model != ImuModelKind::kCalibrated) WriteImuModelYaml(r, &yaml);
  WriteFurtherImusYaml(r, &yaml);
  if (r.cameras.size() > 1) {
    yaml.BeginMap("cameras");
    for (size_t c = 0; c < r.cameras.size(); ++c) {
      yaml.BeginMap("cam" + std::to_string(c));
      WriteCameraYaml(r.cameras[c], &yaml);
      yaml.EndMap();
    }
    yaml.EndMap();
  }
  yaml.StringList("warnings", r.warnings);
  return yaml.str();
}

std::string CalibrateReprojectionCsv(const CalibrationResult& r) {
  std::ostringstream out;
  out << "#t_ns,cam_id,point_id,u,v,error_u,error_v\n";
  for (const ReprojectionSample& s : r.reprojection_samples) {
    out << s.t_ns << ',' << s.cam_id << ',' << s.point_id << ',' << FormatDouble(s.uv.x()) << ','
        << FormatDouble(s.uv.y()) << ',' << FormatDouble(s.error.x()) << ','
        << FormatDouble(s.error.y()) << '\n';
  }
  return out.str();
}

std::string CalibrateReportHtml(const CalibrationResult& r,
                                const CalibrateOptions& options,
                                const CalibrateReportInputs& inputs,
                                int max_points) {
  HtmlPage page("splinecal calibrate", kCalibrationReportCss);
  page.Append(InputFilesHtml({{"IMU", inputs.imu_path},
                              {"observations", inputs.observations_path},
                              {"camchain", inputs.camchain_path},
                              {"target", inputs.target_path},
                              {"initial poses", inputs.initial_poses_path}}));
  page.Append(ImuNoiseTableHtml(r.imu_noise, inputs.imu_yaml_path));
  page.Append(RunHtml(r, options));
  page.Append(EstimatesTable(r, options));
  page.Append(IntrinsicsTable(r));
  page.Append(ImuModelHtml(r));
  if (!r.further_imus.empty()) {
    page.Append("<h2>Further IMUs</h2>\n<pre>" + FurtherImusText(r) + "</pre>\n");
  }
  page.ListSection("Warnings", r.warnings);
  page.FigureSection("Reprojection", ReprojectionErrorFigure(ReprojectionDataOf(r), max_points));
  ReprojectionImageFigure by_position = MakeReprojectionImageFigure(ReprojectionDataOf(r), max_points);
  page.FigureSection("Reprojection by image position", std::move(by_position.figure));
  page.Append(by_position.key_html);
  page.FigureSection("IMU", ImuFigure(r, max_points));
  bool course_recorded = false;
  plot::Figure biases = BiasFigure(r, max_points, &course_recorded);
  page.FigureSection("IMU biases", std::move(biases));
  if (!course_recorded) {
    page.Append("<p>This result carries the biases' time averages only: drawn flat.</p>\n");
  }
  page.FigureSection("Trajectory", TrajectoryFigure(r));
  return page.str();
}

std::string CalibrateSummaryText(const CalibrationResult& result) {
  std::string text;
  for (size_t c = 0; c < result.cameras.size(); ++c) {
    const CameraEstimate& e = result.cameras[c];
    const Eigen::Matrix4d T = e.calibration.T_cam_imu.matrix();
    text += StringPrintf("cam%zu T_cam_imu:\n", c);
    for (int row = 0; row < 4; ++row) {
      text += StringPrintf(
          "  [%12.9f %12.9f %12.9f %12.9f]\n", T(row, 0), T(row, 1), T(row, 2), T(row, 3));
    }
    text +=
        StringPrintf("  rotation std [%.4f %.4f %.4f] deg, translation std [%.2f %.2f %.2f] mm\n",
                     e.rotation_std_deg.x(),
                     e.rotation_std_deg.y(),
                     e.rotation_std_deg.z(),
                     1e3 * e.translation_std_m.x(),
                     1e3 * e.translation_std_m.y(),
                     1e3 * e.translation_std_m.z());
    text += StringPrintf("  timeshift_cam_imu %.6f ms ", 1e3 * e.calibration.time_offset_s) +
            StdText(e.time_offset_estimated, 1e3 * e.time_offset_std_s, "ms") + "\n";
    text += StringPrintf("  line_delay %.4f us/row ", 1e6 * e.calibration.line_delay_s) +
            StdText(e.line_delay_estimated, 1e6 * e.line_delay_std_s, "us") + "\n";
    text += std::string("  intrinsics ") + ParameterModeName(e.intrinsics_mode) + "\n";
    text += StringPrintf("  reprojection RMS %.3f px over %d points in %d frames\n",
                         e.reprojection_rms_px,
                         e.num_observations,
                         e.num_frames);
  }
  text += StringPrintf("gyro RMS %.3e rad/s, accel RMS %.3e m/s^2, pixel sigma %.3f px%s\n",
                       result.gyro_rms,
                       result.accel_rms,
                       result.pixel_sigma_px,
                       result.pixel_sigma_estimated ? " (estimated)" : "");
  text += ImuModelText(result);
  text += FurtherImusText(result);
  if (std::isfinite(result.target_scale)) {
    text += StringPrintf("target scale against the IMU %.4f (std %.4f)%s\n",
                         result.target_scale,
                         result.target_scale_std,
                         result.target_scale_mode == TargetScaleMode::kCheck ? ", held at 1" : "");
  }
  for (const std::string& w : result.warnings) text += "warning: " + w + "\n";
  return text;
}

}  // namespace splinecal
