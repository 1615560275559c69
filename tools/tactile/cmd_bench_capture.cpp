// `tactile bench capture`: throughput and accuracy of the strain measurement on synthetic
// sequences with exact ground truth, for the landmark pipeline at a few settings and for the
// Lucas-Kanade and DIS optical-flow baselines (same strain computation): a table, a CSV and the
// speed-accuracy chart. `--sweeps` pushes noise, blur, contrast, speed, pore size and loss of
// contact until the pipeline fails and reports where.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "command.hpp"
#include "number_checks.hpp"
#include "sweep_failures.hpp"
#include "tactile/capture/baselines.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/stopwatch.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

using Frames = std::vector<capture::GrayImage>;
using Method =
    std::function<capture::StrainMovie(const Frames&, const capture::Calibration&, double rate_hz)>;

struct NamedMethod {
  std::string name;
  Method run;
};

capture::StrainMovie from_tracks(const std::vector<capture::Track>& tracks, const Frames& frames,
                                 const capture::Calibration& c, double rate_hz) {
  const capture::CaptureParams defaults;
  return capture::strain_from_tracks(tracks, static_cast<int>(frames.size()), c, rate_hz, 1,
                                     defaults.max_edge_ratio);
}

std::vector<NamedMethod> methods(bool quick) {
  std::vector<NamedMethod> m;
  auto pipeline = [](capture::CaptureParams p) {
    return [p](const Frames& f, const capture::Calibration& c, double rate) {
      return capture::measure_strain(f, c, rate, p);
    };
  };
  m.push_back({"pores, 2 threads", pipeline({})});
  capture::CaptureParams one_thread;
  one_thread.threads = 1;
  m.push_back({"pores, 1 thread", pipeline(one_thread)});
  if (!quick) {
    capture::CaptureParams optimal;
    optimal.assignment = capture::Assignment::optimal;
    m.push_back({"pores, optimal match", pipeline(optimal)});
    capture::CaptureParams with_minutiae;
    with_minutiae.features.find_minutiae = true;
    m.push_back({"pores + minutiae", pipeline(with_minutiae)});
    // The ridge-blob pore detector (trained on real 1200 dpi prints) is left out: at about
    // 3 frames/s on 640 x 484 it is a detector for single images, not for sequences.
  }
  m.push_back({"Lucas-Kanade", [](const Frames& f, const capture::Calibration& c, double rate) {
                 return from_tracks(capture::track_lucas_kanade(f, c), f, c, rate);
               }});
  m.push_back({"DIS flow", [](const Frames& f, const capture::Calibration& c, double rate) {
                 return from_tracks(capture::track_dis_flow(f, c), f, c, rate);
               }});
  return m;
}

std::string load_average() {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) != 3) return "unknown";
  return fmt::format("{:.1f} {:.1f} {:.1f}", load[0], load[1], load[2]);
}

struct Result {
  std::string method;
  std::string scene;
  int frames = 0;
  double seconds = 0;
  double cpu_seconds = 0;
  capture::Evaluation eval;
  std::string error;  // a method that throws is a failure, not a crash of the benchmark
};

double frames_per_s(const Result& r) {
  return r.seconds > 0 ? r.frames / r.seconds : 0.0;
}

double cpu_ms_per_frame(const Result& r) {
  return r.frames > 0 ? 1e3 * r.cpu_seconds / r.frames : 0.0;
}

Result run(const NamedMethod& m, const capture::SyntheticSequence& seq) {
  Result r{m.name, seq.spec.scene, static_cast<int>(seq.frames.size()), 0, 0, {}, {}};
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = process_cpu_s();
    const capture::StrainMovie movie = m.run(seq.frames, seq.calibration, seq.spec.frame_rate_hz);
    r.cpu_seconds = process_cpu_s() - c0;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.eval = capture::evaluate_strain(movie, {seq.spec, seq.calibration, seq.landmarks, {}});
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

void print_row(const Result& r, const std::string& extra = {}) {
  if (!r.error.empty()) {
    fmt::print("{:<20} {:<15} {}failed: {}\n", r.method, r.scene, extra, r.error);
    return;
  }
  fmt::print("{:<20} {:<15} {}{:>8.0f} {:>8.2f} {:>9.5f} {:>9.5f} {:>7.0f} {:>7.4f} {:>6}\n",
             r.method, r.scene, extra, frames_per_s(r), cpu_ms_per_frame(r), r.eval.rms_error,
             r.eval.rms_truth, r.eval.median_tracked_points, r.eval.localisation_rms_mm,
             r.eval.track_count);
}

struct Sweep {
  std::string name;
  std::vector<double> values;
  std::function<void(capture::SceneSpec&, double)> apply;
};

std::vector<Sweep> sweeps() {
  return {
      {"noise (grey levels)",
       {2, 4, 8, 12, 16, 24, 32, 48},
       [](capture::SceneSpec& s, double v) { s.noise_sigma = v; }},
      {"blur (px)",
       {0.9, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0},
       [](capture::SceneSpec& s, double v) { s.blur_sigma_px = v; }},
      {"contrast",
       {1.0, 0.6, 0.4, 0.25, 0.15, 0.1, 0.05},
       [](capture::SceneSpec& s, double v) { s.contrast = v; }},
      {"speed (mm/s)",
       {2.4, 5, 10, 20, 30, 40, 60},
       [](capture::SceneSpec& s, double v) { s.speed_mm_per_s = v; }},
      {"pore size (x nominal)",
       {1.0, 0.75, 0.6, 0.5, 0.4, 0.3},
       [](capture::SceneSpec& s, double v) {
         s.pore_min_diameter_mm *= v;
         s.pore_max_diameter_mm *= v;
       }},
      {"bump height (mm), loss of contact",
       {0.5, 1.0, 1.5, 2.0, 2.5, 3.0},
       [](capture::SceneSpec& s, double v) { s.feature_height_mm = v; }},
      {"contact patch size (x nominal)",
       {1.0, 0.8, 0.6, 0.5, 0.4, 0.3},
       [](capture::SceneSpec& s, double v) {
         s.contact_semi_x_mm *= v;
         s.contact_semi_y_mm *= v;
       }},
  };
}

}  // namespace

