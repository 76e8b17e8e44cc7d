#include "splinecal/io/kalibr_yaml.h"

#include "splinecal/io/yaml_document.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Densities and rates beyond these are refused as implausible (a corrupt file, or a variance
// where a density belongs): real IMUs are below 1 in every unit and below 10 kHz.
constexpr double kMaxDensity = 1e3;
constexpr double kMaxRateHz = 1e6;

}  // namespace

ImuNoise ReadImuYaml(const std::string& path) {
  const YamlDocument yaml(path);
  yaml.CheckTypos("",
                  {"accelerometer_noise_density",
                   "accelerometer_random_walk",
                   "gyroscope_noise_density",
                   "gyroscope_random_walk",
                   "update_rate",
                   "rate_hz",
                   "rostopic"});
  ImuNoise noise;
  noise.accelerometer_noise_density =
      yaml.PositiveNumber("accelerometer_noise_density", kMaxDensity, "m/s^2/sqrt(Hz)");
  noise.accelerometer_random_walk =
      yaml.PositiveNumber("accelerometer_random_walk", kMaxDensity, "m/s^3/sqrt(Hz)");
  noise.gyroscope_noise_density =
      yaml.PositiveNumber("gyroscope_noise_density", kMaxDensity, "rad/s/sqrt(Hz)");
  noise.gyroscope_random_walk =
      yaml.PositiveNumber("gyroscope_random_walk", kMaxDensity, "rad/s^2/sqrt(Hz)");
  if (yaml.Has("update_rate")) {
    noise.update_rate_hz = yaml.PositiveNumber("update_rate", kMaxRateHz, "Hz");
  } else if (yaml.Has("rate_hz")) {
    noise.update_rate_hz = yaml.PositiveNumber("rate_hz", kMaxRateHz, "Hz");
  }
  return noise;
}

std::string ImuYamlText(const ImuNoise& noise, const std::string& rostopic) {
  std::string text;
  text += "# IMU noise in Kalibr's continuous-time densities (written by splinecal)\n";
  text += "accelerometer_noise_density: " + FormatDouble(noise.accelerometer_noise_density) +
          "  # [m/s^2/sqrt(Hz)]\n";
  text += "accelerometer_random_walk: " + FormatDouble(noise.accelerometer_random_walk) +
          "  # [m/s^3/sqrt(Hz)]\n";
  text += "gyroscope_noise_density: " + FormatDouble(noise.gyroscope_noise_density) +
          "  # [rad/s/sqrt(Hz)]\n";
  text += "gyroscope_random_walk: " + FormatDouble(noise.gyroscope_random_walk) +
          "  # [rad/s^2/sqrt(Hz)]\n";
  text += "rostopic: " + rostopic + "\n";
  text += "update_rate: " + FormatDouble(noise.update_rate_hz) + "  # [Hz]\n";
  return text;
}

}  // namespace splinecal
