// An experiment as cells: stable ids, a manifest that refuses damage, one cell run idempotently
// with a failed cell rerun, a merge that names what is missing and otherwise equals the
// one-machine run, and the Slurm scripts.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "../common/file_text.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/experiments/cells.hpp"
#include "tactile/experiments/slurm.hpp"

namespace tactile::experiments {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* kGrid = R"({
  "name": "cells", "seed": 3,
  "sources": [{"name": "bump", "ground_truth": {"scene": "bump", "frames": 8}, "grid_spacing_mm": 0.6}],
  "layouts": ["stress"],
  "methods": ["proportional", "integrated"],
  "parameters": {"rate_hz": 100, "gain_um_per_strain": [500, 1000]}
})";

std::string slurp(const fs::path& path) {
  return tactile::test::file_text(path);
}

// metrics.csv without its comment line and without the timing column (the last).
std::string rows_without_timing(const fs::path& path) {
  std::istringstream in(slurp(path));
  std::string line, out;
  while (std::getline(in, line))
    if (!line.starts_with("#")) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

const CellContext kOneThread{.threads = 1, .runner = "test", .progress = {}};

Experiment grid(const std::string& text = kGrid) {
  return parse_experiment(text, "cells.json", ".");
}

TEST(Cells, IdsComeFromTheParametersAndStayTheSame) {
  const Plan a = plan_experiment(grid());
  const Plan b = plan_experiment(grid());
  ASSERT_EQ(a.cells.size(), 4u);
  std::set<std::string> ids;
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    EXPECT_EQ(a.cells[i].id, b.cells[i].id);
    EXPECT_EQ(a.cells[i].index, i);
    EXPECT_EQ(a.cells[i].folder, fs::path("cells") / a.cells[i].id);
    ids.insert(a.cells[i].id);
  }
  EXPECT_EQ(ids.size(), 4u);
  // The same file named another way (as a cluster's task names it, absolutely) plans the same.
  const Plan absolute = plan_experiment(parse_experiment(kGrid, "/some/where/cells.json", "/x"));
  for (std::size_t i = 0; i < a.cells.size(); ++i) EXPECT_EQ(absolute.cells[i].id, a.cells[i].id);
  // Another gain changes the ids of the cells that use it, and only theirs.
  std::string other = kGrid;
  other.replace(other.find("[500, 1000]"), 11, "[500, 2000]");
  const Plan c = plan_experiment(grid(other));
  int same = 0;
  for (std::size_t i = 0; i < 4; ++i) same += a.cells[i].id == c.cells[i].id;
  EXPECT_EQ(same, 2);
  EXPECT_NE(a.experiment_hash, c.experiment_hash);
}

