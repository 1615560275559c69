#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "pores/pore_model.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/common/error.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// Coefficients that no short decimal form holds exactly, so a round trip checks every bit.
PoreModelFile sample_model() {
  PoreModelFile m;
  for (std::size_t i = 0; i < kPoreModelSize; ++i) {
    m.coefficients.push_back((static_cast<double>(i) - 70.0) / 3.0 +
                             1e-13 * static_cast<double>(i));
  }
  m.px_per_mm = 47.25;
  m.label_radius_mm = 0.064;
  m.l2 = 0.5;
  m.min_log_odds = -0.75;
  m.trained_on = {"image_01.jpg", "image_02.png"};
  return m;
}

nlohmann::json sample_json(const fs::path& dir) {
  write_pore_model_json(dir / "good.json", sample_model());
  return nlohmann::json::parse(std::ifstream(dir / "good.json"));
}

std::string read_error(const fs::path& path) {
  try {
    read_pore_model_json(path);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "";
}

// Writes `text` to DIR/bad.json and expects the reader to refuse it naming the file and `part`.
void expect_refused(const fs::path& dir, const std::string& text, const std::string& part) {
  const fs::path path = dir / "bad.json";
  std::ofstream(path) << text;
  const std::string message = read_error(path);
  ASSERT_FALSE(message.empty()) << "accepted: " << text.substr(0, 200);
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST(PoreModelIo, RoundTripIsExact) {
  TempDir dir;
  const PoreModelFile written = sample_model();
  write_pore_model_json(dir.path() / "model.json", written);
  EXPECT_FALSE(fs::exists(dir.path() / "model.json.partial"));
  const PoreModelFile read = read_pore_model_json(dir.path() / "model.json");
  EXPECT_EQ(read.coefficients, written.coefficients);
  EXPECT_EQ(read.px_per_mm, written.px_per_mm);
  EXPECT_EQ(read.label_radius_mm, written.label_radius_mm);
  EXPECT_EQ(read.l2, written.l2);
  EXPECT_EQ(read.min_log_odds, written.min_log_odds);
  EXPECT_EQ(read.trained_on, written.trained_on);
  const auto j = sample_json(dir.path());
  EXPECT_EQ(j.at("format"), "tactile-pore-model");
  EXPECT_EQ(j.at("format_version"), 1);
  EXPECT_EQ(j.at("measures"), kPoreMeasures);
  EXPECT_EQ(j.at("coefficient_count"), kPoreModelSize);
}

TEST(PoreModelIo, WriterRefusesWrongSizeAndNonFinite) {
  TempDir dir;
  PoreModelFile m = sample_model();
  m.coefficients.resize(10);
  try {
    write_pore_model_json(dir.path() / "m.json", m);
    ADD_FAILURE() << "a 10-coefficient model was written";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pore model has 10 coefficients"), std::string::npos);
  }
  m = sample_model();
  m.coefficients[5] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(write_pore_model_json(dir.path() / "m.json", m), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir.path() / "m.json"));
}

TEST(PoreModelIo, RefusesWhatIsNotAModel) {
  TempDir dir;
  EXPECT_NE(read_error(dir.path() / "missing.json").find("cannot open"), std::string::npos);
  expect_refused(dir.path(), "", "not valid JSON");
  expect_refused(dir.path(), "{\"format\": \"tactile-pore-model\",", "not valid JSON");
  expect_refused(dir.path(), "[1, 2, 3]", "expected a JSON object");
  auto j = sample_json(dir.path());
  j["format"] = "tactile-calibration";
  expect_refused(dir.path(), j.dump(), "'format' is not tactile-pore-model");
  j = sample_json(dir.path());
  j["format_version"] = 2;
  expect_refused(dir.path(), j.dump(), "format_version 2 is not supported");
  j = sample_json(dir.path());
  j["measures"] = 15;
  expect_refused(dir.path(), j.dump(), "15 measures");
}

TEST(PoreModelIo, RefusesBadCoefficients) {
  TempDir dir;
  auto j = sample_json(dir.path());
  j["coefficients"] = std::vector<double>(10, 0.5);
  j["coefficient_count"] = 10;
  expect_refused(dir.path(), j.dump(), "pore model has 10 coefficients, expected 153");
  j = sample_json(dir.path());
  j["coefficient_count"] = 152;
  expect_refused(dir.path(), j.dump(), "'coefficient_count' is 152 but 'coefficients' holds 153");
  j = sample_json(dir.path());
  j["coefficients"][7] = "0.5";
  expect_refused(dir.path(), j.dump(), "coefficient 7 is not a number");
  j = sample_json(dir.path());
  j["coefficients"][8] = nullptr;  // what a NaN becomes in JSON
  expect_refused(dir.path(), j.dump(), "coefficient 8 is not a number");
  j = sample_json(dir.path());
  j["coefficients"] = "all of them";
  expect_refused(dir.path(), j.dump(), "'coefficients' is not an array");
  // JSON has no infinity, but its text can overflow a double: refused as a FormatError too.
  j = sample_json(dir.path());
  j["coefficients"][0] = 12345.5;
  std::string text = j.dump();
  text.replace(text.find("12345.5"), 7, "1e999");
  expect_refused(dir.path(), text, "number overflow parsing '1e999'");
}

TEST(PoreModelIo, RefusesMissingFieldsAndBadValues) {
  TempDir dir;
  for (const char* field :
       {"format", "format_version", "measures", "coefficient_count", "coefficients", "px_per_mm",
        "label_radius_mm", "l2", "min_log_odds", "trained_on"}) {
    auto j = sample_json(dir.path());
    j.erase(field);
    SCOPED_TRACE(field);
    expect_refused(dir.path(), j.dump(), std::string("'") + field + "' is missing");
  }
  auto j = sample_json(dir.path());
  j["px_per_mm"] = 0;
  expect_refused(dir.path(), j.dump(), "'px_per_mm' must be positive");
  j = sample_json(dir.path());
  j["label_radius_mm"] = -0.1;
  expect_refused(dir.path(), j.dump(), "'label_radius_mm' must be positive");
  j = sample_json(dir.path());
  j["l2"] = -1;
  expect_refused(dir.path(), j.dump(), "'l2' must not be negative");
  j = sample_json(dir.path());
  j["min_log_odds"] = "low";
  expect_refused(dir.path(), j.dump(), "'min_log_odds' has the wrong type");
  j = sample_json(dir.path());
  j["trained_on"] = {1, 2};
  expect_refused(dir.path(), j.dump(), "'trained_on' has the wrong type");
}

}  // namespace
}  // namespace tactile::capture
