// Pixels of the wide-angle models against their papers' published projection formulas,
// evaluated independently by scripts/camera_reference_pixels.py (Python, standard library
// math) and committed as reference_pixels.inc: double sphere (basalt's published EuRoC cam0
// calibration and a 190 degree lens), extended unified, Mei's unified model (omni, with and
// without radtan) and the field-of-view model, from the optical axis to beyond 90 degrees, and
// points outside each valid region, which must not project.
//
// Tolerance. The script and splinecal compute the same quantities in double precision along
// different algebraic routes (e.g. Mei's sphere-then-shift against (x, y) / (z + xi |p|)), with
// the same libm; printing with 17 significant digits is exact. The differences are rounding,
// ~1e-13 px at |uv| ~ 1e3 px (a little more where den is small near a region's border);
// kPublishedTolerancePx = 1e-9 px leaves a factor 1e4 and is far below any formula error
// (a wrong term moves pixels by far more than 1e-6 px at these angles).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"

namespace splinecal {
namespace {

constexpr double kPublishedTolerancePx = 1e-9;

struct ReferencePixel {
  const char* camera;
  const char* model;
  double intrinsics[kNumIntrinsics];
  double p_c[3];
  bool valid;
  double uv[2];
};

const ReferencePixel kReferencePixels[] = {
#include "camera/reference_pixels.inc"
};

TEST(CameraPublishedReference, ProjectMatchesThePapersFormulas) {
  int compared = 0;
  int refused = 0;
  for (const ReferencePixel& r : kReferencePixels) {
    Camera camera;
    ASSERT_TRUE(ParseCameraModelName(r.model, &camera.projection, &camera.distortion)) << r.model;
    camera.set_intrinsics(Eigen::Map<const IntrinsicsVector>(r.intrinsics));
    const Eigen::Vector3d p(r.p_c[0], r.p_c[1], r.p_c[2]);
    Eigen::Vector2d uv;
    const bool valid = camera.Project(p, &uv);
    EXPECT_EQ(valid, r.valid) << r.camera << " at " << p.transpose();
    if (!valid || !r.valid) {
      refused += !valid;
      continue;
    }
    EXPECT_LT((uv - Eigen::Vector2d(r.uv[0], r.uv[1])).norm(), kPublishedTolerancePx)
        << r.camera << " at " << p.transpose() << ": " << uv.transpose() << " vs " << r.uv[0] << " "
        << r.uv[1];
    ++compared;
  }
  // The table's shape (scripts/camera_reference_pixels.py): 7 cameras, every one with points
  // outside its region.
  EXPECT_GE(compared, 300);
  EXPECT_GE(refused, 7 * 8);
}

TEST(CameraPublishedReference, TableCoversEveryWideAngleModel) {
  std::vector<std::string> models;
  for (const ReferencePixel& r : kReferencePixels) {
    if (models.empty() || models.back() != r.model) models.push_back(r.model);
  }
  for (const std::string model :
       {"ds-none", "eucm-none", "omni-none", "omni-radtan", "pinhole-fov"}) {
    EXPECT_NE(std::find(models.begin(), models.end(), model), models.end()) << model;
  }
}

}  // namespace
}  // namespace splinecal
