// `tactile experiment` with a perception section, as a user meets it: Table 2 from the movies of
// each mapping, with the columns of `tactile perceive`'s table2.csv, and a summary with one row
// per mapping (and the simulated sensor) per exponent; a bad section fails before any work.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/temp_dir.hpp"
#include "csv_rows.hpp"
#include "run.hpp"

namespace fs = std::filesystem;
using tactile::test::read_csv_rows;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

std::string experiment(const std::string& perception) {
  return R"({"name": "movies", "seed": 1,
  "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
  "layouts": ["stress"], "methods": ["proportional", "integrated"],
  "parameters": {"strain": "accumulated", "gain_um_per_strain": 250}, "write_movies": false,
  "perception": )" +
         perception + "}";
}

}  // namespace

TEST(ExperimentPerceptionCli, BadPerceptionSectionFailsBeforeAnyOutput) {
  const tactile::test::TempDir d_tmp("bad");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "bad.json") << experiment(R"({"trials": 3, "kernel": 2})");
  const auto r =
      run_tactile("experiment " + (d / "bad.json").string() + " --out " + (d / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("bad.json: perception: unknown field 'kernel'"));
  EXPECT_FALSE(fs::exists(d / "out"));
}

TEST(ExperimentPerceptionCli, Table2FromMoviesPerMappingBesideTheSensors) {
  const tactile::test::TempDir d_tmp("run");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "movies.json")
      << experiment(R"({"trials": 2, "degree": [1, 2], "footprints_mm": [5]})");
  const auto r = run_tactile("experiment " + (d / "movies.json").string() + " --out " +
                             (d / "out").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("perception (Table 2 from movies"));
  const std::vector<std::string> tables = {"sensor", "00-stress-proportional-accumulated",
                                           "01-stress-integrated-accumulated"};
  // The columns of `tactile perceive`'s table2.csv (docs/formats.md, "Perception results").
  std::string expected_header = "inputs,degree,correct,tested,accuracy";
  for (int t = 0; t < 3; ++t)
    for (int p = 0; p < 3; ++p)
      expected_header += ",true_" + std::to_string(t) + "_as_" + std::to_string(p);
  expected_header +=
      ",r2_planar,r2_conical,r2_spherical,rms_planar_mm,rms_conical_mm,rms_spherical_mm,"
      "cascade_rms_mm,train_test_s";
  for (const auto& id : tables) {
    const auto rows = read_csv_rows(d / "out" / "perception" / ("table2-" + id + ".csv"), false);
    ASSERT_EQ(rows.size(), 11u) << id;  // header + 5 input sets x 2 exponents
    std::string header;
    for (const auto& f : rows[0]) header += (header.empty() ? "" : ",") + f;
    EXPECT_EQ(header, expected_header) << id;
    for (std::size_t i = 1; i < rows.size(); ++i) {
      ASSERT_EQ(rows[i].size(), rows[0].size()) << id;
      const double accuracy = std::stod(rows[i][4]);
      EXPECT_GE(accuracy, 0.0) << id;
      EXPECT_LE(accuracy, 1.0) << id;
      EXPECT_EQ(rows[i][3], "6") << id;  // one held-out trial of each of the 6 features
      EXPECT_NEAR(accuracy, std::stod(rows[i][2]) / 6, 1e-4) << id;
    }
  }
  // Summary: one row per mapping (the sensor first) and exponent.
  const auto summary = read_csv_rows(d / "out" / "perception" / "summary.csv", true);
  ASSERT_EQ(summary.size(), 1u + 3 * 2);
  EXPECT_EQ(summary[0][0], "mapping");
  EXPECT_EQ(summary[1][0], "sensor");
  EXPECT_EQ(summary[3][0], tables[1]);
  EXPECT_EQ(summary[3][2], "proportional");
  EXPECT_EQ(summary[5][2], "integrated");
  EXPECT_EQ(summary[5][7], "1");
  EXPECT_EQ(summary[6][7], "2");
  for (std::size_t i = 1; i < summary.size(); ++i) {
    const double accuracy_all = std::stod(summary[i][8]);
    EXPECT_GE(accuracy_all, 0.0);
    EXPECT_LE(accuracy_all, 1.0);
  }
  EXPECT_TRUE(fs::exists(d / "out" / "plots" / "perception.png"));
}
