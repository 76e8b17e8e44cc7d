#include "splinecal/io/text_file.h"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

constexpr size_t kBufferBytes = size_t{256} << 10;
// A single line longer than this is not a data line of any format we read; refusing it bounds
// memory on a file without newlines.
constexpr size_t kMaxLineBytes = size_t{1} << 20;

std::string Quote(std::string_view field) {
  constexpr size_t kShown = 40;
  std::string shown(field.substr(0, kShown));
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
  }
  if (field.size() > kShown) shown += "...";
  return "'" + shown + "'";
}

void CheckIsReadableFile(const std::string& path) {
  struct stat info;
  if (::stat(path.c_str(), &info) != 0) {
    throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  }
  if (S_ISDIR(info.st_mode)) throw Error(path, 0, "is a directory, expected a file");
}

// std::from_chars over the whole field, after one leading '+' (which from_chars does not take):
// its error code, and whether it read every character of a non-empty field.
struct FieldParse {
  std::errc ec;
  bool whole;
};

template <typename T>
FieldParse FromCharsWhole(std::string_view field, T* value) {
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  const auto result = std::from_chars(field.data(), field.data() + field.size(), *value);
  return {result.ec, !field.empty() && result.ptr == field.data() + field.size()};
}

}  // namespace

TextFileReader::TextFileReader(const std::string& path) : path_(path) {
  CheckIsReadableFile(path);
  file_ = std::fopen(path.c_str(), "rb");
  if (file_ == nullptr) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  buffer_.resize(kBufferBytes);
}

TextFileReader::~TextFileReader() {
  if (file_ != nullptr) std::fclose(file_);
}

bool TextFileReader::ReadRawLine() {
  long_line_.clear();
  bool straddles = false;
  while (true) {
    if (begin_ == end_) {
      if (eof_) {
        if (!straddles) return false;
        line_ = long_line_;
        ++line_number_;
        return true;
      }
      end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_);
      begin_ = 0;
      if (end_ < buffer_.size()) {
        if (std::ferror(file_)) Fail(std::string("read error: ") + std::strerror(errno));
        eof_ = true;
      }
      continue;
    }
    const char* start = buffer_.data() + begin_;
    const void* newline = std::memchr(start, '\n', end_ - begin_);
    if (newline == nullptr) {
      long_line_.append(start, end_ - begin_);
      begin_ = end_;
      straddles = true;
      if (long_line_.size() > kMaxLineBytes) {
        ++line_number_;
        Fail("line longer than 1 MiB: not a text data file");
      }
      continue;
    }
    const size_t length = static_cast<const char*>(newline) - start;
    begin_ += length + 1;
    ++line_number_;
    if (straddles) {
      long_line_.append(start, length);
      line_ = long_line_;
    } else {
      line_ = std::string_view(start, length);
    }
    return true;
  }
}

bool TextFileReader::NextLine() {
  while (ReadRawLine()) {
    if (!line_.empty() && line_.back() == '\r') line_.remove_suffix(1);
    if (!IsDataLine(line_)) {
      const std::string_view content = TrimLine(line_);
      if (comment_visitor_ && !content.empty()) comment_visitor_(content);
      continue;
    }
    ++data_lines_;
    // Only the first data line: a table whose first row is data or a header is never YAML, and
    // the check then costs nothing on files of 10^7 rows.
    if (data_lines_ == 1 && LooksLikeYamlLine(line_)) {
      Fail("a YAML file (" + Quote(TrimLine(line_)) + "), not a table of numbers" +
           (yaml_hint_.empty() ? "" : ": " + yaml_hint_));
    }
    return true;
  }
  line_ = std::string_view();
  return false;
}

void TextFileReader::Fail(const std::string& message) const {
  throw Error(path_, line_number_, message);
}

void TextFileReader::Fail(const std::string& message, std::string_view field) const {
  int column = 0;
  if (field.data() >= line_.data() && field.data() <= line_.data() + line_.size()) {
    column = static_cast<int>(field.data() - line_.data()) + 1;
  }
  throw Error(path_, line_number_, message, column);
}

void SplitFields(std::string_view line, std::vector<std::string_view>* fields) {
  fields->clear();
  if (line.find(',') != std::string_view::npos) {
    size_t start = 0;
    while (true) {
      const size_t comma = line.find(',', start);
      const size_t stop = comma == std::string_view::npos ? line.size() : comma;
      fields->push_back(TrimLine(line.substr(start, stop - start)));
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    return;
  }
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) fields->push_back(line.substr(start, i - start));
  }
}

bool LooksLikeYamlLine(std::string_view line) {
  const std::string_view content = TrimLine(line);
  if (content.rfind("%YAML", 0) == 0) return true;
  if (content == "---" || content.rfind("--- ", 0) == 0) return true;
  if (content.empty() ||
      !(std::isalpha(static_cast<unsigned char>(content[0])) || content[0] == '_')) {
    return false;
  }
  size_t i = 1;
  while (i < content.size() && (std::isalnum(static_cast<unsigned char>(content[i])) ||
                                content[i] == '_' || content[i] == '.' || content[i] == '-')) {
    ++i;
  }
  return i < content.size() && content[i] == ':' &&
         (i + 1 == content.size() || content[i + 1] == ' ' || content[i + 1] == '\t');
}

