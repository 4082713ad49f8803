#include "io/base/json_file.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

using nlohmann::json;

TEST(JsonFile, MatricesReadOneRowPerLine) {
  const json value = {{"name", "x"}, {"rows", {{1.5, 2}, {3, 0.1}}}, {"empty", json::array()}};
  EXPECT_EQ(FormatJson(value),
            "{\n \"empty\": [],\n \"name\": \"x\",\n \"rows\": [\n  [1.5,2],\n  [3,0.1]\n ]\n}\n");
}

TEST(JsonFile, FormatParsesBackToTheSameValueExactly) {
  const json value = {{"a", {{0.1 + 0.2, -2.43511e-15, 1e300}}}, {"b", {{"c", {true, nullptr}}}}};
  EXPECT_EQ(json::parse(FormatJson(value)), value);
}

TEST(JsonFile, ReaderNamesFileAndField) {
  const json value = {{"n", 3}, {"x", "text"}, {"v", nullptr}};
  const JsonReader in("f.json");
  EXPECT_EQ(in.Get<int>(value, "n", ""), 3);
  test::ExpectInputError([&] { in.Get<int>(value, "m", "top."); }, {"f.json", "field 'top.m' missing"});
  test::ExpectInputError([&] { in.Get<int>(value, "x", ""); }, {"'x' has the wrong type (string)"});
  test::ExpectInputError([&] { in.Get<double>(value, "v", ""); }, {"'v' has the wrong type (null)"});
}

TEST(JsonFile, ReadJsonFileReportsWhereParsingFailed) {
  test::TempDir dir;
  test::ExpectInputError([&] { ReadJsonFile(dir.Write("bad.json", "{\n \"a\": [1,\n"), "a thing"); },
                         {"bad.json", "invalid JSON", "line 3"});
}

}  // namespace
}  // namespace jgpm
