#include "splinecal/imu/imu_model_kind.h"

namespace splinecal {

const char* ImuModelName(ImuModelKind kind) {
  switch (kind) {
    case ImuModelKind::kCalibrated:
      return "calibrated";
    case ImuModelKind::kScaleMisalignment:
      return "scale-misalignment";
    case ImuModelKind::kScaleMisalignmentSizeEffect:
      return "scale-misalignment-size-effect";
  }
  return "calibrated";
}

bool ParseImuModelKind(const std::string& name, ImuModelKind* kind) {
  for (ImuModelKind candidate : {ImuModelKind::kCalibrated,
                                 ImuModelKind::kScaleMisalignment,
                                 ImuModelKind::kScaleMisalignmentSizeEffect}) {
    if (name == ImuModelName(candidate)) {
      *kind = candidate;
      return true;
    }
  }
  return false;
}

const char* ImuModelNames() {
  return "calibrated, scale-misalignment, scale-misalignment-size-effect";
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
