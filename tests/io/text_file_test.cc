#include "splinecal/io/text_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "splinecal/error.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

// The first data line of a file written with `text`, split into fields: the reader stays open
// for the parsers' error context (file:line:column).
class FirstLineFields {
 public:
  FirstLineFields(const std::string& name, const std::string& text)
      : path_(dir_.Write(name, text)), reader_(path_) {
    EXPECT_TRUE(reader_.NextLine()) << "no data line in " << path_;
    SplitFields(reader_.line(), &fields_);
  }

  const std::string& path() const { return path_; }
  const TextFileReader& reader() const { return reader_; }
  std::string_view operator[](int i) const { return fields_.at(i); }

 private:
  TempDir dir_;
  std::string path_;
  TextFileReader reader_;
  std::vector<std::string_view> fields_;
};

std::vector<std::string> DataLines(const std::string& path) {
  TextFileReader reader(path);
  std::vector<std::string> lines;
  while (reader.NextLine()) lines.emplace_back(reader.line());
  return lines;
}

TEST(TextFileReader, SkipsCommentsBlankLinesAndCarriageReturns) {
  TempDir dir;
  const std::string path = dir.Write("a.csv", "# header\r\n\r\n1,2\r\n   \n  # indented comment\n3,4");
  EXPECT_THAT(DataLines(path), ::testing::ElementsAre("1,2", "3,4"));
}

TEST(TextFileReader, LineNumbersCountEveryLine) {
  TempDir dir;
  const std::string path = dir.Write("a.csv", "#h\n\n1\n2\n");
  TextFileReader reader(path);
  ASSERT_TRUE(reader.NextLine());
  EXPECT_EQ(reader.line_number(), 3);
  ASSERT_TRUE(reader.NextLine());
  EXPECT_EQ(reader.line_number(), 4);
  EXPECT_FALSE(reader.NextLine());
}

TEST(TextFileReader, LinesStraddlingTheBufferAreWhole) {
  // Many times the 256 KiB buffer, with lines of varying length, so that some cross a refill.
  TempDir dir;
  std::string text;
  std::vector<std::string> expected;
  for (int i = 0; i < 300000; ++i) {
    expected.push_back(std::to_string(i) + "," + std::string(i % 17, 'x'));
    text += expected.back() + "\n";
  }
  EXPECT_EQ(DataLines(dir.Write("big.csv", text)), expected);
}

TEST(TextFileReader, MissingFileAndDirectoryAreClearErrors) {
  TempDir dir;
  try {
    TextFileReader reader(dir.File("nope.csv"));
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("nope.csv: cannot open"));
  }
  try {
    TextFileReader reader(dir.path());
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a directory"));
  }
}

TEST(LooksLikeYamlLine, YamlStartsButNoTableRow) {
  for (const char* yaml : {"%YAML:1.0",
                           "---",
                           "--- # a document",
                           "accelerometer_noise_density: 2.0e-3  # [ m / s^2 / sqrt(Hz) ]",
                           "cam0:",
                           "  rostopic: /imu0",
                           "update_rate:\t200.0"}) {
    EXPECT_TRUE(LooksLikeYamlLine(yaml)) << yaml;
  }
  for (const char* row : {"1403715273262142976,0.1,0.2,0.3,1,2,9.8",
                          "timestamp [ns],w_RS_S_x [rad s^-1]",
                          "t_ns,cam_id,point_id,u,v",
                          "1403715273.262 1 2 3 0 0 0 1",
                          "time:,x",
                          "http://example.org:80",
                          "-1.5,2"}) {
    EXPECT_FALSE(LooksLikeYamlLine(row)) << row;
  }
}

TEST(TextFileReader, RefusesAYamlFileOnItsFirstDataLineWithTheHint) {
  TempDir dir;
  const std::string path = dir.Write(
      "imu.yaml", "#Accelerometers\naccelerometer_noise_density: 2.0e-3\nupdate_rate: 200.0\n");
  TextFileReader reader(path);
  reader.set_yaml_hint("it goes to --imu-yaml");
  try {
    reader.NextLine();
    FAIL() << "a YAML file was read as a table";
  } catch (const Error& e) {
    EXPECT_EQ(e.line(), 2);
    EXPECT_THAT(e.what(), HasSubstr("imu.yaml:2"));
    EXPECT_THAT(e.what(),
                HasSubstr("a YAML file ('accelerometer_noise_density: 2.0e-3'), not a table of "
                          "numbers: it goes to --imu-yaml"));
  }
  // OpenCV's first line is YAML too, and a later "key:" line in a table is just a bad row.
  EXPECT_THROW(DataLines(dir.Write("cv.yaml", "%YAML:1.0\ncam0:\n")), Error);
  EXPECT_THAT(DataLines(dir.Write("t.csv", "1,2\nkey: 3\n")),
              ::testing::ElementsAre("1,2", "key: 3"));
}

TEST(SplitFields, CommasWithSpacesAndWhitespace) {
  std::vector<std::string_view> fields;
  SplitFields("1, 2 ,3,,", &fields);
  EXPECT_THAT(fields, ::testing::ElementsAre("1", "2", "3", "", ""));
  SplitFields("  1 \t2   3 ", &fields);
  EXPECT_THAT(fields, ::testing::ElementsAre("1", "2", "3"));
}

