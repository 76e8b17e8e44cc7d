// The names of a 3-vector's axes, as every result file, report and message writes them.
#ifndef SPLINECAL_AXIS_NAME_H_
#define SPLINECAL_AXIS_NAME_H_

namespace splinecal {

// "x", "y" or "z" for axis 0, 1 or 2.
inline const char* AxisName(int axis) {
  static constexpr const char* kNames[3] = {"x", "y", "z"};
  return kNames[axis];
}

}  // namespace splinecal

#endif  // SPLINECAL_AXIS_NAME_H_
