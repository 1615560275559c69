// `tactile bench prints`: strain on real skin. Every hand-marked print of a folder is moved by
// exact warps (print_warp.hpp) and measured by the landmark pipeline with its default settings
// and by the Lucas-Kanade and DIS baselines (same strain computation); tuning and held-out prints
// are reported apart. `--sweeps` pushes noise, blur, strain and speed on one held-out print until
// the pipeline fails.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "command.hpp"
#include "number_checks.hpp"
#include "sweep_failures.hpp"
#include "tactile/capture/baselines.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

using capture::PrintSequence;

struct Row {
  std::string print;
  bool held_out = false;
  std::string pattern;
  double strain = 0;
  std::string method;
  double frames_per_s = 0;
  double cpu_ms_per_frame = 0;  // every thread's CPU time: the machine may be shared
  capture::Evaluation eval;
};

capture::StrainMovie landmarks_default(const PrintSequence& seq) {
  // The settings `tactile capture` picks when given only the scale.
  capture::CaptureParams p =
      capture::with_choice({}, capture::choose_capture_settings(seq.frames[0], seq.spec.px_per_mm));
  p.min_track_frames = std::min(p.min_track_frames, seq.spec.frame_count);
  return capture::measure_strain(seq.frames, seq.calibration, seq.spec.frame_rate_hz, p);
}

capture::StrainMovie from_tracks(const std::vector<capture::Track>& tracks,
                                 const PrintSequence& seq) {
  return capture::strain_from_tracks(tracks, static_cast<int>(seq.frames.size()), seq.calibration,
                                     seq.spec.frame_rate_hz, 1,
                                     capture::CaptureParams{}.max_edge_ratio);
}

struct Method {
  std::string name;
  std::function<capture::StrainMovie(const PrintSequence&)> run;
};

std::vector<Method> methods(bool with_baselines) {
  std::vector<Method> m{{"landmarks (default)", landmarks_default}};
  if (!with_baselines) return m;
  m.push_back({"Lucas-Kanade", [](const PrintSequence& s) {
                 auto p = capture::LucasKanadeParams{};
                 p.min_track_frames = std::min(p.min_track_frames, s.spec.frame_count);
                 return from_tracks(capture::track_lucas_kanade(s.frames, s.calibration, p), s);
               }});
  m.push_back({"DIS flow", [](const PrintSequence& s) {
                 auto p = capture::DisFlowParams{};
                 p.min_track_frames = std::min(p.min_track_frames, s.spec.frame_count);
                 return from_tracks(capture::track_dis_flow(s.frames, s.calibration, p), s);
               }});
  return m;
}

capture::Evaluation evaluate(const capture::StrainMovie& movie, const PrintSequence& seq) {
  return capture::evaluate_strain(movie, capture::ground_truth_of(seq));
}

Row run(const Method& m, const PrintSequence& seq) {
  Row r;
  r.method = m.name;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t cpu0 = std::clock();
  const capture::StrainMovie movie = m.run(seq);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.frames_per_s = s > 0 ? seq.frames.size() / s : 0.0;
  r.cpu_ms_per_frame = 1e3 * static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC /
                       static_cast<double>(seq.frames.size());
  r.eval = evaluate(movie, seq);
  return r;
}

void print_row(const Row& r, const std::string& lead) {
  fmt::print("{} {:<20} {:>7.1f} {:>7.2f} {:>9.5f} {:>9.5f} {:>7.4f} {:>7.0f}\n", lead, r.method,
             r.frames_per_s, r.cpu_ms_per_frame, r.eval.rms_error, r.eval.rms_truth,
             r.eval.correlation, r.eval.median_tracked_points);
}

}  // namespace

