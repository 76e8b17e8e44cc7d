// One simulated camera of every model splinecal calibrates, wide-angle lenses included, for
// the intrinsics round trips (calibrate_intrinsics_test.cc, intrinsics_nees_slow_test.cc).
// Values are plausible lenses, not published calibrations, except where named.
#ifndef SPLINECAL_TESTS_INTRINSICS_INTRINSICS_MODELS_H_
#define SPLINECAL_TESTS_INTRINSICS_INTRINSICS_MODELS_H_

#include <string>
#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"

namespace splinecal {
namespace testing {

struct ModelCase {
  std::string name;
  IntrinsicsScene scene;
};

// What the command is told about a camera whose truth is `truth`: its models and image size,
// nothing of its parameters (the calibration starts from its own sweep).
inline IntrinsicsCameraSpec SpecOf(const Camera& truth) {
  IntrinsicsCameraSpec spec;
  spec.camera.projection = truth.projection;
  spec.camera.distortion = truth.distortion;
  spec.camera.width = truth.width;
  spec.camera.height = truth.height;
  return spec;
}

inline Camera MakeTestCamera(ProjectionModel projection,
                             DistortionModel distortion,
                             const std::vector<double>& fu_fv_pu_pv,
                             const Eigen::Vector2d& shape,
                             const std::vector<double>& coeffs,
                             int width,
                             int height) {
  Camera camera;
  camera.projection = projection;
  camera.distortion = distortion;
  camera.fu = fu_fv_pu_pv[0];
  camera.fv = fu_fv_pu_pv[1];
  camera.pu = fu_fv_pu_pv[2];
  camera.pv = fu_fv_pu_pv[3];
  camera.projection_params = shape;
  camera.distortion_coeffs.setZero();
  for (size_t i = 0; i < coeffs.size(); ++i) camera.distortion_coeffs(i) = coeffs[i];
  camera.width = width;
  camera.height = height;
  return camera;
}

// Every model; the wide-angle ones (512 x 512, fields of view of 150 to 190 degrees) are viewed
// closer and further off-axis so that corners reach the image's edges.
inline std::vector<ModelCase> AllModelCases() {
  using P = ProjectionModel;
  using D = DistortionModel;
  const std::vector<double> euroc = {458.654, 457.296, 367.215, 248.375};
  std::vector<ModelCase> cases = {
      {"pinhole-none", {}},
      {"pinhole-radtan", {}},
      {"pinhole-equi", {}},
      {"pinhole-fov", {}},
      {"omni-none", {}},
      {"omni-radtan", {}},
      {"eucm-none", {}},
      {"ds-none", {}},
  };
  cases[0].scene.cameras = {MakeTestCamera(P::kPinhole, D::kNone, euroc, {0, 0}, {}, 752, 480)};
  cases[1].scene.cameras = {EurocCam0()};
  // TUM-VI's cam0 equidistant calibration (published with the dataset).
  cases[2].scene.cameras = {MakeTestCamera(P::kPinhole, D::kEquidistant,
                                           {190.978, 190.973, 254.932, 256.897}, {0, 0},
                                           {0.00348239, 0.00071503, -0.00205324, 0.00020294},
                                           512, 512)};
  cases[3].scene.cameras = {
      MakeTestCamera(P::kPinhole, D::kFov, {270.0, 269.0, 256.5, 255.0}, {0, 0}, {0.92}, 512, 512)};
  cases[4].scene.cameras = {
      MakeTestCamera(P::kOmni, D::kNone, {730.0, 728.0, 370.0, 242.0}, {0.95, 0}, {}, 752, 480)};
  // Mei's unified model with radtan: xi and k1 both bend rays radially, and only a wide field
  // of view tells them apart (on a 90 degree lens they trade along a curved valley).
  cases[5].scene.cameras = {MakeTestCamera(P::kOmni, D::kRadTan, {370.0, 369.0, 255.0, 257.0},
                                           {0.95, 0}, {-0.06, 0.012, 4e-4, -2e-4}, 512, 512)};
  cases[6].scene.cameras = {MakeTestCamera(P::kEucm, D::kNone, {188.0, 187.5, 254.0, 257.0},
                                           {0.62, 1.05}, {}, 512, 512)};
  // basalt's TUM-VI-like double sphere.
  cases[7].scene.cameras = {MakeTestCamera(P::kDoubleSphere, D::kNone,
                                           {158.3, 158.2, 256.1, 255.4}, {-0.18, 0.59}, {}, 512,
                                           512)};
  for (ModelCase& c : cases) {
    c.scene.T_cn_c0 = {SE3d()};
    c.scene.views = 40;
    if (c.scene.cameras[0].width == 512) {  // wide angle: closer, further off-axis
      c.scene.min_distance_m = 0.35;
      c.scene.max_distance_m = 0.8;
      c.scene.spread = 1.2;
    }
  }
  return cases;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_INTRINSICS_INTRINSICS_MODELS_H_
