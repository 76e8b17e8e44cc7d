// The strict YAML check of the tests (tests/testing/strict_yaml.h) finds what yaml-cpp accepts.
#include "testing/strict_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <string>

namespace splinecal {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

TEST(DuplicateYamlKeys, TopLevelKeyTwice) {
  const std::string text = "a: 1\nb: 2\na: 3\n";
  ASSERT_NO_THROW(YAML::Load(text));  // what the strict check is for: yaml-cpp takes it
  EXPECT_THAT(testing::DuplicateYamlKeys(text),
              ElementsAre("line 3: key 'a' repeats (first at line 1)"));
}

TEST(DuplicateYamlKeys, NestedAndFlowMaps) {
  EXPECT_THAT(testing::DuplicateYamlKeys("cam0:\n  x: 1\n  y: [1, 2]\n  x: 2\n"),
              ElementsAre("line 4: key 'x' repeats (first at line 2)"));
  EXPECT_THAT(testing::DuplicateYamlKeys("m: {p: 1, p: 2}\n"), ElementsAre(HasSubstr("'p'")));
  // A key whose value is a map or a list is a key like any other.
  EXPECT_THAT(testing::DuplicateYamlKeys("m:\n  a: 1\nm:\n  b: 2\n"),
              ElementsAre("line 3: key 'm' repeats (first at line 1)"));
}

TEST(DuplicateYamlKeys, SameKeyInDifferentMapsIsFine) {
  EXPECT_THAT(testing::DuplicateYamlKeys("cam0:\n  T: [1]\n  x: 1\ncam1:\n  T: [2]\n  x: 1\n"
                                         "list:\n  - {x: 1}\n  - {x: 2}\nx: 3\n"),
              IsEmpty());
}

TEST(DuplicateYamlKeys, SyntaxErrorIsAProblem) {
  EXPECT_THAT(testing::DuplicateYamlKeys("a: [1, 2\n"), ElementsAre(HasSubstr("not YAML")));
}

TEST(LoadStrictYaml, FailsTheTestOnARepeatedKey) {
  EXPECT_NONFATAL_FAILURE(testing::LoadStrictYaml("k: 1\nk: 2\n", "result.yaml"),
                          "result.yaml: line 2: key 'k' repeats");
  EXPECT_EQ(testing::LoadStrictYaml("k: 1\n")["k"].as<int>(), 1);
}

}  // namespace
}  // namespace splinecal
