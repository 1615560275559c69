// The perception section of experiment files: good values parsed, every bad one refused by name
// before any work; a small run gives one Table 2 per mapping plus the sensor's.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::experiments {
namespace {

using namespace tactile::capture;
using namespace tactile::mapping;
using namespace tactile::perception;

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string with_perception(const std::string& perception,
                            const std::string& methods = R"(["proportional", "integrated"])",
                            const std::string& layouts = R"(["stress"])") {
  return R"({"name": "p", "seed": 1,
    "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
    "layouts": )" +
         layouts + R"(, "methods": )" + methods +
         R"(, "parameters": {"strain": ["per-frame", "accumulated"]},
    "perception": )" +
         perception + "}";
}

std::string refusal(const std::string& text) {
  try {
    parse_experiment(text, "p.json", ".");
  } catch (const FormatError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ExperimentPerception, ParsesTheSection) {
  auto ex = parse_experiment(with_perception("{}"), "p.json", ".");
  ASSERT_TRUE(ex.perception.has_value());
  EXPECT_EQ(ex.perception->trials, 20);
  EXPECT_EQ(ex.perception->degrees, (std::vector<int>{1, 2}));
  EXPECT_TRUE(ex.perception->footprints_mm.empty());
  EXPECT_TRUE(ex.perception->reference);
  ex = parse_experiment(
      with_perception(R"({"trials": 3, "degree": 2, "footprints_mm": [5, 10], "seed": 4,
                          "reference": false, "grid_spacing_mm": 0.5})"),
      "p.json", ".");
  EXPECT_EQ(ex.perception->trials, 3);
  EXPECT_EQ(ex.perception->degrees, (std::vector<int>{2}));
  EXPECT_EQ(ex.perception->footprints_mm, (std::vector<double>{5, 10}));
  EXPECT_EQ(ex.perception->seed, 4u);
  EXPECT_FALSE(ex.perception->reference);
  EXPECT_DOUBLE_EQ(ex.perception->grid_spacing_mm, 0.5);
  EXPECT_FALSE(parse_experiment(with_perception("{}").replace(
                                    with_perception("{}").find(",\n    \"perception\""), 22, ""),
                                "p.json", ".")
                   .perception.has_value());
}

TEST(ExperimentPerception, BadSectionsAreRefusedByName) {
  EXPECT_THAT(refusal(with_perception("[]")), HasSubstr("perception must be a JSON object"));
  EXPECT_THAT(refusal(with_perception(R"({"trails": 3})")),
              HasSubstr("perception: unknown field 'trails'"));
  EXPECT_THAT(refusal(with_perception(R"({"trials": 1})")),
              HasSubstr("perception.trials = 1 is not in 2..1000"));
  EXPECT_THAT(refusal(with_perception(R"({"trials": 2.5})")),
              HasSubstr("'perception.trials' must be an integer"));
  EXPECT_THAT(refusal(with_perception(R"({"degree": [1, 3]})")),
              HasSubstr("perception.degree 3 is not 1 or 2"));
  EXPECT_THAT(refusal(with_perception(R"({"degree": [2, 2]})")),
              HasSubstr("perception.degree 2 is given twice"));
  EXPECT_THAT(refusal(with_perception(R"({"degree": []})")),
              HasSubstr("'perception.degree' is an empty list"));
  EXPECT_THAT(refusal(with_perception(R"({"footprints_mm": [6]})")),
              HasSubstr("perception.footprints_mm: 6 is not a footprint of the paper's plates"));
  EXPECT_THAT(refusal(with_perception(R"({"footprints_mm": ["5"]})")),
              HasSubstr("'perception.footprints_mm' must be a number"));
  EXPECT_THAT(refusal(with_perception(R"({"footprints_mm": [5, 5]})")),
              HasSubstr("perception.footprints_mm: 5 is given twice"));
  EXPECT_THAT(refusal(with_perception(R"({"seed": -1})")),
              HasSubstr("perception.seed must not be negative"));
  EXPECT_THAT(refusal(with_perception(R"({"reference": 1})")),
              HasSubstr("'perception.reference' must be true or false"));
  EXPECT_THAT(refusal(with_perception(R"({"grid_spacing_mm": 0.1})")),
              HasSubstr("perception.grid_spacing_mm = 0.1 is not in [0.25, 3]"));
  EXPECT_THAT(refusal(with_perception("{}", R"(["profile"])")),
              HasSubstr("perception: needs a strain-driven method"));
  const tactile::test::TempDir dir;
  std::ofstream(dir / "narrow.json")
      << R"({"name": "narrow", "rows": 4, "cols": 4, "pitch_mm": [1, 1], "contactor_size_mm": [0.5, 0.5],
            "deflection_axis": "x", "deflection_range_um": [-50, 50], "max_rate_hz": 700})";
  EXPECT_THAT(refusal(with_perception("{}", R"(["proportional"])",
                                      "[\"" + (dir / "narrow.json").string() + "\"]")),
              HasSubstr("perception: layout 'narrow' has 4 columns, fewer than the 6"));
}

TEST(ExperimentPerception, SmallRunGivesOneTable2PerMappingAndTheSensors) {
  // One footprint (6 features), 2 trials, exponent 1: small enough for sanitizer builds.
  auto ex = parse_experiment(
      with_perception(R"({"trials": 2, "degree": 1, "footprints_mm": [5]})", R"(["proportional"])"),
      "p.json", ".");
  ex.write_movies = false;
  const tactile::test::TempDir out_tmp;
  const fs::path& out = out_tmp.path();
  const auto report = run_experiment(ex, out, 2);
  // One method x 2 strains, and the sensor first.
  ASSERT_EQ(report.perception.size(), 3u);
  EXPECT_EQ(report.perception[0].id, "sensor");
  EXPECT_EQ(report.perception[1].id, "00-stress-proportional-per-frame");
  EXPECT_EQ(report.perception[2].id, "01-stress-proportional-accumulated");
  for (const auto& t : report.perception) {
    ASSERT_EQ(t.rows.size(), 5u) << t.id;  // all, static, dp, ru, roll with exponent 1
    for (const auto& row : t.rows) {
      EXPECT_EQ(row.result.tested, 6) << t.id;  // one held-out trial per feature
      int confusion = 0;
      for (const auto& line : row.result.confusion)
        for (int v : line) confusion += v;
      EXPECT_EQ(confusion, 6) << t.id;
      EXPECT_GE(row.result.correct, 0);
      EXPECT_LE(row.result.correct, 6);
    }
    EXPECT_TRUE(fs::exists(out / "perception" / ("table2-" + t.id + ".csv"))) << t.id;
    EXPECT_TRUE(fs::exists(out / "perception" / ("accuracy_by_footprint-" + t.id + ".csv")))
        << t.id;
  }
  EXPECT_TRUE(fs::exists(out / "perception" / "summary.csv"));
  EXPECT_TRUE(fs::exists(out / "plots" / "perception.png"));
  EXPECT_TRUE(fs::exists(out / "plots" / "perception.svg"));
}

}  // namespace
}  // namespace tactile::experiments
