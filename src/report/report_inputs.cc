#include "splinecal/report/report_inputs.h"

#include <string>
#include <vector>

#include "splinecal/plot/svg_plot.h"
#include "splinecal/string_printf.h"

namespace splinecal {

std::string InputFilesHtml(const std::vector<ReportInput>& inputs) {
  std::string lines;
  for (const auto& [label, path] : inputs) {
    if (path.empty()) continue;
    if (!lines.empty()) lines += "<br>";
    lines += plot::EscapeXml(label) + ": " + plot::EscapeXml(path);
  }
  return lines.empty() ? std::string() : "<p>" + lines + "</p>\n";
}

std::string NoiseSourceText(const std::string& imu_yaml_path) {
  return imu_yaml_path.empty() ? "ADIS16448 defaults (EuRoC), no --imu-yaml given" : imu_yaml_path;
}

std::string ImuNoiseTableHtml(const ImuNoise& noise, const std::string& imu_yaml_path) {
  std::string html =
      "<table><caption>IMU noise model: " + plot::EscapeXml(NoiseSourceText(imu_yaml_path)) +
      "</caption>\n";
  auto row = [&html](const char* key, double value, const char* unit) {
    html += StringPrintf("<tr><td>%s</td><td>%.6g</td><td>%s</td></tr>\n", key, value, unit);
  };
  row("gyroscope_noise_density", noise.gyroscope_noise_density, "rad/s/sqrt(Hz)");
  row("gyroscope_random_walk", noise.gyroscope_random_walk, "rad/s^2/sqrt(Hz)");
  row("accelerometer_noise_density", noise.accelerometer_noise_density, "m/s^2/sqrt(Hz)");
  row("accelerometer_random_walk", noise.accelerometer_random_walk, "m/s^3/sqrt(Hz)");
  // The weights use the IMU's measured rate (sigma = density sqrt(rate)); this is the file's.
  row("update_rate (as given)", noise.update_rate_hz, "Hz");
  return html + "</table>\n";
}

}  // namespace splinecal
