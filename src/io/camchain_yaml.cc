#include "splinecal/io/camchain_yaml.h"

#include <glog/logging.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/io/yaml_transforms.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {

namespace {

// Resolutions beyond this [px] per side are refused as implausible (a corrupt file).
constexpr int64_t kMaxResolution = 1 << 20;
// Plausibility limits, far beyond any real camera (a corrupt file or another unit beyond them):
// focal lengths and principal point [px], distortion coefficients, time offset [s] (it moves
// int64 nanosecond stamps: 1e9 s keeps them far from overflow), line delay [s per row].
constexpr double kMaxIntrinsic = 1e6;
constexpr double kMaxDistortionCoefficient = 1e3;
constexpr double kMaxTimeOffsetS = 1e9;
constexpr double kMaxLineDelay = 1e-2;
// cam_overlaps: camera indices; a rig of more than 64 cameras is a corrupt file.
constexpr double kMaxCameras = 64;
// The keys of a camN map: ours and the others Kalibr writes (ignored); near misses are typos.
const std::vector<std::string> kCameraKeys = {"camera_model",
                                              "intrinsics",
                                              "distortion_model",
                                              "distortion_coeffs",
                                              "resolution",
                                              "T_cam_imu",
                                              "timeshift_cam_imu",
                                              "line_delay",
                                              "rostopic",
                                              "T_cn_cnm1",
                                              "cam_overlaps",
                                              "splinecal_covariance"};

// A camera model's intrinsics in Kalibr's order: the projection's parameters first, then
// fu fv pu pv (camera/camera_model.h's layout takes m0 m1 and fu fv pu pv from them).
struct IntrinsicsOrder {
  const char* names;  // for messages
  int count;
};

constexpr ProjectionModel kProjectionModels[] = {ProjectionModel::kPinhole,
                                                 ProjectionModel::kOmni,
                                                 ProjectionModel::kEucm,
                                                 ProjectionModel::kDoubleSphere};
constexpr DistortionModel kDistortionModels[] = {DistortionModel::kNone,
                                                 DistortionModel::kRadTan,
                                                 DistortionModel::kEquidistant,
                                                 DistortionModel::kFov};

ProjectionModel ParseProjectionModel(const YamlDocument& yaml, const std::string& key) {
  const std::string name = yaml.String(key);
  for (ProjectionModel m : kProjectionModels) {
    if (name == ProjectionModelName(m)) return m;
  }
  throw Error(
      yaml.path(),
      yaml.Line(key),
      key + ": unsupported camera model '" + name +
          "' (supported: pinhole, omni, eucm, ds; as pairs: " + SupportedCameraModelNames() + ")");
}

DistortionModel ParseDistortionModel(const YamlDocument& yaml,
                                     const std::string& key,
                                     ProjectionModel projection) {
  const std::string name = yaml.String(key);
  for (DistortionModel m : kDistortionModels) {
    if (name != DistortionModelName(m)) continue;
    if (!IsSupportedCameraModel(projection, m)) break;
    return m;
  }
  std::string supported;
  for (DistortionModel m : kDistortionModels) {
    if (!IsSupportedCameraModel(projection, m)) continue;
    supported += (supported.empty() ? "" : ", ") + DistortionModelName(m);
  }
  throw Error(yaml.path(),
              yaml.Line(key),
              key + ": unsupported distortion model '" + name + "' for camera model " +
                  ProjectionModelName(projection) + " (supported: " + supported + ")");
}

// Kalibr's intrinsics order per camera model.
IntrinsicsOrder IntrinsicsOrderToRead(ProjectionModel model) {
  switch (model) {
    case ProjectionModel::kPinhole:
      return {"[fu, fv, pu, pv]", 4};
    case ProjectionModel::kOmni:
      return {"[xi, fu, fv, pu, pv]", 5};
    case ProjectionModel::kEucm:
      return {"[alpha, beta, fu, fv, pu, pv]", 6};
    case ProjectionModel::kDoubleSphere:
      return {"[xi, alpha, fu, fv, pu, pv]", 6};
  }
  return {"[fu, fv, pu, pv]", 4};
}

// The numbers of distortion_coeffs a model takes (radtan: 4 or, with OpenCV's k3, 5).
std::vector<size_t> CoefficientCounts(DistortionModel model) {
  switch (model) {
    case DistortionModel::kNone:
      return {0};
    case DistortionModel::kRadTan:
      return {4, 5};
    case DistortionModel::kEquidistant:
      return {4};
    case DistortionModel::kFov:
      return {1};
  }
  return {0};
}

// T_cam_imu and the time offset (Kalibr's key timeshift_cam_imu) of `cam`, when present.
void ReadExtrinsics(const YamlDocument& yaml, const std::string& cam, CameraCalibration* c) {
  if (yaml.Has(cam + "/T_cam_imu")) c->T_cam_imu = ReadRigidTransform(yaml, cam + "/T_cam_imu");
  if (cam != "cam0" && yaml.Has(cam + "/T_cn_cnm1")) {
    c->T_cn_cnm1 = ReadRigidTransform(yaml, cam + "/T_cn_cnm1");
  }
  if (yaml.Has(cam + "/timeshift_cam_imu")) {
    c->time_offset_s = yaml.BoundedNumber(cam + "/timeshift_cam_imu", kMaxTimeOffsetS, "s");
  }
}

CameraCalibration ReadCamera(const YamlDocument& yaml, const std::string& cam) {
  yaml.CheckTypos(cam, kCameraKeys);
  CameraCalibration calibration;
  Camera& camera = calibration.camera;
  camera.projection = ParseProjectionModel(yaml, cam + "/camera_model");
  const IntrinsicsOrder order = IntrinsicsOrderToRead(camera.projection);
  const std::vector<double> intrinsics =
      yaml.BoundedNumbers(cam + "/intrinsics", kMaxIntrinsic, "px");
  const int64_t intrinsics_line = yaml.Line(cam + "/intrinsics");
  if (static_cast<int>(intrinsics.size()) != order.count) {
    throw Error(yaml.path(),
                intrinsics_line,
                cam + "/intrinsics: the " + ProjectionModelName(camera.projection) +
                    " model expects " + std::to_string(order.count) + " numbers " + order.names +
                    ", got " + std::to_string(intrinsics.size()));
  }
  // Kalibr puts the projection's parameters first: [m0 (m1)] fu fv pu pv.
  const int first = order.count - 4;
  for (int i = 0; i < first; ++i) camera.projection_params(i) = intrinsics[i];
  camera.fu = intrinsics[first];
  camera.fv = intrinsics[first + 1];
  camera.pu = intrinsics[first + 2];
  camera.pv = intrinsics[first + 3];
  camera.distortion = yaml.Has(cam + "/distortion_model")
                          ? ParseDistortionModel(yaml, cam + "/distortion_model", camera.projection)
                          : DistortionModel::kNone;
  std::vector<double> coeffs;
  if (yaml.Has(cam + "/distortion_coeffs")) {
    coeffs = yaml.BoundedNumbers(cam + "/distortion_coeffs", kMaxDistortionCoefficient, "");
  }
  const std::vector<size_t> expected = CoefficientCounts(camera.distortion);
  // `none` with four zeros is what some tools write: accept zeros.
  const bool zeros_for_none = camera.distortion == DistortionModel::kNone && coeffs.size() == 4 &&
                              coeffs == std::vector<double>(4, 0.0);
  if (std::find(expected.begin(), expected.end(), coeffs.size()) == expected.end() &&
      !zeros_for_none) {
    std::string counts = std::to_string(expected[0]);
    for (size_t i = 1; i < expected.size(); ++i) counts += " or " + std::to_string(expected[i]);
    throw Error(yaml.path(),
                yaml.Line(cam + "/distortion_coeffs"),
                cam + "/distortion_coeffs: the " + DistortionModelName(camera.distortion) +
                    " model takes " + counts + (counts == "1" ? " coefficient" : " coefficients") +
                    ", got " + std::to_string(coeffs.size()));
  }
  if (camera.distortion != DistortionModel::kNone) {
    for (size_t i = 0; i < coeffs.size(); ++i) camera.distortion_coeffs(i) = coeffs[i];
  }
  camera.radtan_k3 = camera.distortion == DistortionModel::kRadTan && coeffs.size() == 5;
  std::string problem;
  if (!camera.IsValid(&problem)) {
    // The problem is in the coefficients when the camera is valid without them.
    Camera without_distortion = camera;
    without_distortion.distortion_coeffs.setZero();
    const bool in_coefficients = without_distortion.IsValid();
    throw Error(yaml.path(),
                in_coefficients ? yaml.Line(cam + "/distortion_coeffs") : intrinsics_line,
                cam + (in_coefficients ? "/distortion_coeffs: " : "/intrinsics: ") + problem);
  }
  const std::vector<double> resolution = yaml.Numbers(cam + "/resolution");
  if (resolution.size() != 2 || !(resolution[0] >= 1.0) || !(resolution[1] >= 1.0) ||
      resolution[0] != std::floor(resolution[0]) || resolution[1] != std::floor(resolution[1]) ||
      resolution[0] > kMaxResolution || resolution[1] > kMaxResolution) {
    throw Error(yaml.path(),
                yaml.Line(cam + "/resolution"),
                cam + "/resolution: expected two positive integers [width, height] in pixels");
  }
  camera.width = static_cast<int>(resolution[0]);
  camera.height = static_cast<int>(resolution[1]);
  ReadExtrinsics(yaml, cam, &calibration);
  if (yaml.Has(cam + "/line_delay")) {
    calibration.line_delay_s = yaml.BoundedNumber(cam + "/line_delay", kMaxLineDelay, "s per row");
    if (calibration.line_delay_s < 0.0) {
      throw Error(yaml.path(),
                  yaml.Line(cam + "/line_delay"),
                  cam + "/line_delay: must be >= 0 [s per row]");
    }
  }
  if (yaml.Has(cam + "/rostopic")) calibration.rostopic = yaml.String(cam + "/rostopic");
  if (yaml.Has(cam + "/cam_overlaps")) {
    for (double index : yaml.BoundedNumbers(cam + "/cam_overlaps", kMaxCameras, "cameras")) {
      if (index < 0.0 || index != std::floor(index)) {
        throw Error(yaml.path(),
                    yaml.Line(cam + "/cam_overlaps"),
                    cam + "/cam_overlaps: expected camera indices (0, 1, ...)");
      }
      calibration.cam_overlaps.push_back(static_cast<int>(index));
    }
  }
  return calibration;
}

}  // namespace

