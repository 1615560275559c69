// `tactile perceive` on real recordings and on malformed input: clear errors, right exit codes.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "../common/temp_dir.hpp"
#include "csv_rows.hpp"
#include "run.hpp"

using tactile::test::read_csv_rows;
using tactile::test::run_tactile;

namespace {

int line_count(const std::filesystem::path& path) {
  std::ifstream in(path);
  int lines = 0;
  for (std::string line; std::getline(in, line);) ++lines;
  return lines;
}

// Field number `index` (from 0) of every data line of a CSV.
std::vector<std::string> column(const std::filesystem::path& path, std::size_t index) {
  const auto rows = read_csv_rows(path);
  std::vector<std::string> values;
  for (std::size_t i = 1; i < rows.size(); ++i) values.push_back(rows[i].at(index));
  return values;
}

}  // namespace

// The simulated evaluation end to end, small (2 trials per feature: one trains, one is held
// out): every file it promises, with one row per Table 2 row, held-out trial and footprint.
TEST(PerceiveCli, WritesTable2Figure7AndAccuracyPerFootprint) {
  const tactile::test::TempDir out_tmp("simulated");
  const std::filesystem::path& out = out_tmp.path();
  const auto r = run_tactile("perceive --out " + out.string() + " --trials 2 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Table 2 (48 training / 48 held-out samples)"), std::string::npos)
      << r.output;
  // Where the all-inputs classifier errs, for both kernels, out of the 48 held-out trials.
  for (const char* kernel : {"all exp 1: curvature wrong on ", "all exp 2: curvature wrong on "})
    EXPECT_NE(r.output.find(kernel), std::string::npos) << r.output;
  EXPECT_EQ(line_count(out / "table2.csv"), 1 + 5 * 2);     // 5 input sets x 2 kernels
  EXPECT_EQ(line_count(out / "figure7.csv"), 1 + 10 * 48);  // every held-out trial
  EXPECT_EQ(line_count(out / "accuracy_by_footprint.csv"), 1 + 10 * 16);  // 16 footprints
  for (const char* chart :
       {"figure7_all_exp1.svg", "figure7_roll_exp2.svg", "accuracy_by_footprint_exp1.svg",
        "accuracy_by_footprint_exp2.svg", "figure7_all_exp1.png", "accuracy_by_footprint_exp2.png"})
    EXPECT_TRUE(std::filesystem::is_regular_file(out / chart)) << chart;
}

// A subset of footprints and other trial-to-trial spreads (the sensitivity study of
// docs/perception-models.md): only the chosen features are simulated.
TEST(PerceiveCli, FootprintSubsetAndVariationScales) {
  const tactile::test::TempDir out_tmp("subset");
  const std::filesystem::path& out = out_tmp.path();
  const auto r = run_tactile("perceive --out " + out.string() +
                             " --trials 2 --footprints 1.25,20 --position-variation 0.3 "
                             "--depth-variation 0 --speed-variation 2 --export-recordings");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("12 features x 2 trials"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Table 2 (12 training / 12 held-out samples)"), std::string::npos)
      << r.output;
  EXPECT_EQ(line_count(out / "accuracy_by_footprint.csv"), 1 + 10 * 4);  // -20 -1.25 1.25 20
  // Trial 0 of each of the 12 features and 4 procedures, in the real recordings' format: the
  // recordings analysis reads every one back.
  const auto back = run_tactile("perceive --out " + (out / "back").string() + " --recordings " +
                                (out / "recordings").string());
  EXPECT_EQ(back.exit_code, 0) << back.output;
  EXPECT_NE(back.output.find("48 of 48 recordings analysed"), std::string::npos) << back.output;
}

// The sheet electrode field (slower: it weighs the skin out to 3.5 mm), on the smallest features.
TEST(PerceiveCli, SheetElectrodeField) {
  const tactile::test::TempDir out_tmp("sheet");
  const std::filesystem::path& out = out_tmp.path();
  const auto r = run_tactile("perceive --out " + out.string() +
                             " --trials 2 --footprints 1.25 --electrode-field sheet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("6 features x 2 trials"), std::string::npos) << r.output;
  EXPECT_EQ(line_count(out / "table2.csv"), 1 + 5 * 2);
}

// --seeds: every seed's Table 2 is the one a run of that seed alone gives, the first seed's is
// also table2.csv, and the spread is printed for every row.
TEST(PerceiveCli, SeedsRepeatTable2OnEachSeed) {
  const tactile::test::TempDir out_tmp("seeds");
  const std::filesystem::path& out = out_tmp.path();
  const std::string common = " --trials 2 --footprints 1.25,20 --threads 2";
  const auto r = run_tactile("perceive --out " + out.string() + common + " --seed 4 --seeds 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Table 2 over 2 seeds (4-5)"), std::string::npos) << r.output;
  // One spread line per Table 2 row ("all exp 1: " alone would also match the misclassified
  // line that every run prints).
  std::vector<std::string> spread;
  std::istringstream lines(r.output);
  for (std::string line; std::getline(lines, line);)
    if (line.find(" of 12 correct over 2 seeds (mean ") != std::string::npos)
      spread.push_back(line.substr(0, line.find(':')));
  EXPECT_EQ(spread,
            (std::vector<std::string>{"  all exp 1", "  all exp 2", "  static exp 1",
                                      "  static exp 2", "  dp exp 1", "  dp exp 2", "  ru exp 1",
                                      "  ru exp 2", "  roll exp 1", "  roll exp 2"}))
      << r.output;
  const auto seeds_csv = out / "table2_seeds.csv";
  ASSERT_EQ(line_count(seeds_csv), 1 + 2 * 10);
  const auto seeds = column(seeds_csv, 0);
  const auto correct = column(seeds_csv, 3);
  EXPECT_EQ(std::vector<std::string>(seeds.begin(), seeds.begin() + 10),
            std::vector<std::string>(10, "4"));
  EXPECT_EQ(std::vector<std::string>(seeds.begin() + 10, seeds.end()),
            std::vector<std::string>(10, "5"));
  // table2.csv: inputs,degree,correct,...; the same rows in the same order.
  EXPECT_EQ(std::vector<std::string>(correct.begin(), correct.begin() + 10),
            column(out / "table2.csv", 2));
  const tactile::test::TempDir alone_tmp("seed5");
  const std::filesystem::path& alone = alone_tmp.path();
  ASSERT_EQ(run_tactile("perceive --out " + alone.string() + common + " --seed 5").exit_code, 0);
  EXPECT_EQ(std::vector<std::string>(correct.begin() + 10, correct.end()),
            column(alone / "table2.csv", 2));
}

TEST(PerceiveCli, AnalysesEveryRealRecording) {
  const tactile::test::TempDir out_tmp("real");
  const std::filesystem::path& out = out_tmp.path();
  const auto r = run_tactile("perceive --out " + out.string() + " --recordings " +
                             TACTILE_TEST_DATA_DIR + "/biotac-slide");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("9 of 9 recordings analysed"), std::string::npos) << r.output;
  EXPECT_EQ(line_count(out / "recordings.csv"), 10);  // header + 9 recordings
}

