#include "splinecal/allan/detail/sensor_units.h"

namespace splinecal {
namespace internal {

const char* SensorUnits::Of(NoiseTerm term, bool svg) const {
  switch (term) {
    case NoiseTerm::kQuantization:
      return svg ? quantization_svg : quantization;
    case NoiseTerm::kWhite:
      return svg ? density_svg : density;
    case NoiseTerm::kBiasInstability:
      return svg ? adev_svg : adev;
    case NoiseTerm::kRandomWalk:
      return svg ? walk_svg : walk;
    case NoiseTerm::kRateRamp:
      return svg ? ramp_svg : ramp;
  }
  return "";
}

const SensorUnits& UnitsOf(ImuSensor sensor) {
  static const SensorUnits kGyro = {"rad/s",
                                    "rad/s/sqrt(Hz)",
                                    "rad/s^2/sqrt(Hz)",
                                    "rad",
                                    "rad/s^2",
                                    "rad/s",
                                    "rad/s/√Hz",
                                    "rad/s²/√Hz",
                                    "rad",
                                    "rad/s²"};
  static const SensorUnits kAccel = {"m/s^2",
                                     "m/s^2/sqrt(Hz)",
                                     "m/s^3/sqrt(Hz)",
                                     "m/s",
                                     "m/s^3",
                                     "m/s²",
                                     "m/s²/√Hz",
                                     "m/s³/√Hz",
                                     "m/s",
                                     "m/s³"};
  return sensor == ImuSensor::kGyroscope ? kGyro : kAccel;
}

}  // namespace internal
}  // namespace splinecal
