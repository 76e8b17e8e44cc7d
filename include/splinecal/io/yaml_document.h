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
  // The line of the node at key_path (1-based; 0 when missing), for messages of the readers.
  int64_t Line(const std::string& key_path) const;
  double Number(const std::string& key_path) const;              // finite
  // Finite, and at most max_abs in magnitude: a larger value is refused as implausible for the
  // quantity (a corrupt file or another unit), naming the limit and `unit`.
  double BoundedNumber(const std::string& key_path, double max_abs, const char* unit) const;
  double PositiveNumber(const std::string& key_path) const;      // finite and > 0
  double PositiveNumber(const std::string& key_path, double max_abs, const char* unit) const;
  int64_t Integer(const std::string& key_path) const;
  std::string String(const std::string& key_path) const;
  std::vector<double> Numbers(const std::string& key_path) const;  // a flat sequence
  std::vector<std::string> Strings(const std::string& key_path) const;  // a flat sequence
  std::vector<double> BoundedNumbers(const std::string& key_path,
                                     double max_abs,
                                     const char* unit) const;
  // A sequence of rows (e.g. T_cam_imu), each the same length; or an OpenCV matrix
  // ({rows, cols, data}).
  std::vector<std::vector<double>> Rows(const std::string& key_path) const;
  // Keys of the top-level map, in file order.
  std::vector<std::string> TopLevelKeys() const;

  // Refuses a key of the map at map_path ("" for the top level) that is not in `known` but
  // differs only slightly (case, a letter or two) from a key of `known` the map lacks: a typo,
  // which would otherwise leave an optional key at its default without a word, or be reported
  // as a missing key without the line that holds it.
  void CheckTypos(const std::string& map_path, const std::vector<std::string>& known) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace splinecal

#endif  // SPLINECAL_IO_YAML_DOCUMENT_H_
