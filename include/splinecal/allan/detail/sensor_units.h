// The units of a sensor's Allan outputs (result.yaml, imu.yaml, allan.svg): internal to allan/ and
// report/allan_report.h, which writes them.
#ifndef SPLINECAL_ALLAN_DETAIL_SENSOR_UNITS_H_
#define SPLINECAL_ALLAN_DETAIL_SENSOR_UNITS_H_

#include "splinecal/allan/noise_fit.h"
#include "splinecal/imu/static_recording.h"

namespace splinecal {
namespace internal {

struct SensorUnits {
  const char* adev;     // deviation and B [rad/s]
  const char* density;  // N
  const char* walk;     // K
  const char* quantization;
  const char* ramp;
  const char* adev_svg;  // the same with typographic symbols, for the plot
  const char* density_svg;
  const char* walk_svg;
  const char* quantization_svg;
  const char* ramp_svg;

  // The unit of a term's coefficient (plain or typographic).
  const char* Of(NoiseTerm term, bool svg = false) const;
};

const SensorUnits& UnitsOf(ImuSensor sensor);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_DETAIL_SENSOR_UNITS_H_
