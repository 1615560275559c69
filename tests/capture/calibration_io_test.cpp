// Calibration files: an exact round trip, every malformed file refused with a named problem, and
// a failed write that leaves the file already there untouched.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "../common/small_disk.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/common/error.hpp"
#include "test_util.hpp"

namespace {

using tactile::FormatError;
using tactile::capture::Calibration;
using tactile::capture::read_calibration_json;
using tactile::capture::write_calibration_json;
using tactile::capture::testing::TempDir;
using tactile::test::SmallDisk;

Calibration example() {
  Calibration c;
  c.px_to_mm = {0.021, 0.0001, -3.2, -0.0002, 0.0213, -2.4, 1e-6, -2e-6, 1.0};
  c.mm_per_px = 0.0211;
  c.image_width_px = 320;
  c.image_height_px = 240;
  c.method = "dot-grid 0.5 mm";
  return c;
}

void expect_refused(const std::filesystem::path& dir, const std::string& text,
                    const std::string& fragment) {
  const auto path = dir / "calib.json";
  std::ofstream(path) << text;
  EXPECT_THAT([&] { read_calibration_json(path); },
              ::testing::ThrowsMessage<FormatError>(::testing::AllOf(
                  ::testing::HasSubstr("calib.json"), ::testing::HasSubstr(fragment))))
      << text;
}

// A valid file with one field replaced by `value` (JSON text).
std::string with(const std::string& field, const std::string& value) {
  std::map<std::string, std::string> fields = {{"format", "\"tactile-calibration\""},
                                               {"format_version", "1"},
                                               {"px_to_mm", "[0.02, 0, 0, 0, 0.02, 0, 0, 0, 1]"},
                                               {"mm_per_px", "0.02"},
                                               {"image_width_px", "320"},
                                               {"image_height_px", "240"}};
  if (value.empty())
    fields.erase(field);
  else
    fields[field] = value;
  std::ostringstream s;
  s << '{';
  const char* comma = "";
  for (const auto& [k, v] : fields) {
    s << comma << '"' << k << "\": " << v;
    comma = ", ";
  }
  s << '}';
  return s.str();
}

}  // namespace

TEST(CalibrationIo, RoundTripIsExact) {
  TempDir dir;
  const auto path = dir.path() / "calib.json";
  write_calibration_json(path, example());
  const Calibration back = read_calibration_json(path);
  EXPECT_EQ(back.px_to_mm, example().px_to_mm);
  EXPECT_EQ(back.mm_per_px, example().mm_per_px);
  EXPECT_EQ(back.image_width_px, 320);
  EXPECT_EQ(back.image_height_px, 240);
  EXPECT_EQ(back.method, "dot-grid 0.5 mm");
  std::ofstream(dir.path() / "valid.json") << with("format", "\"tactile-calibration\"");
  EXPECT_NO_THROW(read_calibration_json(dir.path() / "valid.json"));  // the helper's base is valid
}

TEST(CalibrationIo, MalformedFilesAreRefusedNamingTheProblem) {
  TempDir dir;
  EXPECT_THAT([&] { read_calibration_json(dir.path() / "missing.json"); },
              ::testing::ThrowsMessage<FormatError>(::testing::HasSubstr("cannot open")));
  expect_refused(dir.path(), "", "not valid JSON");
  expect_refused(dir.path(), "{\"format\": ", "not valid JSON");
  expect_refused(dir.path(), "[1, 2, 3]", "expected a JSON object");
  expect_refused(dir.path(), with("px_to_mm", "[1e999, 0, 0, 0, 1, 0, 0, 0, 1]"),
                 "not valid JSON");  // beyond a double
  expect_refused(dir.path(), with("format", "\"tactile-pore-model\""),
                 "'format' is not tactile-calibration");
  expect_refused(dir.path(), with("px_to_mm", "[1, 0, 0, 0, 1, 0, 0, 0]"), "must hold 9 numbers");
  expect_refused(dir.path(), with("px_to_mm", "[1, 2, 3, 2, 4, 6, 0, 0, 1]"), "singular");
  expect_refused(dir.path(), with("px_to_mm", "\"identity\""), "px_to_mm");
  expect_refused(dir.path(), with("mm_per_px", "5"), "implausible");
  expect_refused(dir.path(), with("mm_per_px", ""), "mm_per_px");
  expect_refused(dir.path(), with("image_width_px", "0"), "image_width_px");
  expect_refused(dir.path(), with("image_height_px", "\"tall\""), "image_height_px");
}

// Found by the second hostile-input run: a file of another format version, a size that is no
// whole number or beyond any camera, and a key written twice were read as if valid.
TEST(CalibrationIo, TamperedVersionsSizesAndRepeatedKeysAreRefused) {
  TempDir dir;
  expect_refused(dir.path(), with("format_version", "2"), "format_version 2 is not supported");
  expect_refused(dir.path(), with("format_version", "\"1\""), "format_version");
  expect_refused(dir.path(), with("format_version", ""), "format_version");
  expect_refused(dir.path(), with("image_width_px", "1e12"), "image_width_px");
  expect_refused(dir.path(), with("image_width_px", "640.5"), "image_width_px");
  expect_refused(dir.path(), with("image_height_px", "4294967536"), "image_height_px");
  // nlohmann keeps the last of two equal keys: the file would silently mean 32 mm per pixel.
  std::string twice = with("format", "\"tactile-calibration\"");
  twice.insert(twice.size() - 1, ", \"mm_per_px\": 0.5");
  expect_refused(dir.path(), twice, "'mm_per_px' appears twice");
  // The homography and the mean scale must agree: here 0.00002 mm vs 0.02 mm per pixel.
  expect_refused(
      dir.path(), with("px_to_mm", "[0.00002, 0, 0, 0, 0.00002, 0, 0, 0, 1]"),
      "'px_to_mm' gives 2e-05 mm per pixel at the image centre but 'mm_per_px' says 0.02");
  expect_refused(dir.path(), with("mm_per_px", "0.05"), "but 'mm_per_px' says 0.05");
}

TEST(CalibrationIo, AFailedWriteKeepsTheFileThatWasThere) {
  const SmallDisk disk;
  const auto path = disk / "calib.json";
  write_calibration_json(path, example());
  disk.fill();
  Calibration other = example();
  other.mm_per_px = 0.05;
  EXPECT_THROW(write_calibration_json(path, other), std::exception);
  EXPECT_EQ(read_calibration_json(path).mm_per_px, example().mm_per_px);
}
