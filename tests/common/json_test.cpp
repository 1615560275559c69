// The strict JSON reader every module uses: each malformed document gets a FormatError that
// names its origin and what is wrong.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "../common/error_of.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/json.hpp"

using tactile::test::error_of;

namespace tactile {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(Json, ParseErrorsNameTheOrigin) {
  const JsonOrigin at{"doc.json"};
  EXPECT_THAT(error_of<FormatError>([&] { parse_json(at, "{\"a\": "); }),
              HasSubstr("doc.json: not valid JSON"));
  // A number beyond a double is nlohmann's out_of_range, not a parse error: still a FormatError.
  EXPECT_THAT(error_of<FormatError>([&] { parse_json(at, "{\"a\": 1e999}"); }),
              HasSubstr("doc.json: not valid JSON"));
}

// Found by the second hostile-input run: nlohmann keeps the last of two equal keys, so a layout
// file with "rows" twice silently meant the second; and its messages carried the library's
// "[json.exception.parse_error.101]" tag.
TEST(Json, RepeatedKeysAreRefusedAndMessagesAreTheProgramsWords) {
  const JsonOrigin at{"doc.json"};
  EXPECT_THAT(
      error_of<FormatError>([&] { parse_json(at, R"({"rows": 6, "cols": 2, "rows": 200})"); }),
      HasSubstr("doc.json: field 'rows' appears twice"));
  EXPECT_THAT(error_of<FormatError>([&] { parse_json(at, R"({"a": {"b": 1, "b": 2}})"); }),
              HasSubstr("field 'b' appears twice"));
  // The same key in two different objects is no repetition.
  EXPECT_NO_THROW(parse_json(at, R"({"a": {"b": 1}, "c": {"b": 2}, "b": [{"b": 3}, {"b": 4}]})"));
  const std::string cut = error_of<FormatError>([&] { parse_json(at, "{\"a\": "); });
  EXPECT_THAT(cut, HasSubstr("doc.json: not valid JSON (parse error at line 1"));
  EXPECT_THAT(cut, ::testing::Not(HasSubstr("json.exception")));
  EXPECT_THAT(error_of<FormatError>([&] { parse_json(at, "[1e999]"); }),
              ::testing::AllOf(HasSubstr("number overflow parsing '1e999'"),
                               ::testing::Not(HasSubstr("json.exception"))));
}

TEST(Json, FieldsAreCheckedForWhatAPersonMeant) {
  const JsonOrigin at{"doc.json"};
  const auto j = parse_json(at, R"({"n": "3", "i": 2.5, "s": "", "x": 1, "nan": null})");
  EXPECT_THAT(error_of<FormatError>([&] { json_number(at, j["n"], "n"); }),
              HasSubstr("doc.json: 'n' must be a number, got \"3\""));
  EXPECT_THAT(error_of<FormatError>([&] { json_integer(at, j["i"], "i"); }),
              HasSubstr("doc.json: 'i' must be an integer, got 2.5"));
  EXPECT_THAT(error_of<FormatError>([&] { json_string(at, j["s"], "s"); }),
              HasSubstr("'s' must be a non-empty string"));
  EXPECT_THAT(error_of<FormatError>([&] { json_required(at, j, "missing", "the doc"); }),
              HasSubstr("doc.json: the doc: missing field 'missing'"));
  EXPECT_THAT(error_of<FormatError>([&] { json_required(at, j, "missing", ""); }),
              HasSubstr("doc.json: missing field 'missing'"));
  EXPECT_THAT(error_of<FormatError>([&] {
                json_only_keys(at, j, "the doc", {"n", "i", "s", "nan"});
              }),
              HasSubstr("the doc: unknown field 'x'"));
  EXPECT_THAT(error_of<FormatError>([&] { json_field<int>(j, "s", "doc.json"); }),
              HasSubstr("field 's' has the wrong type"));
  EXPECT_DOUBLE_EQ(json_number(at, j["x"], "x"), 1.0);
  EXPECT_EQ(json_integer(at, j["x"], "x"), 1);
}

// A fuzzed pore model's format_version of 666666666666666666661 (beyond 64 bits, so parsed as a
// double) reached an int with undefined behaviour; every integer field is checked for its type's
// range and for being whole, and says so with the number as written.
TEST(Json, AnIntegerFieldBeyondItsTypeOrWithAFractionIsRefused) {
  const JsonOrigin at{"doc.json"};
  const auto j = parse_json(at, R"({"huge": 666666666666666666661, "big": 3000000000,
      "below": -3000000000, "half": 2.5, "max": 2147483647, "neg": -7, "u": 3000000000})");
  EXPECT_THAT(error_of<FormatError>([&] { json_field<int>(j, "huge", "doc.json"); }),
              HasSubstr("doc.json: field 'huge' must be a whole number from -2147483648 to "
                        "2147483647, got 6.666666666666"));
  EXPECT_THAT(error_of<FormatError>([&] { json_field<int>(j, "big", "doc.json"); }),
              HasSubstr("field 'big' must be a whole number from -2147483648 to 2147483647, got "
                        "3000000000"));
  EXPECT_THAT(error_of<FormatError>([&] { json_field<int>(j, "below", "doc.json"); }),
              HasSubstr("got -3000000000"));
  EXPECT_THAT(error_of<FormatError>([&] { json_field<int>(j, "half", "doc.json"); }),
              HasSubstr("field 'half' must be a whole number"));
  EXPECT_EQ(json_field<int>(j, "max", "doc.json"), 2147483647);
  EXPECT_EQ(json_field<int>(j, "neg", "doc.json"), -7);
  EXPECT_EQ(json_field<std::int64_t>(j, "u", "doc.json"), 3000000000LL);
  EXPECT_THAT(error_of<FormatError>([&] { json_field<std::uint32_t>(j, "neg", "doc.json"); }),
              HasSubstr("from 0 to 4294967295, got -7"));
}

class Files : public ::testing::Test {
 protected:
  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

TEST_F(Files, ReadJsonObjectRefusesWhatIsNotAnObject) {
  EXPECT_THAT(error_of<FormatError>([&] { read_json_object(dir_ / "none.json", "a calibration"); }),
              HasSubstr("none.json: cannot open a calibration"));
  std::ofstream(dir_ / "list.json") << "[1, 2]";
  EXPECT_THAT(error_of<FormatError>([&] { read_json_object(dir_ / "list.json", "a calibration"); }),
              HasSubstr("list.json: expected a JSON object"));
  // Found by the second hostile-input run: a FIFO as the model file blocked the read forever.
  ASSERT_EQ(::mkfifo((dir_ / "fifo.json").c_str(), 0600), 0);
  EXPECT_THAT(error_of<FormatError>([&] { read_json_object(dir_ / "fifo.json", "a model file"); }),
              HasSubstr("fifo.json: cannot open a model file: not a regular file"));
  EXPECT_THAT(error_of<FormatError>([&] { read_json_object(dir_, "a model file"); }),
              HasSubstr("not a regular file"));
  std::ofstream(dir_ / "empty.json") << "";
  EXPECT_THAT(
      error_of<FormatError>([&] { read_json_object(dir_ / "empty.json", "a calibration"); }),
      HasSubstr("empty.json: not valid JSON"));
}

}  // namespace
}  // namespace tactile
