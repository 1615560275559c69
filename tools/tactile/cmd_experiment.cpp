// `tactile experiment`: a grid of mapping runs from a JSON file into one output folder.

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "command.hpp"
#include "number_checks.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_experiment(CLI::App& app, Action& action) {
  struct Options {
    fs::path file;
    std::optional<fs::path> out;
    int threads = 0;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "experiment",
      "Run a mapping experiment: every source x layout x method x parameter combination in\n"
      "EXP.json, in parallel, into one folder (movies, metrics.csv, plots, the configuration).\n"
      "The whole file is checked before any work starts. Schema: docs/formats.md;\n"
      "example: tools/experiments/methods.json. With a \"perception\" section, also Table 2\n"
      "of paper 2 computed from each mapping's movies of the simulated fingertip's skin\n"
      "(tools/experiments/perception.json).");
  sub->add_option("EXP_JSON", opt->file, "Experiment file (JSON)")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", opt->out, "Output folder (default: <experiment name>-results)");
  sub->add_option("--threads", opt->threads, "Worker threads (0: all cores)")
      ->check(within(0, 256))
      ->capture_default_str();
  sub->add_flag("--quiet", opt->quiet, "Print only the summary");
  sub->callback([opt, &action] {
    action = [opt] {
      const auto t0 = std::chrono::steady_clock::now();
      experiments::Experiment ex = experiments::read_experiment(opt->file);
      const fs::path out = opt->out.value_or(fs::path(ex.name + "-results"));
      std::vector<NamedPath> inputs = {{"EXP_JSON", opt->file}};
      for (const auto& s : ex.sources)
        if (!s.path.empty()) inputs.push_back({"source '" + s.name + "'", s.path});
      for (const auto& layout : ex.layout_files) inputs.push_back({"layout", layout});
      refuse_output_over_input({experiments::experiment_output("--out", out)}, inputs);
      fmt::print("experiment '{}': {} sources x {} layouts -> {} runs, checked; writing {}\n",
                 ex.name, ex.sources.size(), ex.layouts.size(), ex.runs.size(), out.string());
      std::mutex print_mutex;
      const auto report =
          experiments::run_experiment(ex, out, opt->threads, [&](const std::string& message) {
            if (opt->quiet) return;
            const std::lock_guard lock(print_mutex);
            fmt::print("  {}\n", message);
          });
      const double total_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print("{:<44} {:>6} {:>9} {:>6} {:>8}\n", "run", "corr", "rms err", "sat", "map ms");
      for (std::size_t i = 0; i < ex.runs.size(); ++i) {
        const auto& r = report.results[i];
        fmt::print("{:<44} {:>6.3f} {:>9.4f} {:>6.3f} {:>8.1f}\n", ex.runs[i].id,
                   r.metrics.strain_correlation, r.metrics.strain_rms_error,
                   r.metrics.saturated_fraction, r.map_ms);
      }
      if (!report.perception.empty()) {
        fmt::print(
            "perception (Table 2 from movies; accuracy with all 76 inputs, mean R^2, "
            "cascade RMS):\n");
        for (const auto& t : report.perception)
          for (const auto& row : t.rows)
            if (row.result.inputs == "all") {
              const auto& r = row.result;
              fmt::print("  {:<40} exp {} {:>3}/{:<3} R^2 {:.3f} cascade RMS {:.2f} mm\n", t.id,
                         r.degree, r.correct, r.tested, (r.r2[0] + r.r2[1] + r.r2[2]) / 3,
                         r.cascade_rms_mm);
            }
      }
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
