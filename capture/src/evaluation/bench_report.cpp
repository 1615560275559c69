#include "tactile/capture/bench_report.hpp"

#include <fmt/format.h>

namespace tactile::capture {

// ---------------------------------------------------------------- synthetic scenes

std::string scene_bench_table_header() {
  return fmt::format("{:<20} {:<15} {:>8} {:>8} {:>9} {:>9} {:>7} {:>7} {:>6}\n", "method", "scene",
                     "frames/s", "cpu_ms/f", "rms_err", "rms_true", "points", "loc_mm", "tracks");
}

std::string scene_bench_table_row(const SceneBenchResult& r, const std::string& lead) {
  if (!r.error.empty()) {
    return fmt::format("{:<20} {:<15} {}failed: {}\n", r.method, to_string(r.scene), lead, r.error);
  }
  return fmt::format(
      "{:<20} {:<15} {}{:>8.0f} {:>8.2f} {:>9.5f} {:>9.5f} {:>7.0f} {:>7.4f} {:>6}\n", r.method,
      to_string(r.scene), lead, r.frames_per_s(), r.cpu_ms_per_frame(), r.eval.rms_error,
      r.eval.rms_truth, r.eval.median_tracked_points, r.eval.localisation_rms_mm,
      r.eval.track_count);
}

std::string scene_sweep_table_row(const std::string& sweep, const SceneSweepPoint& p) {
  return scene_bench_table_row(p.result, fmt::format("{:<34} {:>6g} ", sweep, p.value));
}

std::string scene_bench_csv_header() {
  return "method,scene,frames,seconds,frames_per_s,cpu_ms_per_frame,rms_error,rms_truth,edges,"
         "median_tracked_points,localisation_rms_mm,track_count,median_track_frames,error";
}

std::string scene_bench_csv_row(const SceneBenchResult& r) {
  return fmt::format(
      "\"{}\",{},{},{:.4f},{:.1f},{:.3f},{:.6g},{:.6g},{},{:.0f},{:.5f},{},{:.0f},\"{}\"\n",
      r.method, to_string(r.scene), r.frames, r.seconds, r.frames_per_s(), r.cpu_ms_per_frame(),
      r.eval.rms_error, r.eval.rms_truth, r.eval.edges, r.eval.median_tracked_points,
      r.eval.localisation_rms_mm, r.eval.track_count, r.eval.median_track_frames, r.error);
}

std::string scene_sweep_csv_header() {
  return "condition,value,frames_per_s,rms_error,rms_truth,median_tracked_points,passes";
}

std::string scene_sweep_csv_row(const std::string& sweep, const SceneSweepPoint& p) {
  const auto& r = p.result;
  return fmt::format("\"{}\",{},{:.1f},{:.6g},{:.6g},{:.0f},{}\n", sweep, p.value, r.frames_per_s(),
                     r.eval.rms_error, r.eval.rms_truth, r.eval.median_tracked_points,
                     p.accurate && p.enough ? 1 : 0);
}

XYChart scene_bench_chart(const std::vector<SceneBenchResult>& results) {
  XYChart chart{.title = "Strain from the five synthetic scenes (640 x 484)",
                .x = {.label = "frames per second (extract + match + track + strain)",
                      .scale = AxisScale::log},
                .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                .x_targets = {{.value = 300, .label = "300 frames/s"}},
                .y_targets = {{.value = kSceneStrainTarget,
                               .label = fmt::format("RMS {:g}", kSceneStrainTarget)}},
                .width = 960,
                .height = 600};
  for (const auto& r : results) {
    if (r.error.empty()) add_point(chart, r.method, r.frames_per_s(), r.eval.rms_error);
  }
  return chart;
}

// ---------------------------------------------------------------- real prints

std::string print_group(bool held_out) {
  return held_out ? "held-out" : "tuning";
}

namespace {

std::string print_figures(const PrintBenchRow& r) {
  return fmt::format("{:<20} {:>7.1f} {:>7.2f} {:>9.5f} {:>9.5f} {:>7.4f} {:>7.0f}\n", r.method,
                     r.frames_per_s, r.cpu_ms_per_frame, r.eval.rms_error, r.eval.rms_truth,
                     r.eval.correlation, r.eval.median_tracked_points);
}

}  // namespace

std::string print_bench_table_header() {
  return fmt::format("{:<6} {:<8} {:<10} {:>5} {:<20} {:>7} {:>7} {:>9} {:>9} {:>7} {:>7}\n",
                     "print", "group", "pattern", "strain", "method", "frames/s", "cpu_ms",
                     "rms_err", "rms_true", "corr", "points");
}

std::string print_bench_table_row(const PrintBenchRow& r) {
  return fmt::format("{:<6} {:<8} {:<10} {:>4.0f}% ", r.print, print_group(r.held_out), r.pattern,
                     100 * r.strain) +
         print_figures(r);
}

std::string print_sweep_table_row(const std::string& sweep, const PrintSweepPoint& p) {
  return fmt::format("{:<34} {:>6g} ", sweep, p.value) + print_figures(p.row);
}

std::string print_summary_table_header() {
  return fmt::format("{:<20} {:<8} {:>7} {:>9} {:>8} {:>8} {:>10} {:>7}\n", "method", "group",
                     "points", "rms_err", "corr", "min_corr", "frames/s", "cpu_ms");
}

std::string print_summary_table_row(const PrintBenchSummary& m) {
  return fmt::format("{:<20} {:<8} {:>7.0f} {:>9.5f} {:>8.4f} {:>8.4f} {:>10.1f} {:>7.2f}\n",
                     m.method, print_group(m.held_out), m.points, m.rms_error, m.correlation,
                     m.min_correlation, m.frames_per_s, m.cpu_ms_per_frame);
}

std::string print_bench_csv_header() {
  return "print,group,pattern,strain,method,frames_per_s,rms_error,rms_truth,correlation,"
         "median_tracked_points,edges";
}

std::string print_bench_csv_row(const PrintBenchRow& r) {
  return fmt::format("{},{},{},{},\"{}\",{:.2f},{:.6g},{:.6g},{:.5f},{:.0f},{}\n", r.print,
                     print_group(r.held_out), r.pattern, r.strain, r.method, r.frames_per_s,
                     r.eval.rms_error, r.eval.rms_truth, r.eval.correlation,
                     r.eval.median_tracked_points, r.eval.edges);
}

std::string print_sweep_csv_header() {
  return "condition,method,value,rms_error,rms_truth,correlation,median_tracked_points,"
         "frames_per_s,passes";
}

std::string print_sweep_csv_row(const std::string& sweep, const PrintSweepPoint& p) {
  const auto& r = p.row;
  return fmt::format("\"{}\",\"{}\",{},{:.6g},{:.6g},{:.5f},{:.0f},{:.2f},{}\n", sweep, r.method,
                     p.value, r.eval.rms_error, r.eval.rms_truth, r.eval.correlation,
                     r.eval.median_tracked_points, r.frames_per_s, p.accurate && p.enough ? 1 : 0);
}

XYChart print_bench_chart(const std::vector<PrintBenchRow>& rows) {
  XYChart chart{.title = "Strain on real prints under exact warps",
                .x = {.label = "frames per second (whole pipeline)", .scale = AxisScale::log},
                .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                .y_targets = {{.value = kPrintStrainTarget,
                               .label = fmt::format("RMS {:g}", kPrintStrainTarget)}},
                .width = 960,
                .height = 600};
  for (const auto& r : rows) {
    add_point(chart, r.method + ", " + print_group(r.held_out), r.frames_per_s, r.eval.rms_error);
  }
  return chart;
}

PrintSweepCharts print_sweep_charts(double max_rms) {
  return {.by_speed = {.title = "Strain error at the speed of touch (8 % wave, 60 Hz)",
                       .x = {.label = "exploration speed (mm/s)"},
                       .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                       .y_targets = {{.value = max_rms, .label = "failure"}},
                       .width = 960,
                       .height = 600},
          .fps_error = {.title = "Frames per second against strain error (speed and rate sweeps)",
                        .x = {.label = "edge strain RMS error", .scale = AxisScale::log},
                        .y = {.label = "frames per second", .scale = AxisScale::log},
                        .width = 960,
                        .height = 600}};
}

void add_print_sweep_point(PrintSweepCharts& charts, const PrintSweep& sweep,
                           const PrintSweepPoint& p) {
  const auto& r = p.row;
  if (!sweep.every_method || r.eval.edges <= 0) return;
  if (sweep.name.starts_with("exploration")) {
    add_point(charts.by_speed, r.method, p.value, r.eval.rms_error);
  }
  add_point(charts.fps_error, r.method, r.eval.rms_error, r.frames_per_s);
}

}  // namespace tactile::capture
