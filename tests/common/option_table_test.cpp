// The option table's rules, which both front ends apply: ranges, choices, paths and unset
// values, worded with the front end's spelling of the option.

#include "tactile/common/option_table.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>

namespace {

using tactile::OptionRow;
using tactile::OptionSpelling;
using tactile::RequestError;
using ::testing::HasSubstr;
namespace rows = tactile::option_rows;

enum class Colour { red, green };
constexpr std::array<tactile::Named<Colour>, 2> kColourNames = {
    {{Colour::red, "red"}, {Colour::green, "green"}}};

struct Request {
  double scale_mm = 1.5;
  std::optional<int> count;
  Colour colour = Colour::green;
  std::optional<std::filesystem::path> file;
};

const std::vector<OptionRow<Request>>& table() {
  static const std::vector<OptionRow<Request>> t = {
      rows::number<Request>("scale_mm", &Request::scale_mm, 0.1, 10, "mm", "Scale"),
      rows::number<Request>("count", &Request::count, 1, 100, "", "Count"),
      rows::choice<Request>("colour", &Request::colour, kColourNames, "Colour"),
      rows::path<Request>("file", &Request::file, "File"),
  };
  return t;
}

std::string error_of(const char* name, const tactile::OptionValue& value,
                     OptionSpelling spelling = OptionSpelling::cli) {
  Request r;
  try {
    tactile::set_option(r, *tactile::find_option(table(), name), value, spelling);
  } catch (const RequestError& e) {
    return e.what();
  }
  return {};
}

TEST(OptionTable, RangesReadAsAPersonWritesThem) {
  EXPECT_EQ(error_of("scale_mm", 0.05), "--scale-mm: 0.05 is out of range: must be from 0.1 to 10");
  EXPECT_EQ(error_of("scale_mm", 0.05, OptionSpelling::python),
            "scale_mm: 0.05 is out of range: must be from 0.1 to 10");
  EXPECT_EQ(error_of("count", std::int64_t{0}),
            "--count: 0 is out of range: must be from 1 to 100");
  EXPECT_EQ(error_of("count", 2.5), "--count: 2.5 is not a whole number");
  EXPECT_THAT(error_of("scale_mm", std::nan("")), HasSubstr("not a finite number"));
  EXPECT_EQ(error_of("scale_mm", std::string("big")), "--scale-mm: takes a number");
  EXPECT_EQ(error_of("scale_mm", 10.0), "");
}

TEST(OptionTable, ChoicesComeFromTheNameTable) {
  EXPECT_EQ(error_of("colour", std::string("blue")),
            "--colour: unknown value 'blue' (known: red, green)");
  Request r;
  tactile::set_option(r, *tactile::find_option(table(), "colour"), std::string("red"),
                      OptionSpelling::cli);
  EXPECT_EQ(r.colour, Colour::red);
}

TEST(OptionTable, PathsAreNeverEmptyAndUnsetOnlyWhereOptional) {
  EXPECT_EQ(error_of("file", std::string()), "--file: the path is empty");
  EXPECT_EQ(error_of("file", std::string("a\0b", 3)), "--file: the path holds a NUL character");
  EXPECT_EQ(error_of("scale_mm", std::monostate{}), "--scale-mm: cannot be unset (None)");
  Request r;
  r.count = 5;
  tactile::set_option(r, *tactile::find_option(table(), "count"), std::monostate{},
                      OptionSpelling::python);
  EXPECT_FALSE(r.count.has_value());
}

TEST(OptionTable, ARequestFilledByAProgramIsCheckedToo) {
  Request r;
  EXPECT_NO_THROW(tactile::check_options(r, table(), OptionSpelling::cli));
  r.scale_mm = 100;
  EXPECT_THROW(tactile::check_options(r, table(), OptionSpelling::cli), RequestError);
}

TEST(OptionTable, HelpShowsUnitRangeAndTheStructsDefault) {
  EXPECT_EQ(tactile::describe_option(table()[0]), "Scale [mm; from 0.1 to 10; default 1.5]");
  EXPECT_EQ(tactile::describe_option(table()[1]), "Count [from 1 to 100]");  // unset by default
  EXPECT_EQ(tactile::describe_option(table()[2]), "Colour [red | green; default green]");
  EXPECT_EQ(tactile::describe_option(table()[0], false), "Scale [mm; default 1.5]");
}

TEST(OptionTable, ClosestNameOnlyForTypos) {
  const std::vector<std::string> names = {"capture", "calibrate", "classify", "map"};
  EXPECT_EQ(tactile::closest_name("captur", names), "capture");
  EXPECT_EQ(tactile::closest_name("clasify", names), "classify");
  EXPECT_EQ(tactile::closest_name("zzzzzzzz", names), std::nullopt);
}

}  // namespace
