// The one input layer's base: a streaming reader of text data files, field splitting and number
// parsing that report errors as "path:line:column: what was expected".
//
// Every reader of splinecal (EuRoC, TUM, spline.csv, plain columns, observations) is built on
// this file, so every file format accepts the same things (docs/conventions.md, "File formats"):
// CRLF line ends, blank lines, '#' comment lines, spaces after commas. And every one refuses a
// YAML file the same way: a configuration file given where a table is expected (Kalibr's
// imu.yaml as --imu) is named as such on its first data line, not reported as a wrong column
// count further down.
#ifndef SPLINECAL_IO_TEXT_FILE_H_
#define SPLINECAL_IO_TEXT_FILE_H_

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace splinecal {

// Reads a text file one data line at a time without loading it whole (files of 10^8 rows stream
// through a fixed 256 KiB buffer).
class TextFileReader {
 public:
  // Throws Error(path, 0, ...) when the file is missing, a directory or unreadable.
  explicit TextFileReader(const std::string& path);
  ~TextFileReader();
  TextFileReader(const TextFileReader&) = delete;
  TextFileReader& operator=(const TextFileReader&) = delete;

  // Advances to the next data line: blank lines and lines whose first non-blank character is '#'
  // are skipped, a trailing CR is removed. Returns false at the end of the file. Throws when the
  // first data line is YAML (LooksLikeYamlLine): "a YAML file (...), not a table".
  bool NextLine();

  // Appended to the error for a YAML file, to say where that YAML belongs (the CLI names the
  // flag that takes it, e.g. --imu-yaml).
  void set_yaml_hint(const std::string& hint) { yaml_hint_ = hint; }

  // Called by NextLine with each '#' comment line it skips (trimmed, the '#' kept), for formats
  // that keep metadata in comments (spline.csv's "# trajectory: split"); Fail() inside it
  // reports that line.
  void set_comment_visitor(std::function<void(std::string_view comment)> visitor) {
    comment_visitor_ = std::move(visitor);
  }

  std::string_view line() const { return line_; }
  int64_t line_number() const { return line_number_; }
  const std::string& path() const { return path_; }
  // Data lines returned so far.
  int64_t data_lines() const { return data_lines_; }

  // Throws Error for the current line. `field` (a view into line()) gives the column.
  [[noreturn]] void Fail(const std::string& message) const;
  [[noreturn]] void Fail(const std::string& message, std::string_view field) const;

 private:
  bool ReadRawLine();

  std::string path_;
  std::FILE* file_ = nullptr;
  std::vector<char> buffer_;
  size_t begin_ = 0;  // unread bytes of buffer_ are [begin_, end_)
  size_t end_ = 0;
  bool eof_ = false;
  std::string long_line_;  // a line that straddles buffer refills
  std::string_view line_;
  int64_t line_number_ = 0;
  int64_t data_lines_ = 0;
  std::string yaml_hint_;
  std::function<void(std::string_view)> comment_visitor_;
};

// The line and number primitives of every reader, shared with code that scans a file itself (the
// parallel EuRoC path, io/parallel_euroc_imu.h) so that both accept exactly the same text. Inline:
// they run once per line or field, on files of 10^7 rows.

// `line` without surrounding spaces and tabs and without a trailing CR.
inline std::string_view TrimLine(std::string_view line) {
  while (!line.empty() && (line.front() == ' ' || line.front() == '\t')) line.remove_prefix(1);
  while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r')) {
    line.remove_suffix(1);
  }
  return line;
}

// The data of a line as TrimLine leaves it; empty for a blank line and a '#' comment line.
inline std::string_view DataLineContent(std::string_view line) {
  const std::string_view content = TrimLine(line);
  return !content.empty() && content.front() == '#' ? std::string_view() : content;
}

// True for a line that holds data: not blank and not a '#' comment line (the lines
// TextFileReader::NextLine returns).
inline bool IsDataLine(std::string_view line) { return !DataLineContent(line).empty(); }

