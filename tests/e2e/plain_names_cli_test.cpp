// Names read from a file that become part of a path (the experiment's default output folder,
// movie and plot files, the manifest), and text written into the Slurm scripts: a hostile or
// careless experiment file or command line never writes outside the output folder, never fails
// halfway on a name the file system refuses, and never has the shell run a word of it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "run.hpp"

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

// One word for /bin/sh, whatever it holds (run_tactile passes its text to the shell).
std::string sh(const std::string& word) {
  std::string q = "'";
  for (const char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// A small experiment whose source and layout are given by the caller.
std::string experiment(const std::string& name, const std::string& source,
                       const std::string& layout = "\"stress\"") {
  return R"({"name": ")" + name + R"(", "seed": 1, "sources": [{"name": ")" + source +
         R"(", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
  "layouts": [)" +
         layout + R"(], "methods": ["integrated"], "parameters": {"rate_hz": 100}})";
}

// Everything under `dir`, as paths relative to it: what a run left behind.
std::string listing(const fs::path& dir) {
  std::string all;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    all += e.path().lexically_relative(dir).string() + "\n";
  return all;
}

}  // namespace

// Without --out the folder is named after the experiment: a name that is a path put it anywhere.
TEST(PlainNamesCli, ExperimentNameThatIsAPathIsRefusedBeforeAnyFolderIsMade) {
  const tactile::test::TempDir d_tmp("expname");
  const fs::path& d = d_tmp.path();
  fs::create_directories(d / "work");
  const fs::path elsewhere = d / "elsewhere";
  std::ofstream(d / "work" / "exp.json") << experiment(elsewhere.string(), "gt");
  auto r = run_tactile("experiment " + sh((d / "work" / "exp.json").string()) + " --plan");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("exp.json: name \"" + elsewhere.string() +
                                  "\" is not a plain name: it holds '/'"));
  EXPECT_FALSE(fs::exists(elsewhere.string() + "-results")) << listing(d);
}

// A source name that is a folder of its own, or a path, is refused naming the field, and nothing
// appears inside or outside --out.
TEST(PlainNamesCli, SourceNameThatIsAPathWritesNothingAnywhere) {
  const tactile::test::TempDir d_tmp("source");
  const fs::path& d = d_tmp.path();
  fs::create_directories(d / "base");
  const std::string out = (d / "base" / "out").string();
  for (const std::string name : {"../escape", "..", ".", "a\\\\b"}) {
    std::ofstream(d / "exp.json") << experiment("x", name);
    const auto r = run_tactile("experiment " + sh((d / "exp.json").string()) + " --out " + sh(out));
    EXPECT_EQ(r.exit_code, 1) << name << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("exp.json: sources[0].name \"")) << name;
    EXPECT_THAT(r.output, HasSubstr("is not a plain name")) << name;
    EXPECT_FALSE(fs::exists(out)) << name << ": " << listing(d);
    EXPECT_EQ(listing(d / "base"), "") << name;
    EXPECT_FALSE(fs::exists(d / "escape")) << name;
  }
}

// A name longer than a file name may be made the run's movie fail after the work was done (the
// run's id holds it): refused at once instead, with the limit.
TEST(PlainNamesCli, OverlongSourceOrLayoutNameIsRefusedBeforeAnyWork) {
  const tactile::test::TempDir d_tmp("long");
  const fs::path& d = d_tmp.path();
  const std::string long_name(240, 'a');
  const std::string out = (d / "out").string();
  std::ofstream(d / "exp.json") << experiment("x", long_name);
  auto r =
      run_tactile("experiment " + sh((d / "exp.json").string()) + " --out " + sh(out) + " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("sources[0].name \"" + long_name + "\" is not a plain name"));
  EXPECT_THAT(r.output, HasSubstr("240 bytes"));
  EXPECT_FALSE(fs::exists(out)) << listing(d);

  std::ofstream(d / "lab.json") << R"({"name": ")" + long_name +
                                       R"(", "rows": 5, "cols": 7, "pitch_mm": [1, 1.2],
    "contactor_size_mm": [0.5, 0.5], "deflection_axis": "y", "deflection_range_um": [-40, 40],
    "max_rate_hz": 500})";
  std::ofstream(d / "exp2.json") << experiment("x", "gt", "\"lab.json\"");
  r = run_tactile("experiment " + sh((d / "exp2.json").string()) + " --out " + sh(out) +
                  " --quiet");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("lab.json: name \"" + long_name + "\" is not a plain name"));
  EXPECT_FALSE(fs::exists(out)) << listing(d);
}

