// The one way splinecal writes result.yaml: block mappings, flow lists for vectors and matrix
// rows, doubles with 17 significant digits (docs/conventions.md, "Time"), NaN as .nan.
#ifndef SPLINECAL_IO_YAML_WRITER_H_
#define SPLINECAL_IO_YAML_WRITER_H_

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace splinecal {

class YamlWriter {
 public:
  void Comment(const std::string& text);
  void Scalar(const std::string& key, double value);
  void Scalar(const std::string& key, int value) { Scalar(key, static_cast<int64_t>(value)); }
  void Scalar(const std::string& key, int64_t value);
  void Scalar(const std::string& key, bool value);
  void Scalar(const std::string& key, const std::string& value);
  void Scalar(const std::string& key, const char* value) { Scalar(key, std::string(value)); }
  void Vector(const std::string& key, const Eigen::VectorXd& value);
  void Matrix(const std::string& key, const Eigen::MatrixXd& value);  // a list of rows
  void StringList(const std::string& key, const std::vector<std::string>& values);
  void BeginMap(const std::string& key);
  void EndMap();
  // A block list of mappings:  key:\n  - a: 1\n    b: 2\n  - a: 3 ...
  // BeginList(key), then per item BeginListItem(), its keys, EndListItem(); then EndList().
  void BeginList(const std::string& key);
  void BeginListItem();
  void EndListItem();
  void EndList();

  // The document; every BeginMap must have been closed.
  std::string str() const;

 private:
  void Key(const std::string& key);

  std::string text_;
  int depth_ = 0;
  bool item_pending_ = false;  // the next key opens a list item ("- ")
};

// A YAML double: 17 significant digits, .nan / .inf / -.inf.
std::string YamlNumber(double value);
// A YAML string, quoted when it would otherwise read as something else.
std::string YamlString(const std::string& value);

}  // namespace splinecal

#endif  // SPLINECAL_IO_YAML_WRITER_H_