// The number at the start of [begin, end) (T is int64_t or double): an optional '+', then what
// std::from_chars reads. Returns the first character after it; nullptr when there is no number or
// it is out of range. A double may be inf or nan: callers check finiteness (TryParseFiniteDouble)
// or a finite limit, which refuses both.
template <typename T>
inline const char* ParseNumberPrefix(const char* begin, const char* end, T* value) {
  const bool plus = begin != end && *begin == '+';  // std::from_chars refuses it
  const std::from_chars_result result = std::from_chars(begin + plus, end, *value);
  return result.ec == std::errc() ? result.ptr : nullptr;
}

// The parsers below without error reporting, for callers that hand failures to them: true when
// the whole field reads as an int64, or as a finite double.
inline bool TryParseInt64(std::string_view field, int64_t* value) {
  const char* end = field.data() + field.size();
  return ParseNumberPrefix(field.data(), end, value) == end;
}
inline bool TryParseFiniteDouble(std::string_view field, double* value) {
  const char* end = field.data() + field.size();
  return ParseNumberPrefix(field.data(), end, value) == end && std::isfinite(*value);
}

// Splits a data line into fields: at commas (surrounding spaces trimmed) when the line has a
// comma, else at runs of spaces and tabs. `fields` views into `line`.
void SplitFields(std::string_view line, std::vector<std::string_view>* fields);

// True for a line that starts a YAML document and never a table row: OpenCV's "%YAML:1.0", a
// "---" document marker, or a mapping key ("name:" then a blank or the end; letters, digits, '_',
// '.' or '-', starting with a letter or '_').
bool LooksLikeYamlLine(std::string_view line);

// True when the field reads as a number (used to tell a header row without '#' from data).
bool LooksNumeric(std::string_view field);

// Parses a finite double; throws "path:line:column: <what>: expected a number, got 'x'" or
// "...: value is not finite". `what` names the field (e.g. "gyro x").
double ParseFiniteDouble(std::string_view field, const TextFileReader& at, const std::string& what);
// Parses a finite double whose magnitude is at most `max_abs`; a larger value is refused as
// implausible for the quantity (a corrupt file or wrong units), naming the limit and `unit`.
double ParseBoundedDouble(std::string_view field,
                          const TextFileReader& at,
                          const std::string& what,
                          double max_abs,
                          const char* unit);

// Plausibility limits of the readers: far beyond any real rig, small enough that squares and
// products of them stay finite in double.
inline constexpr double kMaxAngularRate = 1e3;     // [rad/s]
inline constexpr double kMaxAcceleration = 1e4;    // [m/s^2]
inline constexpr double kMaxPosition = 1e7;        // [m]
inline constexpr double kMaxVelocity = 1e5;        // [m/s]

// Parses a decimal int64 without going through floating point.
int64_t ParseInt64(std::string_view field, const TextFileReader& at, const std::string& what);

// Timestamps beyond +-4e18 ns (as Unix time, the years 1843 to 2096) are refused: the difference
// of any two accepted stamps then fits in int64, so that periods, gaps and spans never overflow.
inline constexpr int64_t kMaxTimestampNs = 4'000'000'000'000'000'000;
// ParseInt64 for a timestamp [ns], refused beyond kMaxTimestampNs.
int64_t ParseTimestampNs(std::string_view field, const TextFileReader& at, const std::string& what);
// Parses seconds written as decimal text ("1403715273.262142976") into int64 nanoseconds
// exactly, digit by digit (never through a double); more than 9 decimals are rounded. Refused
// beyond kMaxTimestampNs.
int64_t ParseSecondsToNs(std::string_view field, const TextFileReader& at, const std::string& what);

// Reads a whole small file (YAML) into a string; throws Error(path, 0, ...) when unreadable.
std::string ReadWholeFile(const std::string& path);

}  // namespace splinecal

#endif  // SPLINECAL_IO_TEXT_FILE_H_
