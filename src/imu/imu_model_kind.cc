#include "splinecal/imu/imu_model_kind.h"

#include <array>

#include "splinecal/enum_names.h"

namespace splinecal {

namespace {

constexpr std::array<EnumName<ImuModelKind>, 3> kImuModelNames = {{
    {ImuModelKind::kCalibrated, "calibrated"},
    {ImuModelKind::kScaleMisalignment, "scale-misalignment"},
    {ImuModelKind::kScaleMisalignmentSizeEffect, "scale-misalignment-size-effect"},
}};

}  // namespace

const char* ImuModelName(ImuModelKind kind) { return NameOf(kImuModelNames, kind); }

bool ParseImuModelKind(const std::string& name, ImuModelKind* kind) {
  return ValueNamed(kImuModelNames, name, kind);
}

const char* ImuModelNames() {
  static const std::string names = JoinNames(kImuModelNames, ", ");
  return names.c_str();
}

int NumImuIntrinsicParameters(ImuModelKind kind) {
  switch (kind) {
    case ImuModelKind::kCalibrated:
      return 0;
    case ImuModelKind::kScaleMisalignment:
      return 24;
    case ImuModelKind::kScaleMisalignmentSizeEffect:
      return 30;
  }
  return 0;
}

}  // namespace splinecal