Camchain ReadCamchainYaml(const std::string& path) {
  const YamlDocument yaml(path);
  Camchain camchain;
  for (int i = 0;; ++i) {
    const std::string cam = "cam" + std::to_string(i);
    if (!yaml.Has(cam)) break;
    camchain.push_back(ReadCamera(yaml, cam));
  }
  if (camchain.empty()) throw Error(path, 0, "no camera: expected a key 'cam0'");
  for (size_t i = 0; i < camchain.size(); ++i) {
    for (int other : camchain[i].cam_overlaps) {
      if (other >= static_cast<int>(camchain.size()) || other == static_cast<int>(i)) {
        const std::string key = "cam" + std::to_string(i) + "/cam_overlaps";
        throw Error(path,
                    yaml.Line(key),
                    key + ": camera " + std::to_string(other) +
                        (other == static_cast<int>(i) ? " is the camera itself"
                                                      : " is not in the chain"));
      }
    }
  }
  for (const std::string& key : yaml.TopLevelKeys()) {
    if (key.rfind("cam", 0) == 0 && key.size() > 3 &&
        key.find_first_not_of("0123456789", 3) == std::string::npos &&
        std::stoll(key.substr(3)) >= static_cast<long long>(camchain.size())) {
      throw Error(path,
                  yaml.Line(key),
                  "'" + key + "': cameras must be numbered cam0, cam1, ... without gaps");
    }
  }
  return camchain;
}

