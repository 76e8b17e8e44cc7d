#include "splinecal/estimation/options.h"

#include <cmath>
#include <string>

#include "splinecal/error.h"

namespace splinecal {

void CheckSplineModelOptions(const SplineModelOptions& model) {
  auto positive = [](double value, const std::string& name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw Error(name + " must be a positive number, got " + std::to_string(value));
    }
  };
  if (!(model.knot_spacing_s >= 0.0) || !std::isfinite(model.knot_spacing_s)) {
    throw Error("knot spacing must be >= 0 s (0: automatic), got " +
                std::to_string(model.knot_spacing_s));
  }
  positive(model.gravity_m_s2, "gravity");
  positive(model.noise.gyroscope_noise_density, "gyroscope_noise_density");
  positive(model.noise.accelerometer_noise_density, "accelerometer_noise_density");
  if (model.bias_model == BiasModel::kSpline) {
    positive(model.noise.gyroscope_random_walk,
             "gyroscope_random_walk (needed by the bias spline)");
    positive(model.noise.accelerometer_random_walk,
             "accelerometer_random_walk (needed by the bias spline)");
    positive(model.bias_knot_spacing_s, "bias knot spacing");
  }
}

}  // namespace splinecal
