// Table 2 over several seeds: the spread lines and the CSV from hand-built rows.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../common/temp_dir.hpp"
#include "tactile/perception/seeds.hpp"

namespace perception = tactile::perception;
namespace fs = std::filesystem;

namespace {

perception::TimedCascade row(const std::string& inputs, int degree, int correct, int tested) {
  perception::TimedCascade t;
  t.result.inputs = inputs;
  t.result.degree = degree;
  t.result.correct = correct;
  t.result.tested = tested;
  t.result.r2 = {0.5, 0.25, 0.125};
  t.result.cascade_rms_mm = 1.5;
  return t;
}

// Three seeds of a two-row table: "all exp 1" scores 80, 83, 82; "dp exp 2" 70 every time.
std::vector<perception::SeedTable2> three_seeds() {
  std::vector<perception::SeedTable2> runs;
  const int all[3] = {80, 83, 82};
  for (int k = 0; k < 3; ++k)
    runs.push_back(
        {static_cast<std::uint64_t>(5 + k), {row("all", 1, all[k], 96), row("dp", 2, 70, 96)}});
  return runs;
}

}  // namespace

TEST(SeedSpread, LowestHighestAndMeanOfEachRow) {
  const auto lines = perception::seed_spread_lines(three_seeds());
  ASSERT_EQ(lines.size(), 2u);
  // (80 + 83 + 82) / 3 = 81.67
  EXPECT_EQ(lines[0], "all exp 1: 80-83 of 96 correct over 3 seeds (mean 81.7)");
  EXPECT_EQ(lines[1], "dp exp 2: 70 of 96 correct over 3 seeds (mean 70.0)");
}

TEST(SeedSpread, OneSeedAndNone) {
  auto runs = three_seeds();
  runs.resize(1);
  EXPECT_EQ(perception::seed_spread_lines(runs)[0],
            "all exp 1: 80 of 96 correct over 1 seed (mean 80.0)");
  EXPECT_TRUE(perception::seed_spread_lines({}).empty());
}

TEST(SeedSpread, RefusesTablesWithOtherRows) {
  auto runs = three_seeds();
  runs[2].rows[1].result.degree = 1;  // another kernel in the same place
  try {
    perception::seed_spread_lines(runs);
    FAIL() << "accepted a table with another row";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("seed 7 has other rows"), std::string::npos) << e.what();
  }
  runs = three_seeds();
  runs[1].rows[0].result.tested = 48;  // another split
  EXPECT_THROW(perception::seed_spread_lines(runs), std::invalid_argument);
  runs = three_seeds();
  runs[1].rows.pop_back();
  EXPECT_THROW(perception::seed_spread_lines(runs), std::invalid_argument);
  runs = three_seeds();
  runs[0].rows.clear();  // an empty first table is no reason to accept the others
  EXPECT_THROW(perception::seed_spread_lines(runs), std::invalid_argument);
}

TEST(SeedSpread, CsvHasEveryRowOfEverySeed) {
  const tactile::test::TempDir dir;
  const fs::path path = dir / "seeds.csv";
  perception::write_table2_seeds_csv(path, three_seeds());
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 1u + 3 * 2);
  EXPECT_EQ(lines[0],
            "seed,inputs,degree,correct,tested,accuracy,r2_planar,r2_conical,r2_spherical,"
            "cascade_rms_mm");
  // 83 / 96 = 0.86458...
  EXPECT_EQ(lines[3], "6,all,1,83,96,0.8646,0.5000,0.2500,0.1250,1.5000");
  EXPECT_EQ(lines[6], "7,dp,2,70,96,0.7292,0.5000,0.2500,0.1250,1.5000");
}

TEST(SeedSpread, CsvToAMissingFolderFailsNamingThePath) {
  const tactile::test::TempDir dir;
  const fs::path path = dir / "tactile_no_such_dir" / "t.csv";
  try {
    perception::write_table2_seeds_csv(path, three_seeds());
    FAIL() << "wrote into a missing folder";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("tactile_no_such_dir"), std::string::npos) << e.what();
  }
}