CameraCalibration ReadCam0Extrinsics(const std::string& path) {
  const YamlDocument yaml(path);
  yaml.CheckTypos("cam0", kCameraKeys);
  CameraCalibration calibration;
  ReadExtrinsics(yaml, "cam0", &calibration);
  return calibration;
}

namespace {

// The values of camera's intrinsics vector at `order` (camera/camchain.h's Kalibr orders).
Eigen::VectorXd Pick(const Camera& camera, const std::vector<int>& order) {
  const IntrinsicsVector values = camera.intrinsics();
  Eigen::VectorXd picked(order.size());
  for (size_t i = 0; i < order.size(); ++i) picked(i) = values(order[i]);
  return picked;
}

}  // namespace

void WriteParameterCovariance(const ParameterCovariance& covariance, YamlWriter* yaml) {
  yaml->BeginMap("splinecal_covariance");
  yaml->StringList("parameters", covariance.parameters);
  yaml->Matrix("matrix", covariance.matrix);
  yaml->Scalar("block_seconds", covariance.block_seconds);
  yaml->EndMap();
}

std::string CamchainYamlText(const Camchain& camchain,
                             CamchainKeys keys,
                             const std::vector<ParameterCovariance>& covariances) {
  const bool with_imu = keys == CamchainKeys::kWithImu;
  YamlWriter yaml;
  for (size_t i = 0; i < camchain.size(); ++i) {
    const CameraCalibration& c = camchain[i];
    yaml.BeginMap("cam" + std::to_string(i));
    yaml.Scalar("camera_model", ProjectionModelName(c.camera.projection));
    yaml.Vector("intrinsics", Pick(c.camera, KalibrIntrinsicsOrder(c.camera)));
    yaml.Scalar("distortion_model", DistortionModelName(c.camera.distortion));
    yaml.Vector("distortion_coeffs", Pick(c.camera, KalibrDistortionOrder(c.camera)));
    yaml.Vector("resolution", Eigen::Vector2d(c.camera.width, c.camera.height));
    if (with_imu) yaml.Matrix("T_cam_imu", c.T_cam_imu.matrix());
    if (i > 0 && with_imu) {
      // Kalibr's T_cn_cnm1 (camera n-1 into camera n), the one the T_cam_imu above imply, so that
      // the file never holds a stereo extrinsic that contradicts them.
      yaml.Matrix("T_cn_cnm1", (c.T_cam_imu * camchain[i - 1].T_cam_imu.inverse()).matrix());
    } else if (i > 0) {
      CHECK(c.T_cn_cnm1.has_value()) << "a camera chain without T_cn_cnm1 for cam" << i;
      yaml.Matrix("T_cn_cnm1", c.T_cn_cnm1->matrix());
    }
    if (with_imu) {
      yaml.Scalar("timeshift_cam_imu", c.time_offset_s);  // Kalibr's key
      yaml.Scalar("line_delay", c.line_delay_s);
    }
    if (!c.rostopic.empty()) yaml.Scalar("rostopic", c.rostopic);
    if (!c.cam_overlaps.empty()) {
      yaml.Vector("cam_overlaps",
                  Eigen::Map<const Eigen::VectorXi>(c.cam_overlaps.data(), c.cam_overlaps.size())
                      .cast<double>());
    }
    if (i < covariances.size() && covariances[i].matrix.size() > 0) {
      WriteParameterCovariance(covariances[i], &yaml);
    }
    yaml.EndMap();
  }
  return yaml.str();
}

}  // namespace splinecal