TEST(PerceiveCli, MalformedRecordingFailsNamingFileAndProblem) {
  const tactile::test::TempDir in_tmp("bad_in");
  const std::filesystem::path& in = in_tmp.path();
  std::ofstream(in / "broken_bio.csv") << "timestamp,pdc\n1,2\n";
  const tactile::test::TempDir out_tmp("bad_out");
  const std::filesystem::path& out = out_tmp.path();
  const auto r = run_tactile("perceive --out " + out.string() + " --recordings " + in.string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("broken_bio.csv: line 1: header has 2 columns"), std::string::npos)
      << r.output;
}

TEST(PerceiveCli, UsageErrors) {
  EXPECT_EQ(run_tactile("perceive --out /tmp/x --trials 1").exit_code, 2);
  EXPECT_EQ(run_tactile("perceive --trials 5").exit_code, 2);  // --out missing
  const auto t = run_tactile("perceive --out /tmp/x --threads -1");
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_NE(t.output.find("--threads"), std::string::npos) << t.output;
  EXPECT_EQ(run_tactile("perceive --out /tmp/x --threads many").exit_code, 2);
  const auto g = run_tactile("perceive --out /tmp/x --electrode-field wide");
  EXPECT_EQ(g.exit_code, 2);
  EXPECT_NE(g.output.find("--electrode-field: wide not in"), std::string::npos) << g.output;
  const auto f = run_tactile("perceive --out /tmp/x --footprints 1.25,3");
  EXPECT_EQ(f.exit_code, 2);
  EXPECT_NE(f.output.find("--footprints: 3 not in"), std::string::npos) << f.output;
  for (const char* v :
       {"--position-variation -1", "--depth-variation x", "--speed-variation 1e9"}) {
    const auto e = run_tactile(std::string("perceive --out /tmp/x ") + v);
    EXPECT_EQ(e.exit_code, 2) << v;
    EXPECT_NE(e.output.find(std::string(v).substr(0, std::string(v).find(' '))), std::string::npos)
        << e.output;
  }
  for (const char* v : {"--seeds 0", "--seeds few", "--seeds 1001"}) {
    const auto e = run_tactile(std::string("perceive --out /tmp/x ") + v);
    EXPECT_EQ(e.exit_code, 2) << v;
    EXPECT_NE(e.output.find("--seeds"), std::string::npos) << e.output;
  }
  // Real recordings are analysed once; seeds are for the simulated data set.
  const auto both = run_tactile("perceive --out /tmp/x --seeds 2 --recordings " +
                                std::string(TACTILE_TEST_DATA_DIR) + "/biotac-slide");
  EXPECT_EQ(both.exit_code, 2);
  EXPECT_NE(both.output.find("excludes"), std::string::npos) << both.output;
  const auto r = run_tactile("perceive --out /tmp/x --recordings /nonexistent/dir");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("/nonexistent/dir"), std::string::npos) << r.output;
  const tactile::test::TempDir empty_tmp("empty");
  const std::filesystem::path& empty = empty_tmp.path();
  const auto e = run_tactile("perceive --out /tmp/x --recordings " + empty.string());
  EXPECT_EQ(e.exit_code, 1);
  EXPECT_NE(e.output.find("no *_bio.csv recordings"), std::string::npos) << e.output;
}
