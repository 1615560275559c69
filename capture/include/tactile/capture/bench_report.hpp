#pragma once
// What the capture benchmarks (bench.hpp) report, as text and charts built from their results:
// the terminal tables' lines, the CSV files' header and rows, and the speed-accuracy charts.
// Nothing here measures or writes a file, so the command line decides where each goes and the
// same results always read the same.
//
// Table lines and CSV rows end with a newline; a CSV header does not (csv::open_with_header adds
// it). Method and sweep names are quoted in the CSV files, as they hold spaces and commas.

#include <string>
#include <vector>

#include "tactile/capture/bench.hpp"
#include "tactile/common/chart.hpp"

namespace tactile::capture {

// ---------------------------------------------------------------- synthetic scenes

// The table's column names, and one line per result (a failed method's line says why);
// `lead` is written between the scene and the figures (a sweep's condition and value).
std::string scene_bench_table_header();
std::string scene_bench_table_row(const SceneBenchResult& r, const std::string& lead = {});
// A sweep point's line: the result led by the sweep's name and the point's value.
std::string scene_sweep_table_row(const std::string& sweep, const SceneSweepPoint& p);

// bench_capture.csv: one row per result, failures included with their error.
std::string scene_bench_csv_header();
std::string scene_bench_csv_row(const SceneBenchResult& r);

// sweeps.csv: one row per sweep point; passes = 1 when both accurate and enough.
std::string scene_sweep_csv_header();
std::string scene_sweep_csv_row(const std::string& sweep, const SceneSweepPoint& p);

// Strain error against frames per second, one series per method (its five scenes share a
// colour), failed results left out; the targets are 300 frames/s and kSceneStrainTarget.
XYChart scene_bench_chart(const std::vector<SceneBenchResult>& results);

// ---------------------------------------------------------------- real prints

// "held-out" or "tuning".
std::string print_group(bool held_out);

// The table's column names and one line per row (print, group, pattern, strain, method and
// figures).
std::string print_bench_table_header();
std::string print_bench_table_row(const PrintBenchRow& r);
// A sweep point's line: the row led by the sweep's name and the point's value.
std::string print_sweep_table_row(const std::string& sweep, const PrintSweepPoint& p);

// The summary's column names and one line per method and group.
std::string print_summary_table_header();
std::string print_summary_table_row(const PrintBenchSummary& m);

// bench_prints.csv: one row per sequence and method.
std::string print_bench_csv_header();
std::string print_bench_csv_row(const PrintBenchRow& r);

// prints_sweeps.csv: one row per sweep point and method; passes = 1 when both accurate and
// enough.
std::string print_sweep_csv_header();
std::string print_sweep_csv_row(const std::string& sweep, const PrintSweepPoint& p);

// Strain error against frames per second, one series per method and group (tuning and
// held-out apart), with kPrintStrainTarget as the goal.
XYChart print_bench_chart(const std::vector<PrintBenchRow>& rows);

// The sweeps' two charts, filled one point at a time: strain error against exploration speed
// (a line per method, `max_rms` drawn as the failure), and frames per second against strain
// error over the speed and rate sweeps.
struct PrintSweepCharts {
  XYChart by_speed;
  XYChart fps_error;
};
PrintSweepCharts print_sweep_charts(double max_rms);
// Adds the point where it belongs: only sweeps run with every method, only points with a
// measured edge, and the speed chart only from the exploration-speed sweeps.
void add_print_sweep_point(PrintSweepCharts& charts, const PrintSweep& sweep,
                           const PrintSweepPoint& p);

}  // namespace tactile::capture