void add_bench_prints(CLI::App& bench, Action& action) {
  struct Options {
    fs::path prints;
    fs::path out = "bench-prints";
    std::vector<std::string> held_out = {"11", "12", "13", "14", "15"};
    int frames = 30;
    double px_per_mm = 47;
    bool quick = false;
    bool sweeps = false;
    double max_rms = 0.0025;
    double min_points = 150;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = bench.add_subcommand(
      "prints",
      "Strain on real skin: each hand-marked print of PRINTS_DIR (image_NN + pores_NN.txt, e.g.\n"
      "the PolyU HRF prints in tests/data/polyu-hrf-pores) moved by exact warps (5 patterns at\n"
      "4 %, the wave also at 1 and 8 %, and 8 % crossing at 25 mm/s) and measured by the landmark "
      "pipeline with its default\n"
      "settings, Lucas-Kanade and DIS; tuning and held-out prints reported apart. Writes\n"
      "OUT/bench_prints.csv and OUT/speed_accuracy_prints.png (and .svg); --sweeps pushes noise,\n"
      "blur, strain, slide, exploration speed and camera rate on the first held-out print until\n"
      "failure (OUT/prints_sweeps.csv, accuracy_speed_prints.png, fps_accuracy_prints.png).");
  sub->add_option("PRINTS_DIR", opt->prints, "Folder of marked prints")
      ->required()
      ->check(CLI::ExistingDirectory);
  sub->add_option("--out", opt->out, "Output folder")->capture_default_str();
  sub->add_option("--held-out", opt->held_out,
                  "Numbers NN of the prints kept out of tuning (reported apart)")
      ->delimiter(',')
      ->capture_default_str();
  sub->add_option("--frames", opt->frames, "Frames per sequence")
      ->check(within(12, 1000))
      ->capture_default_str();
  sub->add_option("--px-per-mm", opt->px_per_mm, "Scale of the prints")
      ->check(within(5.0, 500.0))
      ->capture_default_str();
  sub->add_flag("--quick", opt->quick,
                "Only the 4 % wave and the fast 8 % wave, landmarks and Lucas-Kanade");
  sub->add_flag("--sweeps", opt->sweeps, "Also the stability sweeps (slow)");
  sub->add_option("--max-rms", opt->max_rms, "Sweep failure: strain RMS error above this")
      ->check(positive())
      ->capture_default_str();
  sub->add_option("--min-points", opt->min_points,
                  "Sweep failure: median tracked landmarks per frame below this")
      ->check(non_negative())
      ->capture_default_str();
  sub->callback([opt, &action] {
    action = [opt] {
      refuse_output_over_input(
          {output_folder(
              "--out", opt->out,
              {"bench_prints.csv", "speed_accuracy_prints.png", "speed_accuracy_prints.svg",
               "prints_sweeps.csv", "accuracy_speed_prints.png", "accuracy_speed_prints.svg",
               "fps_accuracy_prints.png", "fps_accuracy_prints.svg"})},
          {{"PRINTS_DIR", opt->prints}});
      const auto prints = capture::read_pore_training_prints(opt->prints);
      fs::create_directories(opt->out);
      const std::set<std::string> held(opt->held_out.begin(), opt->held_out.end());
      auto number_of = [](const std::string& name) {
        const auto stem = fs::path(name).stem().string();
        return stem.substr(stem.find('_') + 1);
      };
      struct Case {
        capture::WarpPattern pattern;
        double strain;
        double travel_mm_per_s = 0;  // > 0: the fast scene (see fast_scene)
      };
      std::vector<Case> cases{{capture::WarpPattern::wave, 0.04},
                              {capture::WarpPattern::wave, 0.08, 25}};
      if (!opt->quick) {
        cases = {{capture::WarpPattern::rigid, 0.04},    {capture::WarpPattern::stretch, 0.04},
                 {capture::WarpPattern::compress, 0.04}, {capture::WarpPattern::bump, 0.04},
                 {capture::WarpPattern::wave, 0.01},     {capture::WarpPattern::wave, 0.04},
                 {capture::WarpPattern::wave, 0.08},     {capture::WarpPattern::wave, 0.08, 25}};
      }
      const auto all = methods(true);
      const std::size_t used = opt->quick ? 2 : all.size();
      // A strain pattern crossing at the speed of touch, filmed as a camera does: a 2 ms
      // exposure, each pixel integrated over its area, the finger sliding at 2.5 mm/s and
      // turning 3 degrees.
      auto fast_scene = [](capture::PrintWarpSpec& s, double travel_mm_per_s) {
        s.travel_speed_mm_per_s = travel_mm_per_s;
        s.slide_x_mm = 2.5 * capture::sequence_duration_s(s);
        s.slide_y_mm = 0;
        s.rotation_deg = 3;
        s.exposure_s = std::min(0.002, 1 / s.frame_rate_hz);
        s.supersample = 2;
      };
      auto spec_for = [&](const capture::PoreTrainingPrint& p) {
        capture::PrintWarpSpec s;
        s.source = p.name;
        s.px_per_mm = opt->px_per_mm;
        s.width_px = p.image.width_px;
        s.height_px = p.image.height_px;
        s.frame_count = opt->frames;
        return s;
      };
      fmt::print("{:<6} {:<8} {:<10} {:>5} {:<20} {:>7} {:>7} {:>9} {:>9} {:>7} {:>7}\n", "print",
                 "group", "pattern", "strain", "method", "frames/s", "cpu_ms", "rms_err",
                 "rms_true", "corr", "points");
      std::vector<Row> rows;
      for (const auto& p : prints) {
        const std::string nn = number_of(p.name);
        for (const auto& c : cases) {
          auto spec = spec_for(p);
          spec.pattern = c.pattern;
          spec.strain = c.strain;
          if (c.travel_mm_per_s > 0) fast_scene(spec, c.travel_mm_per_s);
          const PrintSequence seq = capture::render_print_sequence(spec, p.image, p.pores_px);
          for (std::size_t k = 0; k < used; ++k) {
            Row r = run(all[k], seq);
            r.print = nn;
            r.held_out = held.count(nn) > 0;
            r.pattern =
                std::string(capture::to_string(c.pattern)) + (c.travel_mm_per_s > 0 ? "-fast" : "");
            r.strain = c.strain;
            print_row(r,
                      fmt::format("{:<6} {:<8} {:<10} {:>4.0f}%", nn,
                                  r.held_out ? "held-out" : "tuning", r.pattern, 100 * c.strain));
            rows.push_back(r);
          }
        }
      }

      // Summary per method and group; the rigid warp has no strain, so no correlation.
      fmt::print("\nsummary (medians over sequences; correlation over the non-rigid ones)\n");
      fmt::print("{:<20} {:<8} {:>7} {:>9} {:>8} {:>8} {:>10} {:>7}\n", "method", "group", "points",
                 "rms_err", "corr", "min_corr", "frames/s", "cpu_ms");
      for (std::size_t k = 0; k < used; ++k) {
        for (const bool h : {false, true}) {
          std::vector<double> pts, rms, corr, fps, cpu;
          for (const auto& r : rows) {
            if (r.method != all[k].name || r.held_out != h) continue;
            pts.push_back(r.eval.median_tracked_points);
            rms.push_back(r.eval.rms_error);
            fps.push_back(r.frames_per_s);
            cpu.push_back(r.cpu_ms_per_frame);
            if (r.pattern != "rigid") corr.push_back(r.eval.correlation);
          }
          if (pts.empty()) continue;
          fmt::print("{:<20} {:<8} {:>7.0f} {:>9.5f} {:>8.4f} {:>8.4f} {:>10.1f} {:>7.2f}\n",
                     all[k].name, h ? "held-out" : "tuning", median(pts), median(rms), median(corr),
                     corr.empty() ? 0.0 : *std::min_element(corr.begin(), corr.end()), median(fps),
                     median(cpu));
        }
      }

      const auto csv_path = opt->out / "bench_prints.csv";
      auto csv = csv::open_with_header(
          csv_path,
          "print,group,pattern,strain,method,frames_per_s,rms_error,rms_truth,correlation,"
          "median_tracked_points,edges");
      XYChart chart{.title = "Strain on real prints under exact warps",
                    .x = {.label = "frames per second (whole pipeline)", .scale = AxisScale::log},
                    .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                    .y_targets = {{.value = 0.0025, .label = "RMS 0.0025"}},
                    .width = 960,
                    .height = 600};
      for (const auto& r : rows) {
        csv << fmt::format("{},{},{},{},\"{}\",{:.2f},{:.6g},{:.6g},{:.5f},{:.0f},{}\n", r.print,
                           r.held_out ? "held-out" : "tuning", r.pattern, r.strain, r.method,
                           r.frames_per_s, r.eval.rms_error, r.eval.rms_truth, r.eval.correlation,
                           r.eval.median_tracked_points, r.eval.edges);
        const std::string label = r.method + (r.held_out ? ", held-out" : ", tuning");
        auto it = std::find_if(chart.series.begin(), chart.series.end(),
                               [&](const ChartSeries& s) { return s.label == label; });
        if (it == chart.series.end()) it = chart.series.insert(it, {.label = label});
        it->x.push_back(r.frames_per_s);
        it->y.push_back(r.eval.rms_error);
      }
      csv::finish(csv, csv_path);
      const ChartFiles plot = write_scatter_chart(opt->out / "speed_accuracy_prints.png", chart);
      fmt::print("bench prints: wrote {}, {} and {}\n", csv_path.string(), plot.png.string(),
                 plot.svg.string());
      if (!opt->sweeps) return 0;

      const auto first_held = std::find_if(prints.begin(), prints.end(), [&](const auto& p) {
        return held.count(number_of(p.name)) > 0;
      });
      const auto& print = first_held != prints.end() ? *first_held : prints.front();
      struct Sweep {
        std::string name;
        std::vector<double> values;
        std::function<void(capture::PrintWarpSpec&, double)> apply;
        bool every_method = false;  // the pipeline, Lucas-Kanade and DIS, each to its failure
      };
      const std::vector<Sweep> sweeps = {
          {"noise (grey levels)",
           {2, 4, 8, 12, 16, 24, 32},
           [](auto& s, double v) { s.noise_sigma = v; }},
          {"blur (px)",
           {0.7, 1.0, 1.5, 2.0, 3.0, 4.0},
           [](auto& s, double v) { s.blur_sigma_px = v; }},
          {"strain (%)", {1, 2, 4, 8, 12, 16, 20}, [](auto& s, double v) { s.strain = v / 100; }},
          {"slide over the sequence (mm)",
           {0.25, 0.5, 1, 2, 3, 5},
           [](auto& s, double v) { s.slide_x_mm = v; }},
          // The fast scene (8 % wave) at rising exploration speed, camera at 60 Hz ...
          {"exploration speed at 60 Hz (mm/s)",
           {5, 10, 15, 20, 25, 35, 50, 70, 100},
           [&](auto& s, double v) {
             s.strain = 0.08;
             fast_scene(s, v);
           },
           true},
          // ... and at 25 mm/s with a slower and slower camera.
          {"camera rate at 25 mm/s (Hz)",
           {240, 120, 90, 60, 45, 30, 20},
           [&](auto& s, double v) {
             s.strain = 0.08;
             s.frame_rate_hz = v;
             fast_scene(s, 25);
           },
           true},
      };
      const auto sweep_path = opt->out / "prints_sweeps.csv";
      auto sw = csv::open_with_header(sweep_path,
                                      "condition,method,value,rms_error,rms_truth,correlation,"
                                      "median_tracked_points,frames_per_s,"
                                      "passes");
      fmt::print(
          "\nstability sweeps ({} wave 4 %, {} frames; failure: rms error > {} or < {} "
          "points)\n",
          print.name, opt->frames, opt->max_rms, opt->min_points);
      // Accuracy against exploration speed, and frames/s against accuracy, for every method.
      XYChart by_speed{.title = "Strain error at the speed of touch (8 % wave, 60 Hz)",
                       .x = {.label = "exploration speed (mm/s)"},
                       .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                       .y_targets = {{.value = opt->max_rms, .label = "failure"}},
                       .width = 960,
                       .height = 600};
      XYChart fps_error{.title = "Frames per second against strain error (speed and rate sweeps)",
                        .x = {.label = "edge strain RMS error", .scale = AxisScale::log},
                        .y = {.label = "frames per second", .scale = AxisScale::log},
                        .width = 960,
                        .height = 600};
      auto add_point = [](XYChart& chart, const std::string& label, double x, double y) {
        auto it = std::find_if(chart.series.begin(), chart.series.end(),
                               [&](const ChartSeries& c) { return c.label == label; });
        if (it == chart.series.end())
          it = chart.series.insert(chart.series.end(), {.label = label});
        it->x.push_back(x);
        it->y.push_back(y);
      };
      for (const auto& s : sweeps) {
        const std::size_t method_count = s.every_method ? all.size() : 1;
        for (std::size_t k = 0; k < method_count; ++k) {
          SweepFailures failures;
          for (const double v : s.values) {
            auto spec = spec_for(print);
            s.apply(spec, v);
            const Row r = run(all[k], capture::render_print_sequence(spec, print.image, {}));
            const bool accurate = r.eval.edges > 0 && r.eval.rms_error <= opt->max_rms;
            const bool enough = r.eval.median_tracked_points >= opt->min_points;
            print_row(r, fmt::format("{:<34} {:>6g}", s.name, v));
            sw << fmt::format("\"{}\",\"{}\",{},{:.6g},{:.6g},{:.5f},{:.0f},{:.2f},{}\n", s.name,
                              r.method, v, r.eval.rms_error, r.eval.rms_truth, r.eval.correlation,
                              r.eval.median_tracked_points, r.frames_per_s,
                              accurate && enough ? 1 : 0);
            if (s.every_method && r.eval.edges > 0) {
              if (s.name.rfind("exploration", 0) == 0) {
                add_point(by_speed, r.method, v, r.eval.rms_error);
              }
              add_point(fps_error, r.method, r.eval.rms_error, r.frames_per_s);
            }
            failures.note(v, accurate, enough);
            if (failures.both_failed()) break;
          }
          fmt::print("{}", failures.summary(s.name + ", " + all[k].name, s.values.back()));
        }
      }
      const ChartFiles speed_plot =
          write_line_chart(opt->out / "accuracy_speed_prints.png", by_speed);
      const ChartFiles fps_plot =
          write_scatter_chart(opt->out / "fps_accuracy_prints.png", fps_error);
      fmt::print("bench prints: wrote {}, {}\n", speed_plot.png.string(), fps_plot.png.string());
      csv::finish(sw, sweep_path);
      fmt::print("bench prints: wrote {}\n", sweep_path.string());
      return 0;
    };
  });
}

}  // namespace tactile::cli
