#include "row_checks.h"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <limits>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

std::string CsvRow(int64_t t_ns, std::initializer_list<Eigen::Ref<const Eigen::VectorXd>> blocks) {
  std::string row = std::to_string(t_ns);
  char number[32];  // ",%.17g" takes at most 25 characters
  for (const Eigen::Ref<const Eigen::VectorXd>& block : blocks) {
    for (Eigen::Index i = 0; i < block.size(); ++i) {
      std::snprintf(number, sizeof(number), ",%.17g", block[i]);
      row += number;
    }
  }
  row += '\n';
  return row;
}

bool IsHeaderRow(const TextFileReader& reader, const std::vector<std::string_view>& fields) {
  return reader.data_lines() == 1 && !fields.empty() && !LooksNumeric(fields[0]);
}

void CheckColumnCount(const TextFileReader& reader,
                      const std::vector<std::string_view>& fields,
                      size_t expected,
                      const std::string& format) {
  if (fields.size() == expected) return;
  reader.Fail("expected " + std::to_string(expected) + " columns (" + format + "), found " +
              std::to_string(fields.size()));
}

Eigen::Quaterniond CheckedUnitQuaternion(const TextFileReader& reader,
                                         std::string_view first_field,
                                         double w,
                                         double x,
                                         double y,
                                         double z) {
  // Files carry 6 to 17 significant digits; 1e-3 admits all of them and refuses anything that
  // is not a quaternion (positions or a wrong column order).
  constexpr double kNormTolerance = 1e-3;
  const Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (std::abs(norm - 1.0) > kNormTolerance) {
    reader.Fail(
        StringPrintf("quaternion has norm %.6g, expected 1 (columns in the wrong order?)", norm),
        first_field);
  }
  // Leave a quaternion that is unit to rounding untouched, so that files we wrote read back
  // bit-exactly; renormalise anything further off.
  constexpr double kUnitToRounding = 8 * std::numeric_limits<double>::epsilon();
  if (std::abs(norm - 1.0) <= kUnitToRounding) return q;
  return Eigen::Quaterniond(q.coeffs() / norm);
}

void FailNotIncreasing(const TextFileReader& reader,
                       int64_t previous_t_ns,
                       int64_t t_ns,
                       std::string_view field) {
  reader.Fail(std::string("timestamps not increasing: ") + std::to_string(t_ns) +
                  (t_ns == previous_t_ns
                       ? " repeats the previous row"
                       : " is before the previous row's " + std::to_string(previous_t_ns)),
              field);
}

void TimestampChecker::Add(int64_t t_ns, std::string_view field) {
  if (!times_.empty() && t_ns <= times_.back()) {
    FailNotIncreasing(*reader_, times_.back(), t_ns, field);
  }
  times_.push_back(t_ns);
  lines_.push_back(reader_->line_number());
}

void TimestampChecker::CheckGaps(double max_periods) const {
  if (times_.size() < 3) return;
  std::vector<int64_t> periods(times_.size() - 1);
  for (size_t i = 1; i < times_.size(); ++i) periods[i - 1] = times_[i] - times_[i - 1];
  std::vector<int64_t> sorted = periods;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = static_cast<double>(sorted[sorted.size() / 2]);
  for (size_t i = 0; i < periods.size(); ++i) {
    if (periods[i] > max_periods * median) {
      throw Error(reader_->path(),
                  lines_[i + 1],
                  StringPrintf("gap of %.6g s before this row (%.4g times the median period of "
                               "%.6g s)",
                               periods[i] * 1e-9,
                               periods[i] / median,
                               median * 1e-9));
    }
  }
}

}  // namespace internal
}  // namespace splinecal
