#include "splinecal/io/camchain_yaml_covariance.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

constexpr char kKey[] = "splinecal_covariance";
// Symmetry to the 17 significant digits a writer prints, with room for a writer that
// symmetrises after rounding: |S_ij - S_ji| <= this x sqrt(S_ii S_jj).
constexpr double kSymmetryTolerance = 1e-9;

// The project's name of intrinsics entry `index` (camera/camera_model.h's layout) and, for some,
// the agreed schema's synonym.
struct EntryName {
  std::string name;
  std::string synonym;  // empty: none
};

EntryName NameOf(const Camera& camera, int index) {
  static const char* const kBase[] = {"fu", "fv", "pu", "pv"};
  static const char* const kSynonyms[] = {"fx", "fy", "cx", "cy"};
  if (index < 4) return {kBase[index], kSynonyms[index]};
  if (index < kDistortionCoeffsIndex) {
    switch (camera.projection) {
      case ProjectionModel::kOmni:
        return {"xi", ""};
      case ProjectionModel::kEucm:
        return {index == 4 ? "alpha" : "beta", ""};
      case ProjectionModel::kDoubleSphere:
        return {index == 4 ? "xi" : "alpha", ""};
      default:
        return {StringPrintf("m%d", index - 4), ""};
    }
  }
  const int d = index - kDistortionCoeffsIndex;
  switch (camera.distortion) {
    case DistortionModel::kRadTan: {
      static const char* const kRadTan[] = {"k1", "k2", "p1", "p2", "k3"};
      static const char* const kKalibr[] = {"k1", "k2", "r1", "r2", "k3"};
      return {kRadTan[d], d == 2 || d == 3 ? kKalibr[d] : ""};
    }
    case DistortionModel::kEquidistant:
      return {StringPrintf("k%d", d + 1), ""};
    case DistortionModel::kFov:
      return {"w", ""};
    default:
      return {StringPrintf("d%d", d), ""};
  }
}

const char* const kChainNames[kChainTangentSize] = {"T_cn_cnm1_rho_x", "T_cn_cnm1_rho_y",
                                                    "T_cn_cnm1_rho_z", "T_cn_cnm1_phi_x",
                                                    "T_cn_cnm1_phi_y", "T_cn_cnm1_phi_z"};

// The camera's active intrinsics in Kalibr's order.
std::vector<int> ActiveInKalibrOrder(const Camera& camera) {
  const std::vector<int> active = camera.ActiveIntrinsics();
  std::vector<int> order = KalibrIntrinsicsOrder(camera);
  const std::vector<int> distortion = KalibrDistortionOrder(camera);
  order.insert(order.end(), distortion.begin(), distortion.end());
  std::vector<int> kept;
  for (int i : order) {
    if (std::find(active.begin(), active.end(), i) != active.end()) kept.push_back(i);
  }
  return kept;
}

std::string Join(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return "[" + text + "]";
}

