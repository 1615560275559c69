// `tactile bench prints`: strain on real skin. Every hand-marked print of a folder is moved by
// exact warps (print_warp.hpp) and measured by the landmark pipeline with its default settings
// and by the Lucas-Kanade and DIS baselines (same strain computation); tuning and held-out prints
// are reported apart. `--sweeps` pushes noise, blur, strain and speed on one held-out print until
// the pipeline fails.

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "bench_files.hpp"
#include "bench_sweep_options.hpp"
#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/bench_report.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/option_table.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

void add_bench_prints(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path prints;
    std::vector<std::string> held_out = {"11", "12", "13", "14", "15"};
    int frames = 30;
    double px_per_mm = 47;
    bool quick = false;
    bool touch = false;
    bool slip = false;
    std::vector<int> frame_px;  // empty: each print's own size
    BenchSweepOptions common{.out = "bench-prints", .limits = capture::kPrintSweepLimits};
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "prints",
      "Strain on real skin: each hand-marked print of PRINTS_DIR (image_NN + pores_NN.txt, e.g.\n"
      "the PolyU HRF prints in tests/data/polyu-hrf-pores) moved by exact warps (5 patterns at\n"
      "4 %, the wave also at 1 and 8 %, and 8 % crossing at 25 mm/s) and measured by the landmark "
      "pipeline with its default\n"
      "settings, Lucas-Kanade and DIS; tuning and held-out prints reported apart. Writes\n"
      "OUT/bench_prints.csv and OUT/speed_accuracy_prints.png (and .svg); --sweeps pushes noise,\n"
      "blur, strain, slide, exploration speed and camera rate, and full slip's speed and camera\n"
      "rate, on the first held-out print until failure (OUT/prints_sweeps.csv,\n"
      "accuracy_speed_prints.png, fps_accuracy_prints.png).");
  add_input_folder(*sub, "PRINTS_DIR", opt->prints, "Folder of marked prints");
  add_bench_sweep_options(*sub, opt->common);
  sub->add_option("--held-out", opt->held_out,
                  "Numbers NN of the prints kept out of tuning (reported apart)")
      ->delimiter(',')
      ->capture_default_str();
  add_ranged(*sub, "--frames", opt->frames, "Frames per sequence", 12, 1000);
  add_ranged(*sub, "--px-per-mm", opt->px_per_mm, "Scale of the prints", 5.0, 500.0);
  sub->add_option("--frame-px", opt->frame_px,
                  "Film W x H px frames: each print mirrored about its edges until it fills them\n"
                  "(marks mirrored too), e.g. --frame-px 640 484 for a 640 x 484 camera; default:\n"
                  "each print's own size")
      ->expected(2)
      ->check(within(16, 4096));
  sub->add_flag("--quick", opt->quick,
                "Only the 4 % wave and the fast 8 % wave, landmarks and Lucas-Kanade");
  sub->add_flag("--touch", opt->touch,
                "Instead of the wave and the other quasi-static patterns, the other motions of "
                "the fast scene (8 %, 25 mm/s, 60 Hz): pulse, ridge, stick-slip, kernels, and "
                "the wave with a loss of contact");
  sub->add_flag("--slip", opt->slip,
                "Instead, full slip: the skin sliding through the view at 10, 25, 50 and 100 "
                "mm/s (60 Hz) under a static 4 % field; Lucas-Kanade re-seeds every frame")
      ->excludes("--touch");
  sub->callback([opt, &action] {
    action = [opt] {
      refuse_output_over_input(
          {output_folder(
              "--out", opt->common.out,
              {"bench_prints.csv", "speed_accuracy_prints.png", "speed_accuracy_prints.svg",
               "prints_sweeps.csv", "accuracy_speed_prints.png", "accuracy_speed_prints.svg",
               "fps_accuracy_prints.png", "fps_accuracy_prints.svg"})},
          {{"PRINTS_DIR", opt->prints}});
      auto prints = capture::read_pore_training_prints(opt->prints);
      if (!opt->frame_px.empty()) {
        for (auto& p : prints) p = capture::mirrored_to_size(p, opt->frame_px[0], opt->frame_px[1]);
      }
      // A held-out number that names no print would leave that group silently short.
      for (const auto& nn : opt->held_out) {
        if (std::none_of(prints.begin(), prints.end(),
                         [&](const auto& p) { return capture::print_number(p.name) == nn; })) {
          throw RequestError(fmt::format("--held-out {}: {} holds no print image_{}.*", nn,
                                         opt->prints.string(), nn));
        }
      }
      fs::create_directories(opt->common.out);
      const auto all = capture::print_bench_methods();
      capture::PrintBenchOptions bench;
      bench.held_out = opt->held_out;
      bench.frame_count = opt->frames;
      bench.px_per_mm = opt->px_per_mm;
      bench.cases = opt->slip    ? capture::slip_bench_cases()
                    : opt->touch ? capture::touch_bench_cases()
                                 : capture::print_bench_cases(opt->quick);
      bench.method_count = opt->quick ? 2 : all.size();
      fmt::print("{}", capture::print_bench_table_header());
      const auto rows =
          capture::bench_prints(prints, all, bench, [](const capture::PrintBenchRow& r) {
            fmt::print("{}", capture::print_bench_table_row(r));
          });

      fmt::print("\nsummary (medians over sequences; correlation over the non-rigid ones)\n");
      fmt::print("{}", capture::print_summary_table_header());
      std::vector<std::string> names;
      for (std::size_t k = 0; k < bench.method_count; ++k) names.push_back(all[k].name);
      for (const auto& m : capture::summarise_print_bench(rows, names)) {
        fmt::print("{}", capture::print_summary_table_row(m));
      }

      write_bench_files("bench prints", opt->common.out / "bench_prints.csv",
                        capture::print_bench_csv_header(), rows, capture::print_bench_csv_row,
                        opt->common.out / "speed_accuracy_prints.png",
                        capture::print_bench_chart(rows));
      if (!opt->common.sweeps) return 0;

      const std::set<std::string> held(opt->held_out.begin(), opt->held_out.end());
      const auto first_held = std::find_if(prints.begin(), prints.end(), [&](const auto& p) {
        return held.count(capture::print_number(p.name)) > 0;
      });
      const auto& print = first_held != prints.end() ? *first_held : prints.front();
      const auto sweep_path = opt->common.out / "prints_sweeps.csv";
      auto sw = csv::open_with_header(sweep_path, capture::print_sweep_csv_header());
      fmt::print(
          "\nstability sweeps ({}, {} frames; failure: rms error > {} or < {} "
          "points)\n",
          print.name, opt->frames, opt->common.limits.max_rms, opt->common.limits.min_points);
      // Accuracy against exploration speed, and frames/s against accuracy, for every method.
      auto charts = capture::print_sweep_charts(opt->common.limits.max_rms);
      for (const auto& s : capture::print_sweeps()) {
        const std::size_t method_count = s.every_method ? all.size() : 1;
        for (std::size_t k = 0; k < method_count; ++k) {
          const auto failures = capture::run_print_sweep(
              s, all[k], print, bench, opt->common.limits, [&](const capture::PrintSweepPoint& p) {
                fmt::print("{}", capture::print_sweep_table_row(s.name, p));
                sw << capture::print_sweep_csv_row(s.name, p);
                capture::add_print_sweep_point(charts, s, p);
              });
          fmt::print("{}", failures.summary(s.name + ", " + all[k].name, s.values.back()));
        }
      }
      const ChartFiles speed_plot =
          write_line_chart(opt->common.out / "accuracy_speed_prints.png", charts.by_speed);
      const ChartFiles fps_plot =
          write_scatter_chart(opt->common.out / "fps_accuracy_prints.png", charts.fps_error);
      fmt::print("bench prints: wrote {}, {}\n", speed_plot.png.string(), fps_plot.png.string());
      csv::finish(sw, sweep_path);
      fmt::print("bench prints: wrote {}\n", sweep_path.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
