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

#include "bench_files.hpp"
#include "bench_sweep_options.hpp"
#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
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

void add_bench_capture(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    int frames = 90;
    bool quick = false;
    BenchSweepOptions common{.out = "bench-capture", .limits = capture::kSceneSweepLimits};
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "capture",
      "Strain measurement on every synthetic scene (bump, hole, flat-slide, flat-rotate,\n"
      "flat-stick-slip; 640 x 484): frames/s\n"
      "of extract + match + track + strain, and accuracy against the exact ground truth, for the\n"
      "landmark pipeline and the Lucas-Kanade and DIS baselines. Writes OUT/bench_capture.csv\n"
      "and OUT/speed_accuracy.png (and .svg); --sweeps also pushes each image condition until "
      "failure\n"
      "(OUT/sweeps.csv).");
  add_ranged(*sub, "--frames", opt->frames, "Frames per sequence", 35, 2000);
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
      fmt::print("load average after the run: {}\n", load_average());
      write_bench_files("bench capture", opt->common.out / "bench_capture.csv",
                        capture::scene_bench_csv_header(), results, capture::scene_bench_csv_row,
                        opt->common.out / "speed_accuracy.png",
                        capture::scene_bench_chart(results));

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