CameraCovariance ReadCovariance(const YamlDocument& yaml,
                                const std::string& cam,
                                const CameraCalibration& calibration,
                                bool first_camera) {
  const std::string key = cam + "/" + kKey;
  const std::string& path = yaml.path();
  yaml.CheckTypos(key, {"parameters", "matrix", "block_seconds"});
  const std::vector<std::string> names = yaml.Strings(key + "/parameters");
  const int64_t names_line = yaml.Line(key + "/parameters");
  CameraCovariance covariance;
  covariance.intrinsics = ActiveInKalibrOrder(calibration.camera);
  const size_t num_intrinsics = covariance.intrinsics.size();
  covariance.has_T_cn_cnm1 = names.size() == num_intrinsics + kChainTangentSize;
  const std::vector<std::string> expected =
      CovarianceParameterNames(calibration.camera, covariance.has_T_cn_cnm1);
  const std::string model = calibration.camera.model_name();
  if (names.size() != num_intrinsics && !covariance.has_T_cn_cnm1) {
    throw Error(path, names_line,
                key + "/parameters: " + std::to_string(names.size()) + " names for the " + model +
                    " camera, which has " + std::to_string(num_intrinsics) +
                    " intrinsics (expected " + Join(expected) + ", optionally followed by the " +
                    "6 T_cn_cnm1 tangent names)");
  }
  for (size_t i = 0; i < names.size(); ++i) {
    bool match = names[i] == expected[i];
    if (i < num_intrinsics) match = match || names[i] == NameOf(calibration.camera,
                                                                covariance.intrinsics[i]).synonym;
    if (!match) {
      throw Error(path, names_line,
                  key + "/parameters: entry " + std::to_string(i + 1) + " is '" + names[i] +
                      "', expected '" + expected[i] + "' (the " + model + " camera's order: " +
                      Join(expected) + ")");
    }
  }
  if (covariance.has_T_cn_cnm1 && (first_camera || !calibration.T_cn_cnm1.has_value())) {
    throw Error(path, names_line,
                key + "/parameters: T_cn_cnm1 rows for " +
                    (first_camera ? std::string("cam0, which has no predecessor")
                                  : cam + ", which has no T_cn_cnm1"));
  }
  const std::vector<std::vector<double>> rows = yaml.Rows(key + "/matrix");
  const int64_t matrix_line = yaml.Line(key + "/matrix");
  const int n = static_cast<int>(names.size());
  if (static_cast<int>(rows.size()) != n || rows.front().size() != names.size()) {
    throw Error(path, matrix_line,
                key + "/matrix: expected " + std::to_string(n) + "x" + std::to_string(n) +
                    " (one row and column per parameter), got " + std::to_string(rows.size()) +
                    "x" + std::to_string(rows.empty() ? 0 : rows.front().size()));
  }
  covariance.matrix.resize(n, n);
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) covariance.matrix(r, c) = rows[r][c];
  }
  const Eigen::MatrixXd& S = covariance.matrix;
  for (int r = 0; r < n; ++r) {
    if (!(S(r, r) > 0.0)) {
      throw Error(path, matrix_line,
                  key + "/matrix: the variance of " + names[r] + " is " +
                      StringPrintf("%.6g", S(r, r)) + ", not positive");
    }
  }
  for (int r = 0; r < n; ++r) {
    for (int c = r + 1; c < n; ++c) {
      if (std::abs(S(r, c) - S(c, r)) > kSymmetryTolerance * std::sqrt(S(r, r) * S(c, c))) {
        throw Error(path, matrix_line,
                    key + "/matrix: not symmetric (row " + std::to_string(r + 1) + ", column " +
                        std::to_string(c + 1) + ": " + StringPrintf("%.17g", S(r, c)) + " vs " +
                        StringPrintf("%.17g", S(c, r)) + ")");
      }
    }
  }
  // Positive definite: Cholesky of the correlation matrix (scale-free across px, m and rad).
  const Eigen::VectorXd inv_std = S.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd correlation = inv_std.asDiagonal() * S * inv_std.asDiagonal();
  const Eigen::LLT<Eigen::MatrixXd> llt(0.5 * (correlation + correlation.transpose()));
  if (llt.info() != Eigen::Success) {
    throw Error(path, matrix_line, key + "/matrix: not positive definite");
  }
  covariance.matrix = 0.5 * (S + S.transpose());
  if (yaml.Has(key + "/block_seconds")) {
    covariance.block_seconds = yaml.Number(key + "/block_seconds");
  }
  return covariance;
}

}  // namespace

std::vector<std::string> CovarianceParameterNames(const Camera& camera, bool with_chain) {
  std::vector<std::string> names;
  for (int i : ActiveInKalibrOrder(camera)) names.push_back(NameOf(camera, i).name);
  if (with_chain) names.insert(names.end(), kChainNames, kChainNames + kChainTangentSize);
  return names;
}

std::vector<std::optional<CameraCovariance>> ReadCamchainCovariances(const std::string& path,
                                                                     const Camchain& camchain) {
  const YamlDocument yaml(path);
  std::vector<std::optional<CameraCovariance>> covariances(camchain.size());
  for (size_t i = 0; i < camchain.size(); ++i) {
    const std::string cam = "cam" + std::to_string(i);
    if (yaml.Has(cam + "/" + kKey)) covariances[i] = ReadCovariance(yaml, cam, camchain[i], i == 0);
  }
  return covariances;
}

std::string CameraCovarianceYamlText(const Camera& camera,
                                     const CameraCovariance& covariance,
                                     int indent) {
  const std::string pad(indent, ' ');
  std::ostringstream text;
  text << pad << "parameters: " << Join(CovarianceParameterNames(camera, covariance.has_T_cn_cnm1))
       << "\n"
       << pad << "matrix:\n";
  for (int r = 0; r < covariance.matrix.rows(); ++r) {
    text << pad << "  - [";
    for (int c = 0; c < covariance.matrix.cols(); ++c) {
      text << (c > 0 ? ", " : "") << StringPrintf("%.17g", covariance.matrix(r, c));
    }
    text << "]\n";
  }
  if (std::isfinite(covariance.block_seconds)) {
    text << pad << "block_seconds: " << StringPrintf("%.17g", covariance.block_seconds) << "\n";
  }
  return text.str();
}

}  // namespace splinecal
