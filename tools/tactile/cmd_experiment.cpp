// `tactile experiment`: a grid of mapping runs from a JSON file into one output folder.

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "request_options.hpp"
#include "tactile/experiments/cells.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/experiments/experiment_request.hpp"
#include "tactile/experiments/slurm.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

// Where this process runs, for the cell's status file: the Slurm task when under Slurm.
std::string runner_name() {
  const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  if (job && task) return fmt::format("slurm job {}_{}", job, task);
  if (const char* plain = std::getenv("SLURM_JOB_ID")) return fmt::format("slurm job {}", plain);
  return "command line";
}

void print_results(const experiments::Experiment& ex,
                   const std::vector<experiments::RunResult>& results,
                   const std::vector<experiments::PerceptionLine>& perception) {
  fmt::print("{:<44} {:>6} {:>9} {:>6} {:>8}\n", "run", "corr", "rms err", "sat", "map ms");
  for (std::size_t i = 0; i < ex.runs.size(); ++i) {
    const auto& r = results[i];
    fmt::print("{:<44} {:>6.3f} {:>9.4f} {:>6.3f} {:>8.1f}\n", ex.runs[i].id,
               r.metrics.strain_correlation, r.metrics.strain_rms_error,
               r.metrics.saturated_fraction, r.map_ms);
  }
  if (perception.empty()) return;
  fmt::print(
      "perception (Table 2 from movies; accuracy with all 76 inputs, mean R^2, cascade RMS):\n");
  for (const auto& l : perception)
    fmt::print("  {:<40} exp {} {:>3}/{:<3} R^2 {:.3f} cascade RMS {:.2f} mm\n", l.table, l.degree,
               l.correct, l.tested, l.mean_r2, l.cascade_rms_mm);
}

int print_status(const experiments::Plan& plan, const fs::path& out) {
  const auto status = experiments::experiment_status(plan, out);
  std::size_t done = 0, running = 0, failed = 0, missing = 0;
  for (const auto& k : status.kinds) {
    done += k.done;
    running += k.running;
    failed += k.failed;
    missing += k.missing;
  }
  fmt::print("experiment '{}' in {}: {} cells: {} done, {} running, {} failed, {} missing\n",
             plan.experiment, out.string(), plan.cells.size(), done, running, failed, missing);
  fmt::print("{:<11} {:>6} {:>6} {:>8} {:>7} {:>8} {:>12} {:>14}\n", "kind", "cells", "done",
             "running", "failed", "missing", "CPU s (done)", "CPU s per cell");
  for (const auto& k : status.kinds)
    fmt::print("{:<11} {:>6} {:>6} {:>8} {:>7} {:>8} {:>12.2f} {:>14.3f}\n", to_string(k.kind),
               k.cells, k.done, k.running, k.failed, k.missing, k.cpu_s,
               k.done ? k.cpu_s / static_cast<double>(k.done) : 0.0);
  for (const auto& note : status.notes) fmt::print("  {}\n", note);
  return 0;
}

}  // namespace