void add_bench_capture(CLI::App& bench, Action& action) {
  struct Options {
    int frames = 90;
    fs::path out = "bench-capture";
    bool sweeps = false;
    bool quick = false;
    double max_rms = 0.005;
    double min_points = 100;
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
  sub->add_option("--out", opt->out, "Output folder")->capture_default_str();
  sub->add_flag("--sweeps", opt->sweeps, "Also run the stability sweeps (slow)");
  sub->add_flag("--quick", opt->quick, "Only the default pipeline and the two baselines");
  sub->add_option("--max-rms", opt->max_rms, "Sweep failure: strain RMS error above this")
      ->check(positive())
      ->capture_default_str();
  sub->add_option("--min-points", opt->min_points,
                  "Sweep failure: median tracked landmarks per frame below this")
      ->check(non_negative())
      ->capture_default_str();
  sub->callback([opt, &action] {
    action = [opt] {
      fs::create_directories(opt->out);
      const auto all = methods(opt->quick);
      std::vector<Result> results;
      fmt::print("load average before the run: {} ({} cores)\n", load_average(),
                 std::thread::hardware_concurrency());
      fmt::print("{:<20} {:<15} {:>8} {:>8} {:>9} {:>9} {:>7} {:>7} {:>6}\n", "method", "scene",
                 "frames/s", "cpu_ms/f", "rms_err", "rms_true", "points", "loc_mm", "tracks");
      for (const std::string& scene : capture::scene_names()) {
        capture::SceneSpec spec;
        spec.scene = scene;
        spec.frame_count = opt->frames;
        const auto seq = capture::render_sequence(spec);
        for (const auto& m : all) {
          results.push_back(run(m, seq));
          print_row(results.back());
        }
      }
      const auto csv_path = opt->out / "bench_capture.csv";
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
            r.method, r.scene, r.frames, r.seconds, frames_per_s(r), cpu_ms_per_frame(r),
            r.eval.rms_error, r.eval.rms_truth, r.eval.edges, r.eval.median_tracked_points,
            r.eval.localisation_rms_mm, r.eval.track_count, r.eval.median_track_frames, r.error);
        if (!r.error.empty()) continue;
        // One series per method, so that a method's five scenes share a colour.
        auto it = std::find_if(chart.series.begin(), chart.series.end(),
                               [&](const ChartSeries& s) { return s.label == r.method; });
        if (it == chart.series.end()) it = chart.series.insert(it, {.label = r.method});
        it->x.push_back(frames_per_s(r));
        it->y.push_back(r.eval.rms_error);
      }
      csv::finish(csv, csv_path);
      const ChartFiles plot = write_scatter_chart(opt->out / "speed_accuracy.png", chart);
      fmt::print("load average after the run: {}\n", load_average());
      fmt::print("bench capture: wrote {}, {} and {}\n", csv_path.string(), plot.png.string(),
                 plot.svg.string());

      if (!opt->sweeps) return 0;
      const NamedMethod pipeline = all.front();
      const auto sweep_path = opt->out / "sweeps.csv";
      auto sw = csv::open_with_header(sweep_path,
                                      "condition,value,frames_per_s,rms_error,rms_truth,"
                                      "median_tracked_points,passes");
      const int sweep_frames = std::min(opt->frames, 60);
      fmt::print("\nstability sweeps (bump, {} frames; failure: rms error > {} or < {} points)\n",
                 sweep_frames, opt->max_rms, opt->min_points);
      for (const auto& s : sweeps()) {
        SweepFailures failures;
        for (double v : s.values) {
          capture::SceneSpec spec;
          spec.frame_count = sweep_frames;
          s.apply(spec, v);
          Result r;
          try {
            r = run(pipeline, capture::render_sequence(spec));
          } catch (const std::exception& e) {
            r.error = e.what();
          }
          r.scene = "bump";
          r.frames = sweep_frames;
          const bool accurate =
              r.error.empty() && r.eval.edges > 0 && r.eval.rms_error <= opt->max_rms;
          const bool enough = r.error.empty() && r.eval.median_tracked_points >= opt->min_points;
          print_row(r, fmt::format("{:<34} {:>6g} ", s.name, v));
          sw << fmt::format("\"{}\",{},{:.1f},{:.6g},{:.6g},{:.0f},{}\n", s.name, v,
                            frames_per_s(r), r.eval.rms_error, r.eval.rms_truth,
                            r.eval.median_tracked_points, accurate && enough ? 1 : 0);
          failures.note(v, accurate, enough);
          if (failures.both_failed()) break;
        }
        fmt::print("{}", failures.summary(s.name, s.values.back()));
      }
      csv::finish(sw, sweep_path);
      fmt::print("bench capture: wrote {}\n", sweep_path.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