bool LooksNumeric(std::string_view field) {
  double value = 0.0;
  const FieldParse parse = FromCharsWhole(field, &value);
  return parse.ec == std::errc() && parse.whole;
}

double ParseFiniteDouble(std::string_view field, const TextFileReader& at, const std::string& what) {
  double value = 0.0;
  if (TryParseFiniteDouble(field, &value)) return value;
  // Tell a field that is no number from one that is not finite.
  const FieldParse parse = FromCharsWhole(field, &value);
  if (!parse.whole || (parse.ec != std::errc() && parse.ec != std::errc::result_out_of_range)) {
    at.Fail(what + ": expected a number, got " + Quote(field), field);
  }
  at.Fail(what + ": value " + Quote(field) + " is not a finite number", field);
}

double ParseBoundedDouble(std::string_view field,
                          const TextFileReader& at,
                          const std::string& what,
                          double max_abs,
                          const char* unit) {
  const double value = ParseFiniteDouble(field, at, what);
  if (std::abs(value) > max_abs) {
    at.Fail(what + StringPrintf(": value %.6g is beyond the plausible %g %s", value, max_abs, unit),
            field);
  }
  return value;
}

int64_t ParseInt64(std::string_view field, const TextFileReader& at, const std::string& what) {
  int64_t value = 0;
  if (TryParseInt64(field, &value)) return value;
  // Tell an integer out of range from a field that is no integer.
  if (FromCharsWhole(field, &value).ec == std::errc::result_out_of_range) {
    at.Fail(what + ": integer " + Quote(field) + " is out of range", field);
  }
  at.Fail(what + ": expected an integer, got " + Quote(field), field);
}

namespace {

[[noreturn]] void FailTimestampRange(std::string_view field,
                                     const TextFileReader& at,
                                     const std::string& what) {
  at.Fail(what + ": time " + Quote(field) +
              " is outside the plausible range of +-4e18 ns (the years 1843 to 2096 as Unix time)",
          field);
}

}  // namespace

int64_t ParseTimestampNs(std::string_view field,
                         const TextFileReader& at,
                         const std::string& what) {
  const int64_t t_ns = ParseInt64(field, at, what);
  if (t_ns > kMaxTimestampNs || t_ns < -kMaxTimestampNs) FailTimestampRange(field, at, what);
  return t_ns;
}

int64_t ParseSecondsToNs(std::string_view field, const TextFileReader& at, const std::string& what) {
  std::string_view text = field;
  bool negative = false;
  if (!text.empty() && (text.front() == '+' || text.front() == '-')) {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  const size_t dot = text.find('.');
  const std::string_view whole = text.substr(0, dot);
  const std::string_view fraction =
      dot == std::string_view::npos ? std::string_view() : text.substr(dot + 1);
  auto all_digits = [](std::string_view s) {
    for (char c : s) {
      if (c < '0' || c > '9') return false;
    }
    return true;
  };
  if ((whole.empty() && fraction.empty()) || !all_digits(whole) || !all_digits(fraction)) {
    // Exponent notation or junk: accept a plain double when it is one (seconds then lose
    // sub-microsecond precision, which such files never had).
    const double seconds = ParseFiniteDouble(field, at, what);
    if (std::abs(seconds) * 1e9 > kMaxTimestampNs) FailTimestampRange(field, at, what);
    return static_cast<int64_t>(std::llround(seconds * 1e9));
  }
  constexpr int64_t kMaxSeconds = kMaxTimestampNs / 1'000'000'000;
  int64_t seconds = 0;
  for (char c : whole) {
    seconds = seconds * 10 + (c - '0');
    if (seconds > kMaxSeconds) FailTimestampRange(field, at, what);
  }
  int64_t nanos = 0;
  for (size_t i = 0; i < 9; ++i) nanos = nanos * 10 + (i < fraction.size() ? fraction[i] - '0' : 0);
  if (fraction.size() > 9 && fraction[9] >= '5') ++nanos;  // round half up on the 10th digit
  const int64_t total = seconds * 1'000'000'000 + nanos;
  if (total > kMaxTimestampNs) FailTimestampRange(field, at, what);
  return negative ? -total : total;
}

std::string ReadWholeFile(const std::string& path) {
  CheckIsReadableFile(path);
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) throw Error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::string contents;
  char chunk[65536];
  size_t n = 0;
  while ((n = std::fread(chunk, 1, sizeof(chunk), file)) > 0) {
    contents.append(chunk, n);
    if (contents.size() > (size_t{64} << 20)) {
      std::fclose(file);
      throw Error(path, 0, "larger than 64 MiB: not a configuration file");
    }
  }
  const bool failed = std::ferror(file) != 0;
  std::fclose(file);
  if (failed) throw Error(path, 0, "read error");
  return contents;
}

}  // namespace splinecal