TEST(ParseFiniteDouble, ReportsFileLineColumnAndField) {
  const FirstLineFields fields("a.csv", "#h\n1,2.5,abc\n");
  const TextFileReader& reader = fields.reader();
  EXPECT_DOUBLE_EQ(ParseFiniteDouble(fields[1], reader, "x"), 2.5);
  try {
    ParseFiniteDouble(fields[2], reader, "gyro z");
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), fields.path() + ":2:7: gyro z: expected a number, got 'abc'");
  }
}

TEST(ParseFiniteDouble, RefusesNanInfAndOverflow) {
  const FirstLineFields fields("a.csv", "nan,inf,-inf,1e400,+3\n");
  const TextFileReader& reader = fields.reader();
  for (int i = 0; i < 4; ++i) {
    EXPECT_THROW(ParseFiniteDouble(fields[i], reader, "v"), Error) << fields[i];
  }
  EXPECT_EQ(ParseFiniteDouble(fields[4], reader, "v"), 3.0);
}

TEST(ParseInt64, ExactAndRangeChecked) {
  const FirstLineFields fields("a.csv", "1403715273262142976,99999999999999999999,1.5,-7\n");
  const TextFileReader& reader = fields.reader();
  EXPECT_EQ(ParseInt64(fields[0], reader, "t"), 1403715273262142976LL);
  EXPECT_THROW(ParseInt64(fields[1], reader, "t"), Error);
  EXPECT_THROW(ParseInt64(fields[2], reader, "t"), Error);
  EXPECT_EQ(ParseInt64(fields[3], reader, "t"), -7);
}

// Stamps beyond +-4e18 ns would let a difference of two of them overflow int64.
TEST(ParseTimestampNs, RefusesStampsBeyondThePlausibleRange) {
  const FirstLineFields fields(
      "a.txt",
      "4000000000000000000 -4000000000000000000 4000000000000000001 -9000000000000000000 "
      "4000000000.000000001 -4000000001 4e9\n");
  const TextFileReader& reader = fields.reader();
  EXPECT_EQ(ParseTimestampNs(fields[0], reader, "t"), kMaxTimestampNs);
  EXPECT_EQ(ParseTimestampNs(fields[1], reader, "t"), -kMaxTimestampNs);
  try {
    ParseTimestampNs(fields[2], reader, "t");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("a.txt:1:42: t: time '4000000000000000001' is outside the "
                                    "plausible range of +-4e18 ns"));
  }
  EXPECT_THROW(ParseTimestampNs(fields[3], reader, "t"), Error);
  // The same range for seconds (TUM).
  EXPECT_THROW(ParseSecondsToNs(fields[4], reader, "t"), Error);
  EXPECT_THROW(ParseSecondsToNs(fields[5], reader, "t"), Error);
  EXPECT_EQ(ParseSecondsToNs(fields[6], reader, "t"), kMaxTimestampNs);
}

TEST(ParseSecondsToNs, DigitExactWithoutFloatingPoint) {
  const FirstLineFields fields(
      "a.txt", "1403715273.262142976 1403715273.2621429765 12 0.5 -1.25 1.5e3 x1\n");
  const TextFileReader& reader = fields.reader();
  EXPECT_EQ(ParseSecondsToNs(fields[0], reader, "t"), 1403715273262142976LL);
  EXPECT_EQ(ParseSecondsToNs(fields[1], reader, "t"), 1403715273262142977LL);  // rounded
  EXPECT_EQ(ParseSecondsToNs(fields[2], reader, "t"), 12000000000LL);
  EXPECT_EQ(ParseSecondsToNs(fields[3], reader, "t"), 500000000LL);
  EXPECT_EQ(ParseSecondsToNs(fields[4], reader, "t"), -1250000000LL);
  EXPECT_EQ(ParseSecondsToNs(fields[5], reader, "t"), 1500000000000LL);
  EXPECT_THROW(ParseSecondsToNs(fields[6], reader, "t"), Error);
}

TEST(TextFile, DataLinesAndTryParsersAgreeWithTheReader) {
  EXPECT_EQ(TrimLine(" \t1,2 \r"), "1,2");
  EXPECT_TRUE(IsDataLine("  1,2\r"));
  EXPECT_FALSE(IsDataLine(" \t\r"));
  EXPECT_FALSE(IsDataLine("  # comment"));
  int64_t t = 0;
  EXPECT_TRUE(TryParseInt64("+1403715273262142976", &t));
  EXPECT_EQ(t, 1403715273262142976LL);
  EXPECT_FALSE(TryParseInt64("", &t));
  EXPECT_FALSE(TryParseInt64("12x", &t));
  EXPECT_FALSE(TryParseInt64("99999999999999999999", &t));
  double v = 0.0;
  EXPECT_TRUE(TryParseFiniteDouble("+2.5e-3", &v));
  EXPECT_EQ(v, 2.5e-3);
  for (const char* bad : {"", "+", "1.5.", "nan", "inf", "1e999", "x"}) {
    EXPECT_FALSE(TryParseFiniteDouble(bad, &v)) << bad;
  }
}

}  // namespace
}  // namespace splinecal
