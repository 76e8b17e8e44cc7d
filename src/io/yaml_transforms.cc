#include "splinecal/io/yaml_transforms.h"

#include <cmath>
#include <sstream>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"

namespace splinecal {
namespace {

bool IsRotation(const Eigen::Matrix3d& R) {
  return (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() <=
             kMaxOrthonormalityError &&
         R.determinant() > 0.0;
}

// The N x N matrix at `key`: N rows of N numbers.
template <int N>
Eigen::Matrix<double, N, N> ReadSquareMatrix(const YamlDocument& yaml, const std::string& key) {
  const std::vector<std::vector<double>> rows = yaml.Rows(key);
  if (rows.size() != static_cast<size_t>(N) || rows[0].size() != static_cast<size_t>(N)) {
    const std::string n = std::to_string(N);
    throw Error(
        yaml.path(),
        yaml.Line(key),
        key + ": expected a " + n + "x" + n + " matrix (" + n + " rows of " + n + " numbers)");
  }
  Eigen::Matrix<double, N, N> M;
  for (int r = 0; r < N; ++r) {
    for (int c = 0; c < N; ++c) M(r, c) = rows[r][c];
  }
  return M;
}

}  // namespace

Eigen::Matrix3d ReadMatrix3(const YamlDocument& yaml, const std::string& key) {
  return ReadSquareMatrix<3>(yaml, key);
}

SO3d ReadRotation(const YamlDocument& yaml, const std::string& key) {
  const Eigen::Matrix3d R = ReadMatrix3(yaml, key);
  if (!IsRotation(R)) {
    throw Error(yaml.path(),
                yaml.Line(key),
                key + ": not a rotation (must be orthonormal with determinant +1)");
  }
  return SO3d::FromMatrix(R);
}

SE3d ReadRigidTransform(const YamlDocument& yaml, const std::string& key) {
  const Eigen::Matrix4d T = ReadSquareMatrix<4>(yaml, key);
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double bottom =
      std::abs(T(3, 0)) + std::abs(T(3, 1)) + std::abs(T(3, 2)) + std::abs(T(3, 3) - 1.0);
  if (bottom > kMaxOrthonormalityError || !IsRotation(R)) {
    throw Error(yaml.path(),
                yaml.Line(key),
                key +
                    ": not a rigid transform (the rotation block must be orthonormal with "
                    "determinant +1 and the last row 0 0 0 1)");
  }
  const Eigen::Vector3d t = T.topRightCorner<3, 1>();
  if (t.cwiseAbs().maxCoeff() > kMaxPosition) {
    std::ostringstream message;
    message << key << ": translation beyond the plausible " << kMaxPosition << " m";
    throw Error(yaml.path(), yaml.Line(key), message.str());
  }
  return SE3d(SO3d::FromMatrix(R), t);
}

}  // namespace splinecal
