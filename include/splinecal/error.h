// The one error type of splinecal.
//
// Graded errors, as in Ceres: a bad input file or a violated precondition on user data throws
// splinecal::Error; a numerical failure inside a Ceres callback returns false; a library bug is a
// glog CHECK. The command-line front end catches Error, prints what() on one line of stderr and
// exits with code 2 (docs/conventions.md, "Command line").
#ifndef SPLINECAL_ERROR_H_
#define SPLINECAL_ERROR_H_

#include <cstdint>
#include <stdexcept>
#include <string>

namespace splinecal {

class Error : public std::runtime_error {
 public:
  // An error that is not tied to a file: what() is the message alone.
  explicit Error(const std::string& message);
  // An error in a file: what() reads "path:line: message" (line 0 means the whole file) or
  // "path:line:column: message" when column > 0. Lines and columns count from 1.
  Error(const std::string& path, int64_t line, const std::string& message, int column = 0);

  const std::string& path() const { return path_; }
  int64_t line() const { return line_; }
  int column() const { return column_; }
  const std::string& message() const { return message_; }

 private:
  std::string path_;
  int64_t line_ = 0;
  int column_ = 0;
  std::string message_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ERROR_H_
