// `tactile bench capture`: throughput and accuracy of the strain measurement on synthetic
// sequences with exact ground truth, for the landmark pipeline at a few settings and for the
// Lucas-Kanade and DIS optical-flow baselines (same strain computation): a table, a CSV and the
// speed-accuracy chart. `--sweeps` pushes noise, blur, contrast, speed, pore size and loss of
// contact until the pipeline fails and reports where.

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "bench_sweep_options.hpp"
#include "command.hpp"
#include "number_checks.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/bench_report.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

std::string load_average() {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) != 3) return "unknown";
  return fmt::format("{:.1f} {:.1f} {:.1f}", load[0], load[1], load[2]);
}

}  // namespace

void add_bench_capture(CLI::App& bench, Action& action) {
  struct Options {
    int frames = 90;
    bool quick = false;
    BenchSweepOptions common{.out = "bench-capture", .limits = capture::kSceneSweepLimits};
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = bench.add_subcommand(
      "capture",
      "Strain measurement on every synthetic scene (bump, hole, flat-slide, flat-rotate,\n"
      "flat-stick-slip; 640 x 484): frames/s\n"
      "of extract + match + track + strain, and accuracy against the exact ground truth, for the\n"
      "landmark pipeline and the Lucas-Kanade and DIS baselines. Writes OUT/bench_capture.csv\n"
      "and OUT/speed_accuracy.png (and .svg); --sweeps also pushes each image condition until "
      "failure\n"
      "(OUT/sweeps.csv).");
  sub->add_option("--frames", opt->frames, "Frames per sequence")
      ->check(within(35, 2000))
      ->capture_default_str();
  add_bench_sweep_options(*sub, opt->common);
  sub->add_flag("--quick", opt->quick, "Only the default pipeline and the two baselines");
  sub->callback([opt, &action] {
    action = [opt] {
      fs::create_directories(opt->common.out);
      const auto all = capture::scene_bench_methods(opt->quick);
      fmt::print("load average before the run: {} ({} cores)\n", load_average(),
                 std::thread::hardware_concurrency());
      fmt::print("{}", capture::scene_bench_table_header());
      const auto results =
          capture::bench_scenes(opt->frames, all, [](const capture::SceneBenchResult& r) {
            fmt::print("{}", capture::scene_bench_table_row(r));
          });
      const auto csv_path = opt->common.out / "bench_capture.csv";
      auto csv = csv::open_with_header(csv_path, capture::scene_bench_csv_header());
      for (const auto& r : results) csv << capture::scene_bench_csv_row(r);
      csv::finish(csv, csv_path);
      const ChartFiles plot = write_scatter_chart(opt->common.out / "speed_accuracy.png",
                                                  capture::scene_bench_chart(results));
      fmt::print("load average after the run: {}\n", load_average());
      fmt::print("bench capture: wrote {}, {} and {}\n", csv_path.string(), plot.png.string(),
                 plot.svg.string());

      if (!opt->common.sweeps) return 0;
      const auto& pipeline = all.front();
      const auto sweep_path = opt->common.out / "sweeps.csv";
      auto sw = csv::open_with_header(sweep_path, capture::scene_sweep_csv_header());
      const int sweep_frames = std::min(opt->frames, 60);
      fmt::print("\nstability sweeps (bump, {} frames; failure: rms error > {} or < {} points)\n",
                 sweep_frames, opt->common.limits.max_rms, opt->common.limits.min_points);
      for (const auto& s : capture::scene_sweeps()) {
        const auto failures = capture::run_scene_sweep(
            s, pipeline, sweep_frames, opt->common.limits, [&](const capture::SceneSweepPoint& p) {
              fmt::print("{}", capture::scene_sweep_table_row(s.name, p));
              sw << capture::scene_sweep_csv_row(s.name, p);
            });
        fmt::print("{}", failures.summary(s.name, s.values.back()));
      }
      csv::finish(sw, sweep_path);
      fmt::print("bench capture: wrote {}\n", sweep_path.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
