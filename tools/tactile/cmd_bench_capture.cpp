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

void print_row(const capture::SceneBenchResult& r, const std::string& extra = {}) {
  if (!r.error.empty()) {
    fmt::print("{:<20} {:<15} {}failed: {}\n", r.method, to_string(r.scene), extra, r.error);
    return;
  }
  fmt::print("{:<20} {:<15} {}{:>8.0f} {:>8.2f} {:>9.5f} {:>9.5f} {:>7.0f} {:>7.4f} {:>6}\n",
             r.method, to_string(r.scene), extra, r.frames_per_s(), r.cpu_ms_per_frame(),
             r.eval.rms_error, r.eval.rms_truth, r.eval.median_tracked_points,
             r.eval.localisation_rms_mm, r.eval.track_count);
}

}  // namespace

void add_bench_capture(CLI::App& bench, Action& action) {
  struct Options {
    int frames = 90;
    bool quick = false;
    BenchSweepOptions common{
        .out = "bench-capture", .sweeps = false, .limits = {.max_rms = 0.005, .min_points = 100}};
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
      fmt::print("{:<20} {:<15} {:>8} {:>8} {:>9} {:>9} {:>7} {:>7} {:>6}\n", "method", "scene",
                 "frames/s", "cpu_ms/f", "rms_err", "rms_true", "points", "loc_mm", "tracks");
      const auto results = capture::bench_scenes(
          opt->frames, all, [](const capture::SceneBenchResult& r) { print_row(r); });
      const auto csv_path = opt->common.out / "bench_capture.csv";
      auto csv = csv::open_with_header(
          csv_path,
          "method,scene,frames,seconds,frames_per_s,cpu_ms_per_frame,rms_error,rms_truth,edges,"
          "median_tracked_points,localisation_rms_mm,track_count,median_track_frames,error");
      XYChart chart{.title = "Strain from the five synthetic scenes (640 x 484)",
                    .x = {.label = "frames per second (extract + match + track + strain)",
                          .scale = AxisScale::log},
                    .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                    .x_targets = {{.value = 300, .label = "300 frames/s"}},
                    .y_targets = {{.value = 0.005, .label = "RMS 0.005"}},
                    .width = 960,
                    .height = 600};
      for (const auto& r : results) {
        csv << fmt::format(
            "\"{}\",{},{},{:.4f},{:.1f},{:.3f},{:.6g},{:.6g},{},{:.0f},{:.5f},{},{:.0f},\"{}\"\n",
            r.method, to_string(r.scene), r.frames, r.seconds, r.frames_per_s(),
            r.cpu_ms_per_frame(), r.eval.rms_error, r.eval.rms_truth, r.eval.edges,
            r.eval.median_tracked_points, r.eval.localisation_rms_mm, r.eval.track_count,
            r.eval.median_track_frames, r.error);
        if (!r.error.empty()) continue;
        // One series per method, so that a method's five scenes share a colour.
        auto it = std::find_if(chart.series.begin(), chart.series.end(),
                               [&](const ChartSeries& s) { return s.label == r.method; });
        if (it == chart.series.end()) it = chart.series.insert(it, {.label = r.method});
        it->x.push_back(r.frames_per_s());
        it->y.push_back(r.eval.rms_error);
      }
      csv::finish(csv, csv_path);
      const ChartFiles plot = write_scatter_chart(opt->common.out / "speed_accuracy.png", chart);
      fmt::print("load average after the run: {}\n", load_average());
      fmt::print("bench capture: wrote {}, {} and {}\n", csv_path.string(), plot.png.string(),
                 plot.svg.string());

      if (!opt->common.sweeps) return 0;
      const auto& pipeline = all.front();
      const auto sweep_path = opt->common.out / "sweeps.csv";
      auto sw = csv::open_with_header(sweep_path,
                                      "condition,value,frames_per_s,rms_error,rms_truth,"
                                      "median_tracked_points,passes");
      const int sweep_frames = std::min(opt->frames, 60);
      fmt::print("\nstability sweeps (bump, {} frames; failure: rms error > {} or < {} points)\n",
                 sweep_frames, opt->common.limits.max_rms, opt->common.limits.min_points);
      for (const auto& s : capture::scene_sweeps()) {
        const auto failures = capture::run_scene_sweep(
            s, pipeline, sweep_frames, opt->common.limits, [&](const capture::SceneSweepPoint& p) {
              const auto& r = p.result;
              print_row(r, fmt::format("{:<34} {:>6g} ", s.name, p.value));
              sw << fmt::format("\"{}\",{},{:.1f},{:.6g},{:.6g},{:.0f},{}\n", s.name, p.value,
                                r.frames_per_s(), r.eval.rms_error, r.eval.rms_truth,
                                r.eval.median_tracked_points, p.accurate && p.enough ? 1 : 0);
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