// A line break in the experiment's name split the manifest's header in two: the manifest that
// --plan wrote was then refused as damaged by --cell.
TEST(PlainNamesCli, ExperimentNameWithALineBreakIsRefused) {
  const tactile::test::TempDir d_tmp("newline");
  const fs::path& d = d_tmp.path();
  std::ofstream(d / "exp.json") << experiment("two\\nlines", "gt");
  const auto r = run_tactile("experiment " + sh((d / "exp.json").string()) + " --out " +
                             sh((d / "out").string()) + " --plan");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("exp.json: name \"two\\nlines\" is not a plain name: it holds "
                                  "a control character"));
  EXPECT_FALSE(fs::exists(d / "out"));
}

// A line break in --partition or in the output folder's path began a line of its own in
// cells.sh, which bash ran on the cluster.
TEST(PlainNamesCli, SlurmTextThatWouldBreakOutOfItsLineIsAUsageError) {
  const tactile::test::TempDir d_tmp("slurm");
  const fs::path& d = d_tmp.path();
  std::ofstream(d / "exp.json") << experiment("x", "gt");
  const std::string exp = "experiment " + sh((d / "exp.json").string());
  auto r = run_tactile(exp + " --out " + sh((d / "out").string()) + " --slurm --partition " +
                       sh("short\ntouch " + (d / "pwned").string()));
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--partition"));
  EXPECT_FALSE(fs::exists(d / "out")) << listing(d);

  for (const std::string folder : {"a\ntouch b", "with space", "per%jcent", "hash#mark"}) {
    const fs::path out = d / folder;
    r = run_tactile(exp + " --out " + sh(out.string()) + " --slurm");
    EXPECT_EQ(r.exit_code, 2) << folder << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("--out")) << folder;
    EXPECT_FALSE(fs::exists(out / "slurm")) << folder << ": " << listing(d);
    EXPECT_FALSE(fs::exists(out / "manifest.tsv")) << folder;
  }
}

// A folder whose path holds what a shell would expand is named in the scripts as a quoted word:
// the array task run by bash (as Slurm runs it) runs the cell and nothing else.
TEST(PlainNamesCli, SlurmScriptQuotesAFolderHoldingShellSyntax) {
  const tactile::test::TempDir d_tmp("quoted");
  const fs::path& d = d_tmp.path();
  std::ofstream(d / "exp.json") << experiment("x", "gt");
  // (No white space, which the #SBATCH lines refuse: ${IFS} is the shell's own.)
  const fs::path out = d / "r$(touch${IFS}made-by-dollar)`touch${IFS}made-by-backquote`$HOME";
  auto r = run_tactile("experiment " + sh((d / "exp.json").string()) + " --out " +
                       sh(out.string()) + " --slurm");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(out / "slurm" / "cells.sh")) << listing(d);
  const std::string task = "cd " + sh(d.string()) + " && SLURM_ARRAY_TASK_ID=0 bash " +
                           sh((out / "slurm" / "cells.sh").string()) + " >/dev/null 2>&1";
  EXPECT_EQ(std::system(task.c_str()), 0);
  EXPECT_FALSE(fs::exists(d / "made-by-dollar")) << listing(d);
  EXPECT_FALSE(fs::exists(d / "made-by-backquote")) << listing(d);
  r = run_tactile("experiment " + sh((d / "exp.json").string()) + " --out " + sh(out.string()) +
                  " --merge --status");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("1 cells: 1 done"));
}
