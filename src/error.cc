#include "splinecal/error.h"

namespace splinecal {
namespace {

std::string Format(const std::string& path, int64_t line, int column, const std::string& message) {
  std::string where = path;
  if (line > 0) where += ":" + std::to_string(line);
  if (line > 0 && column > 0) where += ":" + std::to_string(column);
  return where + ": " + message;
}

}  // namespace

Error::Error(const std::string& message) : std::runtime_error(message), message_(message) {}

Error::Error(const std::string& path, int64_t line, const std::string& message, int column)
    : std::runtime_error(Format(path, line, column, message)),
      path_(path),
      line_(line),
      column_(column),
      message_(message) {}

}  // namespace splinecal
