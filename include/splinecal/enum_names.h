// Names of an enum's values, written once in one table that both directions read: the name of a
// value (output files, messages) and the value of a name (command lines, input files). A switch
// per direction spells every name twice, and the two can drift apart.
//
//   constexpr std::array<EnumName<Colour>, 2> kColourNames = {{{Colour::kRed, "red"},
//                                                              {Colour::kBlue, "blue"}}};
//   NameOf(kColourNames, Colour::kRed) == "red";  ValueNamed(kColourNames, "blue", &c) == true
#ifndef SPLINECAL_ENUM_NAMES_H_
#define SPLINECAL_ENUM_NAMES_H_

#include <glog/logging.h>

#include <array>
#include <cstddef>
#include <string>

namespace splinecal {

template <typename Enum>
struct EnumName {
  Enum value;
  const char* name;
};

// A table may carry more per value than its name: every function below takes any row type with
// the members `value` and `name`, e.g. struct {Kind value; const char* name; int num_parameters;}.

// The row of `value`. A value missing from the table is a programmer error (a new enumerator
// without its row), not bad input: it aborts.
template <typename Row, size_t N>
const Row& RowOf(const std::array<Row, N>& table, decltype(Row::value) value) {
  for (const Row& row : table) {
    if (row.value == value) return row;
  }
  LOG(FATAL) << "enum value " << static_cast<int>(value) << " has no row";
  return table[0];
}

// The name of `value` (aborts as RowOf does).
template <typename Row, size_t N>
const char* NameOf(const std::array<Row, N>& table, decltype(Row::value) value) {
  return RowOf(table, value).name;
}

// The value named `name` (exact spelling); false, leaving *value alone, when no row has it.
template <typename Row, size_t N>
bool ValueNamed(const std::array<Row, N>& table,
                const std::string& name,
                decltype(Row::value)* value) {
  for (const Row& row : table) {
    if (name == row.name) {
      *value = row.value;
      return true;
    }
  }
  return false;
}

// Every name in table order, joined by `separator` (for messages and --help).
template <typename Row, size_t N>
std::string JoinNames(const std::array<Row, N>& table, const std::string& separator) {
  std::string names;
  for (const Row& row : table) {
    if (!names.empty()) names += separator;
    names += row.name;
  }
  return names;
}

}  // namespace splinecal

#endif  // SPLINECAL_ENUM_NAMES_H_
