// Loading YAML for every reader of splinecal: yaml-cpp behind a small interface that knows the
// file name, tolerates OpenCV's `%YAML:1.0` first line, and turns every problem into a
// splinecal::Error with the line of the offending key.
#ifndef SPLINECAL_IO_YAML_DOCUMENT_H_
#define SPLINECAL_IO_YAML_DOCUMENT_H_

#include <memory>
#include <string>
#include <vector>

namespace splinecal {

// A YAML mapping read from a file. Lookups by key path ("cam0/intrinsics") throw Error naming
// the file and the line of the node (or of the parent map when the key is missing).
class YamlDocument {
 public:
  explicit YamlDocument(const std::string& path);
  ~YamlDocument();
  YamlDocument(YamlDocument&&) noexcept;

  const std::string& path() const;
  bool Has(const std::string& key_path) const;
  double Number(const std::string& key_path) const;              // finite
  double PositiveNumber(const std::string& key_path) const;      // finite and > 0
  int64_t Integer(const std::string& key_path) const;
  std::string String(const std::string& key_path) const;
  std::vector<double> Numbers(const std::string& key_path) const;  // a flat sequence
  // A sequence of rows (e.g. T_cam_imu), each the same length; or an OpenCV matrix
  // ({rows, cols, data}).
  std::vector<std::vector<double>> Rows(const std::string& key_path) const;
  // Keys of the top-level map, in file order.
  std::vector<std::string> TopLevelKeys() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace splinecal

#endif  // SPLINECAL_IO_YAML_DOCUMENT_H_
