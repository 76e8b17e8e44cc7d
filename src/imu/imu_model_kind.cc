#include "splinecal/imu/imu_model_kind.h"

#include <array>

#include "splinecal/enum_names.h"

namespace splinecal {

namespace {

// Kalibr's name of each model and the number of intrinsic parameters it estimates (header).
struct ImuModelRow {
  ImuModelKind value;
  const char* name;
  int num_intrinsic_parameters;
};

constexpr std::array<ImuModelRow, 3> kImuModels = {{
    {ImuModelKind::kCalibrated, "calibrated", 0},
    {ImuModelKind::kScaleMisalignment, "scale-misalignment", 24},
    {ImuModelKind::kScaleMisalignmentSizeEffect, "scale-misalignment-size-effect", 30},
}};

}  // namespace

const char* ImuModelName(ImuModelKind kind) { return NameOf(kImuModels, kind); }

bool ParseImuModelKind(const std::string& name, ImuModelKind* kind) {
  return ValueNamed(kImuModels, name, kind);
}

const char* ImuModelNames() {
  static const std::string names = JoinNames(kImuModels, ", ");
  return names.c_str();
}

int NumImuIntrinsicParameters(ImuModelKind kind) {
  return RowOf(kImuModels, kind).num_intrinsic_parameters;
}

}  // namespace splinecal
