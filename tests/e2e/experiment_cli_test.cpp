// `tactile experiment`, `tactile map --layout FILE.json` and `tactile bench map` as a user meets
// them: wrong usage exits 2, bad files exit 1 naming the problem before any work, good runs write
// what they promise.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/movie/movie_io.hpp"

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

const char* kTiny = R"({"name": "tiny", "seed": 1,
  "sources": [{"name": "gt", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
  "layouts": ["stress"], "methods": ["integrated", "profile"], "parameters": {"rate_hz": 100}})";

}  // namespace

TEST(ExperimentCli, MissingFileArgumentIsUsageError) {
  const auto r = run_tactile("experiment");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("EXP_JSON"));
}

TEST(ExperimentCli, BadFilesFailBeforeAnyOutputIsWritten) {
  const tactile::test::TempDir d_tmp("bad");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "broken.json") << "{\"name\": ";
  auto r =
      run_tactile("experiment " + (d / "broken.json").string() + " --out " + (d / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("broken.json: not valid JSON"));
  EXPECT_FALSE(fs::exists(d / "out"));
  std::string fast = kTiny;
  fast.replace(fast.find("\"rate_hz\": 100"), 14, "\"rate_hz\": 900");
  std::ofstream(d / "fast.json") << fast;
  r = run_tactile("experiment " + (d / "fast.json").string() + " --out " + (d / "out").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("rate 900 Hz is above layout 'stress' maximum rate 700 Hz"));
  EXPECT_FALSE(fs::exists(d / "out"));
}

TEST(ExperimentCli, TinyExperimentWritesItsFolder) {
  const tactile::test::TempDir d_tmp("tiny");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "tiny.json") << kTiny;
  const auto r = run_tactile("experiment " + (d / "tiny.json").string() + " --out " +
                             (d / "out").string() + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2 runs"));
  for (const char* f :
       {"experiment.json", "resolved.json", "metrics.csv", "plots/correlation.png",
        "plots/activity-gt-stress.png", "movies/000-gt-stress-integrated-per-frame.h5",
        "movies/001-gt-stress-profile-per-frame.h5"}) {
    EXPECT_TRUE(fs::exists(d / "out" / f)) << f;
  }
}

TEST(ExperimentCli, MapTakesACustomLayoutFileAndRefusesABadOne) {
  const fs::path strain = fs::path(TACTILE_E2E_DEMO_DIR) / "strain.h5";
  ASSERT_TRUE(fs::exists(strain));
  const tactile::test::TempDir d_tmp("layout");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "bad.json") << R"({"name": "x", "rows": 4})";
  auto r = run_tactile("map " + strain.string() + " --out " + (d / "m.h5").string() + " --layout " +
                       (d / "bad.json").string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("bad.json: missing field 'cols'"));
  std::ofstream(d / "lab.json") << R"({"name": "lab", "rows": 5, "cols": 7, "pitch_mm": [1, 1.2],
    "contactor_size_mm": [0.5, 0.5], "deflection_axis": "y", "deflection_range_um": [-40, 40],
    "max_rate_hz": 500})";
  r = run_tactile("map " + strain.string() + " --out " + (d / "m.h5").string() + " --layout " +
                  (d / "lab.json").string() + " --rate-hz 500 --strain accumulated");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto movie = tactile::movie::read_tactile_movie(d / "m.h5");
  EXPECT_EQ(movie.layout.name, "lab");
  EXPECT_EQ(movie.layout.cols, 7);
  EXPECT_EQ(movie.layout.axis, tactile::movie::DeflectionAxis::y);
  EXPECT_THAT(movie.provenance.parameters_json, HasSubstr("\"strain\":\"accumulated\""));
}

TEST(ExperimentCli, BenchMapPrintsItsFigures) {
  const auto r = run_tactile("bench map --frames 20 --repeats 1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("median ms"));
  EXPECT_THAT(r.output, HasSubstr("integrated"));
}

TEST(ExperimentCli, CellsRefuseBadChoicesDamagedManifestsAndBadSlurmNumbers) {
  const tactile::test::TempDir d_tmp("cells");
  const std::filesystem::path& d = d_tmp.path();
  std::ofstream(d / "tiny.json") << kTiny;
  const std::string exp =
      "experiment " + (d / "tiny.json").string() + " --out " + (d / "out").string();
  auto r = run_tactile(exp + " --cell 0");
  EXPECT_EQ(r.exit_code, 1);  // nothing planned yet
  EXPECT_THAT(r.output, HasSubstr("manifest.tsv: no manifest (plan the cells first"));
  r = run_tactile(exp + " --plan");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2 cells planned"));
  r = run_tactile(exp + " --cell 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--cell 2: out of range: the manifest has 2 cells, 0 to 1"));
  r = run_tactile(exp + " --cell run-123");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("--cell run-123: no cell has this id"));
  r = run_tactile(exp + " --merge");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("2 of 2 cells are not done; nothing merged"));
  r = run_tactile(exp + " --cell 1 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tactile(exp + " --merge --status");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.output, HasSubstr("2 cells: 1 done, 0 running, 0 failed, 1 missing"));
  for (const char* bad :
       {"--max-parallel -1", "--cells-per-task 0", "--time 1:2:3:4", "--cells-per-task x"}) {
    r = run_tactile(exp + " --slurm " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_THAT(r.output, HasSubstr(std::string(bad).substr(0, std::string(bad).find(' ')))) << bad;
  }
  r = run_tactile(exp + " --cells-per-task 2");  // a Slurm option without --slurm
  EXPECT_EQ(r.exit_code, 2);
  // A manifest cut short is damaged work: exit 1 naming the file and line.
  std::filesystem::resize_file(d / "out" / "manifest.tsv",
                               std::filesystem::file_size(d / "out" / "manifest.tsv") - 10);
  r = run_tactile(exp + " --cell 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("manifest.tsv line 5: damaged"));
  r = run_tactile(exp + " --slurm");
  EXPECT_EQ(r.exit_code, 1);
}

TEST(ExperimentCli, CellsPlannedUnderOneNameOfTheFilesRunUnderAnother) {
  const tactile::test::TempDir d_tmp("names");
  const std::filesystem::path& d = d_tmp.path();
  fs::create_directories(d / "sub");
  fs::copy_file(tactile::test::demo_dir() / "strain.h5", d / "strain.h5");
  std::ofstream(d / "exp.json") << R"({"name": "rec", "seed": 1,
    "sources": [{"name": "rec", "file": "strain.h5"}], "layouts": ["stress"],
    "methods": ["proportional", "integrated"]})";
  const std::string out = " --out " + (d / "out").string();
  // Planned through a detour, run and merged as a cluster's task names the files: absolutely.
  auto r = run_tactile("experiment " + (d / "sub" / ".." / "exp.json").string() + out + " --plan");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tactile("experiment " + (d / "exp.json").string() + out + " --cell 0 --cell 1 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_tactile("experiment " + (d / "exp.json").string() + out + " --merge");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("2 cells merged"));
}
