// Custom layouts from JSON: a valid file round-trips; every malformed one is refused by name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/movie/layout_json.hpp"

namespace tactile::movie {
namespace {

using ::testing::HasSubstr;

const char* kValid = R"({
  "name": "lab-6x5", "rows": 6, "cols": 5,
  "pitch_mm": [1.0, 1.25], "contactor_size_mm": [0.5, 0.8],
  "deflection_axis": "y", "deflection_range_um": [-80, 60], "max_rate_hz": 900
})";

TEST(LayoutJson, ReadsEveryField) {
  const Layout l = parse_layout_json(kValid, "test");
  EXPECT_EQ(l.name, "lab-6x5");
  EXPECT_EQ(l.rows, 6);
  EXPECT_EQ(l.cols, 5);
  EXPECT_DOUBLE_EQ(l.pitch_x_mm, 1.0);
  EXPECT_DOUBLE_EQ(l.pitch_y_mm, 1.25);
  EXPECT_DOUBLE_EQ(l.contactor_width_mm, 0.5);
  EXPECT_DOUBLE_EQ(l.contactor_height_mm, 0.8);
  EXPECT_EQ(l.axis, DeflectionAxis::y);
  EXPECT_DOUBLE_EQ(l.deflection_min_um, -80);
  EXPECT_DOUBLE_EQ(l.deflection_max_um, 60);
  EXPECT_DOUBLE_EQ(l.max_rate_hz, 900);
}

TEST(LayoutJson, BuiltInLayoutsRoundTrip) {
  for (const auto& name : {"stress", "stress2", "latero"}) {
    const Layout a = layout_by_name(name);
    const Layout b = parse_layout_json(layout_to_json(a), name);
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.rows, a.rows);
    EXPECT_EQ(b.cols, a.cols);
    EXPECT_DOUBLE_EQ(b.pitch_x_mm, a.pitch_x_mm);
    EXPECT_DOUBLE_EQ(b.pitch_y_mm, a.pitch_y_mm);
    EXPECT_DOUBLE_EQ(b.contactor_width_mm, a.contactor_width_mm);
    EXPECT_DOUBLE_EQ(b.contactor_height_mm, a.contactor_height_mm);
    EXPECT_EQ(b.axis, a.axis);
    EXPECT_DOUBLE_EQ(b.deflection_min_um, a.deflection_min_um);
    EXPECT_DOUBLE_EQ(b.deflection_max_um, a.deflection_max_um);
    EXPECT_DOUBLE_EQ(b.max_rate_hz, a.max_rate_hz);
  }
}

TEST(LayoutJson, ResolvesNamesAndFiles) {
  EXPECT_EQ(resolve_layout("latero").rows, 8);
  const tactile::test::TempDir dir;
  const auto path = dir / "layout.json";
  std::ofstream(path) << kValid;
  EXPECT_EQ(resolve_layout(path.string()).name, "lab-6x5");
  EXPECT_THROW(resolve_layout("no-such-layout"), std::invalid_argument);
  try {
    resolve_layout("/nonexistent/dir/layout.json");
    FAIL() << "a missing file was accepted";
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot open"));
  }
}

// Replaces the first occurrence of `from` in the valid text by `to`.
std::string edit(const std::string& from, const std::string& to) {
  std::string text = kValid;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

void refused(const std::string& text, const std::string& message) {
  try {
    parse_layout_json(text, "bad.json");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json")) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(message)) << e.what();
  }
}

// Every number of a layout, every hostile value (JSON has no NaN: huge and tiny instead).
TEST(LayoutJson, RefusesHostileNumbersInEveryField) {
  for (const char* field : {"\"pitch_mm\": [", "\"contactor_size_mm\": [",
                            "\"deflection_range_um\": [", "\"max_rate_hz\": "}) {
    for (const char* v : {"1e308", "-1e308", "1e-300", "-1e-300"}) {
      const std::string text = kValid;
      const auto at = text.find(field);
      ASSERT_NE(at, std::string::npos) << field;
      std::string bad = text;
      const auto start = at + std::string(field).size();
      const auto end = bad.find_first_of(",]}\n", start);
      bad.replace(start, end - start, v);
      // A tiny lower deflection limit is a fine range ([-1e-300, 400] holds 0).
      if (std::string(field).find("deflection") != std::string::npos && std::string(v) != "1e308" &&
          std::string(v) != "-1e308") {
        continue;
      }
      refused(bad, "out of range");
    }
  }
}

TEST(LayoutJson, RefusesMalformedFilesByName) {
  refused("", "not valid JSON");
  refused("{\"name\": ", "not valid JSON");
  refused("[1, 2]", "must be a JSON object");
  refused(edit("\"max_rate_hz\": 900", "\"max_rate\": 900"), "unknown field 'max_rate'");
  refused(edit(", \"max_rate_hz\": 900", ""), "missing field 'max_rate_hz'");
  refused(edit("\"name\": \"lab-6x5\"", "\"name\": \"\""), "'name' must be a non-empty string");
  refused(edit("\"rows\": 6", "\"rows\": 0"), "'rows' = 0");
  refused(edit("\"cols\": 5", "\"cols\": -3"), "'cols' = -3");
  refused(edit("\"rows\": 6", "\"rows\": 6.5"), "'rows' must be an integer");
  refused(edit("[1.0, 1.25]", "[0, 1.25]"),
          "pitch_mm[0] (x) 0 is out of range: must be from 0.001 to 1000");
  refused(edit("[1.0, 1.25]", "[1.0, -1]"),
          "pitch_mm[1] (y) -1 is out of range: must be from 0.001 to 1000");
  refused(edit("[1.0, 1.25]", "[1.0]"), "'pitch_mm' must be an array of two numbers");
  refused(edit("[1.0, 1.25]", "\"1mm\""), "'pitch_mm' must be an array of two numbers");
  refused(edit("[0.5, 0.8]", "[0.5, \"wide\"]"), "must be a number");
  refused(edit("[0.5, 0.8]", "[500, 800]"), "contactors would overlap");
  refused(edit("\"y\"", "\"z\""), "'deflection_axis' must be \"x\" or \"y\"");
  refused(edit("[-80, 60]", "[10, 60]"), "does not contain 0");
  refused(edit("[-80, 60]", "[60, -80]"), "is empty");
  refused(edit("[-80, 60]", "[-80, -80]"), "is empty");
  refused(edit("\"max_rate_hz\": 900", "\"max_rate_hz\": 0"),
          "max_rate_hz 0 is out of range: must be from 1 to 100000");
  refused(edit("\"max_rate_hz\": 900", "\"max_rate_hz\": null"), "'max_rate_hz' must be a number");
  // Found by the second hostile-input run: an experiment wrote the movie of a layout named
  // "../../evil" outside its folder; and "rows" given twice meant the second.
  refused(edit("\"name\": \"lab-6x5\"", "\"name\": \"../../evil\""),
          "name \"../../evil\" is not a plain name: it holds '/'");
  // Folders of their own and names longer than a file name can hold with the run's other parts.
  refused(edit("\"name\": \"lab-6x5\"", "\"name\": \"..\""), "name \"..\" is not a plain name");
  refused(edit("\"name\": \"lab-6x5\"", "\"name\": \"" + std::string(101, 'l') + "\""),
          "is not a plain name: it is 101 bytes long");
  refused(edit("\"name\": \"lab-6x5\"", "\"name\": \"lab\\u0000x\""),
          "is not a plain name: it holds a control character");
  refused(edit("\"rows\": 6", "\"rows\": 6, \"rows\": 200"), "field 'rows' appears twice");
}

}  // namespace
}  // namespace tactile::movie