TEST(Cells, ManifestRefusesDamageAndAnotherExperiment) {
  const tactile::test::TempDir out_tmp("manifest");
  const fs::path& out = out_tmp.path();
  const Experiment ex = grid();
  const Plan plan = plan_experiment(ex);
  EXPECT_THROW(check_manifest(plan, out), FormatError);  // none yet
  write_manifest(ex, plan, out);
  EXPECT_NO_THROW(check_manifest(plan, out));
  const std::string good = slurp(out / "manifest.tsv");
  const auto refusal = [&](const std::string& text) {
    std::ofstream(out / "manifest.tsv") << text;
    try {
      check_manifest(plan, out);
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // A line cut short, a cell missing at the end, garbage on top, another experiment's.
  std::string cut = good;
  cut.erase(cut.rfind('\t'));
  EXPECT_THAT(refusal(cut), HasSubstr("manifest.tsv line 7: damaged"));
  std::string short_one = good.substr(0, good.rfind('\n', good.size() - 2) + 1);
  EXPECT_THAT(refusal(short_one), HasSubstr("ends after 3 of its 4 cells"));
  EXPECT_THAT(refusal("hello\n" + good), HasSubstr("line 1: not an experiment manifest"));
  std::string other = kGrid;
  other.replace(other.find("[500, 1000]"), 11, "[500, 2000]");
  const Experiment ex2 = grid(other);
  write_manifest(ex2, plan_experiment(ex2), out);
  EXPECT_THAT(refusal(slurp(out / "manifest.tsv")), HasSubstr("planned from another experiment"));
  EXPECT_THAT(refusal(good + good.substr(good.rfind('\n', good.size() - 2) + 1)),
              HasSubstr("more lines than the 4 cells"));
}

TEST(Cells, CellIsChosenByIdOrIndexAndOtherwiseRefused) {
  const Plan plan = plan_experiment(grid());
  EXPECT_EQ(find_cell(plan, "2"), 2u);
  EXPECT_EQ(find_cell(plan, plan.cells[3].id), 3u);
  try {
    find_cell(plan, "4");
    ADD_FAILURE() << "index 4 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("--cell 4: out of range: the manifest has 4 cells, 0 to 3"));
  }
  EXPECT_THROW(find_cell(plan, "99999999999999999999999"), std::invalid_argument);
  EXPECT_THROW(find_cell(plan, "run-0000000000000000"), std::invalid_argument);
  EXPECT_THROW(find_cell(plan, ""), std::invalid_argument);
}

TEST(Cells, AllCellsThenMergeEqualTheOneMachineRunAndAFailedCellReruns) {
  const tactile::test::TempDir local_tmp("local");
  const tactile::test::TempDir cells_tmp("cells");
  const fs::path& cells = cells_tmp.path();
  const Experiment ex = grid();
  run_experiment(ex, local_tmp.path(), 2);
  const Plan plan = plan_experiment(ex);
  write_manifest(ex, plan, cells);

  // Cell 1 fails: a folder stands where its movie goes.
  const fs::path blocker = cells / "movies" / (ex.runs[1].id + ".h5");
  fs::create_directories(blocker / "x");
  for (std::size_t i = 0; i < plan.cells.size(); ++i) {
    if (i == 1) {
      EXPECT_ANY_THROW(run_cell(ex, plan, i, cells, kOneThread));
    } else {
      EXPECT_FALSE(run_cell(ex, plan, i, cells, kOneThread).skipped);
    }
  }
  EXPECT_FALSE(fs::exists(cells / plan.cells[1].folder / "done"));
  EXPECT_EQ(cell_status(plan.cells[1], cells).state, CellState::failed);
  EXPECT_EQ(cell_status(plan.cells[0], cells).state, CellState::done);
  auto merged = merge_experiment(ex, plan, cells, 1);
  ASSERT_EQ(merged.incomplete.size(), 1u);
  EXPECT_THAT(merged.incomplete[0],
              HasSubstr(plan.cells[1].id + " (" + ex.runs[1].id + "): failed"));
  EXPECT_FALSE(fs::exists(cells / "metrics.csv"));
  const auto status = experiment_status(plan, cells);
  ASSERT_EQ(status.kinds.size(), 1u);
  EXPECT_EQ(status.kinds[0].done, 3u);
  EXPECT_EQ(status.kinds[0].failed, 1u);
  EXPECT_GT(status.kinds[0].cpu_s, 0);

  // Done cells are skipped; the failed one reruns once its obstacle is gone.
  const auto marker_time = fs::last_write_time(cells / plan.cells[0].folder / "done");
  EXPECT_TRUE(run_cell(ex, plan, 0, cells, kOneThread).skipped);
  EXPECT_EQ(fs::last_write_time(cells / plan.cells[0].folder / "done"), marker_time);
  fs::remove_all(blocker);
  EXPECT_FALSE(run_cell(ex, plan, 1, cells, kOneThread).skipped);
  EXPECT_EQ(cell_status(plan.cells[1], cells).attempts, 2);
  EXPECT_EQ(cell_status(plan.cells[0], cells).attempts, 1);
  merged = merge_experiment(ex, plan, cells, 1);
  EXPECT_TRUE(merged.incomplete.empty());
  EXPECT_EQ(rows_without_timing(cells / "metrics.csv"),
            rows_without_timing(local_tmp.path() / "metrics.csv"));
  EXPECT_EQ(merged.results.size(), 4u);
  EXPECT_TRUE(fs::exists(cells / "plots" / "correlation.png"));
}

TEST(Cells, CellLeftRunningByAProcessThatIsGoneCountsAsFailed) {
  const tactile::test::TempDir out_tmp("gone");
  const fs::path& out = out_tmp.path();
  const Plan plan = plan_experiment(grid());
  fs::create_directories(out / plan.cells[0].folder);
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  // Pid 2^22 + 1 is above Linux's largest pid (pid_max <= 2^22): no such process.
  std::ofstream(out / plan.cells[0].folder / "status.json")
      << R"({"state": "running", "attempts": 1, "pid": 4194305, "host": ")" << host << "\"}";
  const CellStatus s = cell_status(plan.cells[0], out);
  EXPECT_EQ(s.state, CellState::failed);
  EXPECT_THAT(s.message, HasSubstr("stopped while running"));
  EXPECT_EQ(cell_status(plan.cells[1], out).state, CellState::missing);
}

TEST(Slurm, ScriptsRunTheCellsNotDoneInThrottledTasks) {
  const tactile::test::TempDir out_tmp("slurm");
  const fs::path& out = out_tmp.path();
  const Experiment ex = grid();
  const Plan plan = plan_experiment(ex);
  write_manifest(ex, plan, out);
  run_cell(ex, plan, 0, out, kOneThread);
  const auto jobs = write_slurm_jobs(
      plan, out, "/opt/t/tactile", "/data/exp.json",
      {.partition = "short", .max_parallel = 2, .cells_per_task = 2, .time_limit = "0:30:00"});
  EXPECT_EQ(jobs.cells, 3u);
  EXPECT_EQ(jobs.tasks, 2u);
  const std::string cells = slurp(jobs.cells_script);
  EXPECT_THAT(cells, HasSubstr("#SBATCH --array=0-1%2\n"));
  EXPECT_THAT(cells, HasSubstr("#SBATCH --partition=short\n"));
  EXPECT_THAT(cells, HasSubstr("#SBATCH --time=0:30:00\n"));
  EXPECT_THAT(cells, HasSubstr("cells=(\n  1 2 3\n)"));
  EXPECT_THAT(cells, HasSubstr("'/opt/t/tactile' experiment '/data/exp.json' --out '" +
                               out.string() + "' \"${args[@]}\""));
  EXPECT_THAT(cells, HasSubstr("args+=(--cell \"${cells[i]}\")"));
  EXPECT_THAT(slurp(jobs.merge_script), HasSubstr("--merge\n"));
  EXPECT_EQ(with_array_job(jobs.merge_command, "77")[2], "--dependency=afterok:77");
  EXPECT_THAT(slurm_commands_text(jobs),
              HasSubstr("--dependency=afterok:\"${array_job%%;*}\" " + jobs.merge_script.string()));
  EXPECT_THROW(check_time_limit("5x"), std::invalid_argument);
  EXPECT_THROW(check_time_limit("1:2:3:4"), std::invalid_argument);
  EXPECT_NO_THROW(check_time_limit("2-12:00"));
  for (const char* good : {"30", "30:00", "1:30:00", "2-12", "2-12:00:00"})
    EXPECT_NO_THROW(check_time_limit(good)) << good;
  for (const char* bad : {"", "-1", "1-", "1-2-3", "1::2", ":5", "1:2:", "1.5", "1h"})
    EXPECT_THROW(check_time_limit(bad), std::invalid_argument) << bad;
  // Text that would end its line in a script (then run by bash) or that sbatch splits or
  // rewrites in an #SBATCH line, refused before a script is written.
  const auto refused = [&](const fs::path& folder, const SlurmOptions& options,
                           const std::string& message) {
    try {
      write_slurm_jobs(plan, folder, "/t", "/e.json", options);
      ADD_FAILURE() << "accepted: " << folder << " " << options.partition;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(message));
    }
    EXPECT_FALSE(fs::exists(folder / "slurm" / "cells.sh")) << folder;
  };
  const auto partition = [](const std::string& p) {
    SlurmOptions o;
    o.partition = p;
    return o;
  };
  refused(out / "p", partition("short\ntouch /tmp/pwned"), "--partition");
  refused(out / "p", partition("a b"), "--partition");
  refused(out / "p", partition("$(reboot)"), "--partition");
  for (const char* folder : {"line\nbreak", "a space", "per%jcent", "a#hash", "quo'te", "quo\"te"})
    refused(out / folder, {}, "--out");
  EXPECT_NO_THROW(write_slurm_jobs(plan, out, "/t", "/e.json", partition("short,long_2")));
  try {
    std::vector<Cell> many(2003, plan.cells[1]);
    Plan big = plan;
    big.cells = many;
    write_slurm_jobs(big, out, "/t", "/e.json", SlurmOptions{});
    ADD_FAILURE() << "2003 tasks accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("use --cells-per-task 3 or more"));
  }
}

}  // namespace
}  // namespace tactile::experiments
