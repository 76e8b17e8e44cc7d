// Checks shared by the table readers of io/, and the data row of its CSV writers (internal: not
// part of the public API).
#ifndef SPLINECAL_SRC_IO_ROW_CHECKS_H_
#define SPLINECAL_SRC_IO_ROW_CHECKS_H_

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "splinecal/io/text_file.h"

namespace splinecal {
namespace internal {

// A first data row whose first field is not a number is a header written without '#'
// (some tools do that); it is skipped. Anywhere else it is data and fails to parse.
bool IsHeaderRow(const TextFileReader& reader, const std::vector<std::string_view>& fields);

// row(fields) for every data row of `reader` in turn, its fields split (SplitFields), a header
// row skipped (IsHeaderRow).
template <typename Row>
void ForEachDataRow(TextFileReader* reader, const Row& row) {
  std::vector<std::string_view> fields;
  while (reader->NextLine()) {
    SplitFields(reader->line(), &fields);
    if (IsHeaderRow(*reader, fields)) continue;
    row(fields);
  }
}

// Throws "expected N columns (format), found M".
void CheckColumnCount(const TextFileReader& reader,
                      const std::vector<std::string_view>& fields,
                      size_t expected,
                      const std::string& format);

// Builds a unit quaternion; throws when its norm differs from 1 by more than 1e-3 (a file in
// another order or not a quaternion at all), else normalises it.
Eigen::Quaterniond CheckedUnitQuaternion(const TextFileReader& reader,
                                         std::string_view first_field,
                                         double w,
                                         double x,
                                         double y,
                                         double z);

// Throws "timestamps not increasing: ..." at `field`, for a row whose t_ns is not after the
// previous row's (callers test t_ns <= previous_t_ns themselves: this runs once per row).
[[noreturn]] void FailNotIncreasing(const TextFileReader& reader,
                                    int64_t previous_t_ns,
                                    int64_t t_ns,
                                    std::string_view field);

// A CSV data row: t_ns, then every entry of `blocks` in order with 17 significant digits (they
// read back bit-exactly), and '\n'.
std::string CsvRow(int64_t t_ns, std::initializer_list<Eigen::Ref<const Eigen::VectorXd>> blocks);

// Timestamps must increase strictly; gaps are measured against the median period.
class TimestampChecker {
 public:
  explicit TimestampChecker(const TextFileReader* reader) : reader_(reader) {}
  void Add(int64_t t_ns, std::string_view field);
  // Throws when a gap exceeds max_periods median periods (naming the line after the gap).
  void CheckGaps(double max_periods) const;

 private:
  const TextFileReader* reader_;
  std::vector<int64_t> times_;
  std::vector<int64_t> lines_;
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_IO_ROW_CHECKS_H_