void add_experiment(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    experiments::ExperimentRequest request;
    bool plan = false, merge = false, status = false, slurm = false, submit = false;
    std::vector<std::string> cells;
    experiments::SlurmOptions slurm_options;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "experiment",
      "Run a mapping experiment: every source x layout x method x parameter combination in\n"
      "EXP.json, in parallel, into one folder (movies, metrics.csv, plots, the configuration).\n"
      "The whole file is checked before any work starts. Schema: docs/formats.md;\n"
      "example: tools/experiments/methods.json. With a \"perception\" section, also Table 2\n"
      "of paper 2 computed from each mapping's movies of the simulated fingertip's skin\n"
      "(tools/experiments/perception.json).\n"
      "The grid is a list of independent cells (manifest.tsv): --plan writes it, --cell runs\n"
      "one cell, --merge gathers them; --slurm writes a Slurm job array for them\n"
      "(docs/experiments.md). Without these, all three happen here.");
  add_request_options(*sub, std::shared_ptr<experiments::ExperimentRequest>(opt, &opt->request),
                      experiments::experiment_options());
  auto* plan = sub->add_flag("--plan", opt->plan,
                             "Only write the manifest of cells (manifest.tsv) and experiment.json");
  auto* cell = sub->add_option("--cell", opt->cells,
                               "Run cells, each by its id or its index in the manifest, one after "
                               "the other (repeat the option; a cell already done is skipped)");
  auto* merge = sub->add_flag("--merge", opt->merge,
                              "Gather every cell's results into metrics.csv, resolved.json and "
                              "the plots; exit 1 naming the cells not done");
  auto* status = sub->add_flag("--status", opt->status,
                               "With --merge: print done / running / failed / missing cells and "
                               "CPU time per cell kind, and merge nothing");
  auto* slurm = sub->add_flag("--slurm", opt->slurm,
                              "Write a Slurm job array running the cells not done and a merge "
                              "job after it (into OUT/slurm); print the sbatch commands");
  auto* partition =
      sub->add_option("--partition", opt->slurm_options.partition, "With --slurm: partition");
  auto* max_parallel =
      sub->add_option("--max-parallel", opt->slurm_options.max_parallel,
                      "With --slurm: array tasks running at once (0: as many as Slurm allows)")
          ->check(within(0, 100000));
  auto* per_task = sub->add_option("--cells-per-task", opt->slurm_options.cells_per_task,
                                   "With --slurm: cells each array task runs in turn")
                       ->check(within(1, 1000000))
                       ->capture_default_str();
  auto* time_limit =
      sub->add_option("--time", opt->slurm_options.time_limit,
                      "With --slurm: time limit of each task and of the merge (sbatch --time)")
          ->check(CLI::Validator(
              [](std::string& v) -> std::string {
                try {
                  experiments::check_time_limit(v);
                  return {};
                } catch (const std::invalid_argument& e) {
                  return e.what();
                }
              },
              "TIME"));
  auto* submit = sub->add_flag("--submit", opt->submit,
                               "With --slurm: submit both jobs with sbatch and print their ids");
  plan->excludes(cell, merge, slurm);
  cell->excludes(merge, slurm);
  merge->excludes(slurm);
  status->needs(merge);
  for (auto* o : {partition, max_parallel, per_task, time_limit, submit}) o->needs(slurm);
  sub->callback([opt, &action] {
    action = [opt] {
      const auto t0 = std::chrono::steady_clock::now();
      experiments::ResolvedExperiment resolved =
          experiments::resolve(opt->request, OptionSpelling::cli);
      experiments::Experiment& ex = resolved.experiment;
      const fs::path& out = resolved.out;
      if (opt->slurm) {
        try {
          experiments::check_slurm_options(opt->slurm_options, fs::absolute(out));
        } catch (const std::invalid_argument& e) {
          fmt::print(stderr, "tactile experiment: {}\n", e.what());
          return 2;
        }
      }
      const experiments::Plan plan = experiments::plan_experiment(ex);
      if (opt->plan) {
        const fs::path manifest = experiments::write_manifest(ex, plan, out);
        fmt::print("experiment '{}': {} cells planned into {}\n", ex.name, plan.cells.size(),
                   manifest.string());
        return 0;
      }
      if (!opt->cells.empty() || opt->merge || opt->slurm) {
        if (opt->slurm && !fs::exists(out / "manifest.tsv")) {
          experiments::write_manifest(ex, plan, out);
        }
        experiments::check_manifest(plan, out);
      }
      if (!opt->cells.empty()) {
        // Every choice checked before any cell runs.
        std::vector<std::size_t> chosen;
        for (const auto& choice : opt->cells) {
          try {
            chosen.push_back(experiments::find_cell(plan, choice));
          } catch (const std::invalid_argument& e) {
            fmt::print(stderr, "tactile experiment: {}\n", e.what());
            return 2;
          }
        }
        // A failed cell does not stop the others: each is independent.
        std::size_t failed = 0;
        for (const std::size_t index : chosen) {
          const auto& c = plan.cells[index];
          try {
            const auto outcome = experiments::run_cell(ex, plan, index, out,
                                                       {.threads = opt->request.threads,
                                                        .runner = runner_name(),
                                                        .progress = [&](const std::string& m) {
                                                          if (!opt->request.quiet)
                                                            fmt::print("  {}\n", m);
                                                        }});
            if (outcome.skipped)
              fmt::print("cell {} {} ({}): already done, skipped\n", index, c.id, c.name);
            else
              fmt::print("cell {} {} ({}): done in {:.2f} s wall, {:.2f} s CPU\n", index, c.id,
                         c.name, outcome.wall_s, outcome.cpu_s);
          } catch (const std::exception& e) {
            ++failed;
            fmt::print(stderr, "tactile experiment: cell {} {} ({}) failed: {}\n", index, c.id,
                       c.name, e.what());
          }
          std::fflush(stdout);
        }
        return failed ? 1 : 0;
      }
      if (opt->merge && opt->status) return print_status(plan, out);
      if (opt->merge) {
        const auto merged = experiments::merge_experiment(ex, plan, out, opt->request.threads);
        if (!merged.incomplete.empty()) {
          fmt::print(stderr, "tactile experiment: {} of {} cells are not done; nothing merged:\n",
                     merged.incomplete.size(), plan.cells.size());
          for (const auto& c : merged.incomplete) fmt::print(stderr, "  {}\n", c);
          return 1;
        }
        print_results(ex, merged.results, merged.perception);
        fmt::print("experiment: {} cells merged; {} files in {}\n", plan.cells.size(),
                   merged.files.size(), out.string());
        return 0;
      }
      if (opt->slurm) {
        experiments::SlurmJobs jobs;
        try {
          jobs = experiments::write_slurm_jobs(plan, fs::absolute(out),
                                               fs::read_symlink("/proc/self/exe"),
                                               fs::absolute(opt->request.file), opt->slurm_options);
        } catch (const std::invalid_argument& e) {
          fmt::print(stderr, "tactile experiment: {}\n", e.what());
          return 2;
        }
        fmt::print("experiment '{}': {} of {} cells to run in {} array tasks; scripts in {}\n",
                   ex.name, jobs.cells, plan.cells.size(), jobs.tasks,
                   (fs::absolute(out) / "slurm").string());
        if (!opt->submit) {
          fmt::print("submit with:\n{}", experiments::slurm_commands_text(jobs));
          return 0;
        }
        std::string array_job;
        if (jobs.tasks > 0) {
          array_job = experiments::submit_batch(jobs.cells_command);
          fmt::print("cells job {}\n", array_job);
        }
        const std::string merge_job =
            experiments::submit_batch(experiments::with_array_job(jobs.merge_command, array_job));
        fmt::print("merge job {}\n", merge_job);
        return 0;
      }
      fmt::print("experiment '{}': {} -> {} runs ({} cells), checked; writing {}\n", ex.name,
                 ex.grid, ex.runs.size(), plan.cells.size(), out.string());
      std::mutex print_mutex;
      const auto report = experiments::run_experiment(ex, out, opt->request.threads,
                                                      [&](const std::string& message) {
                                                        if (opt->request.quiet) return;
                                                        const std::lock_guard lock(print_mutex);
                                                        fmt::print("  {}\n", message);
                                                      });
      const double total_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      print_results(ex, report.results, report.lines);
      fmt::print(
          "experiment: {} runs on {} threads: sources {:.2f} s, runs {:.2f} s, perception "
          "{:.2f} s, total {:.2f} s; {} files in {}\n",
          ex.runs.size(), report.threads, report.prepare_s, report.run_s, report.perception_s,
          total_s, report.files.size(), out.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
