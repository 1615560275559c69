#include "tactile/capture/bench_report.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

namespace tactile::capture {
namespace {

// The fields of one CSV line, honouring double quotes (no escaped quotes in these files).
std::vector<std::string> csv_fields(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else if (c != '\n') {
      out.back() += c;
    }
  }
  return out;
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

SceneBenchResult scene_result() {
  SceneBenchResult r;
  r.method = "landmarks, 2 threads";
  r.scene = Scene::hole;
  r.frames = 90;
  r.seconds = 0.3;       // 300 frames/s
  r.cpu_seconds = 0.45;  // 5 ms a frame
  r.eval.rms_error = 0.0012;
  r.eval.rms_truth = 0.05;
  r.eval.edges = 1000;
  r.eval.median_tracked_points = 480.4;
  r.eval.localisation_rms_mm = 0.0123;
  r.eval.track_count = 500;
  r.eval.median_track_frames = 88;
  return r;
}

PrintBenchRow print_row(const std::string& method, bool held_out, double fps, double rms) {
  PrintBenchRow r;
  r.print = "12";
  r.held_out = held_out;
  r.pattern = "wave-fast";
  r.strain = 0.08;
  r.method = method;
  r.frames_per_s = fps;
  r.cpu_ms_per_frame = 7.25;
  r.eval.rms_error = rms;
  r.eval.rms_truth = 0.08;
  r.eval.correlation = 0.97;
  r.eval.median_tracked_points = 150;
  r.eval.edges = 2000;
  return r;
}

TEST(CaptureBenchReport, StrainTargetsAreTheDocumentedOnes) {
  EXPECT_DOUBLE_EQ(kSceneStrainTarget, 0.005);
  EXPECT_DOUBLE_EQ(kPrintStrainTarget, 0.0025);
  EXPECT_DOUBLE_EQ(SweepLimits{}.max_rms, kSceneStrainTarget);
  EXPECT_DOUBLE_EQ(kSceneSweepLimits.max_rms, 0.005);
  EXPECT_DOUBLE_EQ(kSceneSweepLimits.min_points, 100);
  EXPECT_DOUBLE_EQ(kPrintSweepLimits.max_rms, 0.0025);
  EXPECT_DOUBLE_EQ(kPrintSweepLimits.min_points, 150);
}

TEST(CaptureBenchReport, SceneCsvRowHasEveryHeaderColumnInOrder) {
  const auto header = csv_fields(scene_bench_csv_header());
  ASSERT_EQ(header.size(), 14u);
  EXPECT_EQ(header.front(), "method");
  EXPECT_EQ(header[4], "frames_per_s");
  EXPECT_EQ(header[6], "rms_error");
  EXPECT_EQ(header.back(), "error");

  const std::string row = scene_bench_csv_row(scene_result());
  EXPECT_EQ(row.back(), '\n');
  // 90 frames in 0.3 s is 300 frames/s; 0.45 s of CPU over 90 frames is 5 ms a frame.
  const std::vector<std::string> expected = {"landmarks, 2 threads",
                                             "hole",
                                             "90",
                                             "0.3000",
                                             "300.0",
                                             "5.000",
                                             "0.0012",
                                             "0.05",
                                             "1000",
                                             "480",
                                             "0.01230",
                                             "500",
                                             "88",
                                             ""};
  EXPECT_EQ(csv_fields(row), expected);
}

TEST(CaptureBenchReport, AFailedSceneResultSaysWhyInTheTableAndTheCsv) {
  SceneBenchResult r = scene_result();
  r.error = "no landmarks";
  const std::string line = scene_bench_table_row(r);
  EXPECT_NE(line.find("failed: no landmarks"), std::string::npos) << line;
  EXPECT_EQ(line.find("300"), std::string::npos) << line;
  EXPECT_EQ(csv_fields(scene_bench_csv_row(r)).back(), "no landmarks");
}

TEST(CaptureBenchReport, SceneTableRowIsTheHeadersColumns) {
  const auto header = words(scene_bench_table_header());
  ASSERT_EQ(header.size(), 9u);
  EXPECT_EQ(header[2], "frames/s");
  // The method's name holds two words; the figures follow in the header's order.
  const std::vector<std::string> expected = {"landmarks,", "2",      "threads", "hole",
                                             "300",        "5.00",   "0.00120", "0.05000",
                                             "480",        "0.0123", "500"};
  EXPECT_EQ(words(scene_bench_table_row(scene_result())), expected);
}

TEST(CaptureBenchReport, SceneSweepRowsNameTheConditionAndWhetherItPasses) {
  SceneSweepPoint p{.value = 0.5, .result = scene_result(), .accurate = true, .enough = false};
  EXPECT_EQ(csv_fields(scene_sweep_csv_header()).size(),
            csv_fields(scene_sweep_csv_row("blur sigma (px)", p)).size());
  const std::vector<std::string> fails = {
      "blur sigma (px)", "0.5", "300.0", "0.0012", "0.05", "480", "0"};
  EXPECT_EQ(csv_fields(scene_sweep_csv_row("blur sigma (px)", p)), fails);
  p.enough = true;
  EXPECT_EQ(csv_fields(scene_sweep_csv_row("blur sigma (px)", p)).back(), "1");
  const auto line = words(scene_sweep_table_row("blur", p));
  ASSERT_GE(line.size(), 7u);
  EXPECT_EQ(line[3], "hole");
  EXPECT_EQ(line[4], "blur");
  EXPECT_EQ(line[5], "0.5");
}

TEST(CaptureBenchReport, SceneChartHasOneSeriesPerMethodWithoutFailures) {
  SceneBenchResult a = scene_result();
  a.seconds = 0.25;  // 360 frames/s
  SceneBenchResult b = scene_result();
  b.scene = Scene::bump;
  b.seconds = 0.5;  // 180 frames/s
  b.eval.rms_error = 0.003;
  SceneBenchResult failed = scene_result();
  failed.error = "threw";
  SceneBenchResult dis = scene_result();
  dis.method = "DIS flow";
  const XYChart chart = scene_bench_chart({a, failed, dis, b});
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].label, "landmarks, 2 threads");
  EXPECT_EQ(chart.series[0].x, (std::vector<double>{360, 180}));
  EXPECT_EQ(chart.series[0].y, (std::vector<double>{0.0012, 0.003}));
  EXPECT_EQ(chart.series[1].label, "DIS flow");
  EXPECT_EQ(chart.series[1].x.size(), 1u);
  ASSERT_EQ(chart.y_targets.size(), 1u);
  EXPECT_DOUBLE_EQ(chart.y_targets[0].value, 0.005);
  EXPECT_EQ(chart.y_targets[0].label, "RMS 0.005");
  EXPECT_EQ(chart.x.scale, AxisScale::log);
}

TEST(CaptureBenchReport, PrintCsvRowOfKnownFigures) {
  const auto header = csv_fields(print_bench_csv_header());
  ASSERT_EQ(header.size(), 11u);
  EXPECT_EQ(header[1], "group");
  EXPECT_EQ(header.back(), "edges");
  const std::vector<std::string> expected = {"12",       "held-out", "wave-fast", "0.08",
                                             "DIS flow", "123.46",   "0.0021",    "0.08",
                                             "0.97000",  "150",      "2000"};
  EXPECT_EQ(csv_fields(print_bench_csv_row(print_row("DIS flow", true, 123.456, 0.0021))),
            expected);
}

TEST(CaptureBenchReport, PrintTableRowsAndSummary) {
  const std::vector<std::string> row = {"12",    "tuning", "wave-fast", "8%",      "DIS",    "flow",
                                        "123.5", "7.25",   "0.00210",   "0.08000", "0.9700", "150"};
  EXPECT_EQ(words(print_bench_table_row(print_row("DIS flow", false, 123.456, 0.0021))), row);
  EXPECT_EQ(words(print_bench_table_header()).size(), 11u);

  PrintSweepPoint p{.value = 25, .row = print_row("Lucas-Kanade", true, 60, 0.004)};
  const auto sweep = words(print_sweep_table_row("exploration speed (mm/s)", p));
  ASSERT_EQ(sweep.size(), 11u);
  EXPECT_EQ(sweep[3], "25");
  EXPECT_EQ(sweep[4], "Lucas-Kanade");
  const std::vector<std::string> csv = {"exploration speed (mm/s)",
                                        "Lucas-Kanade",
                                        "25",
                                        "0.004",
                                        "0.08",
                                        "0.97000",
                                        "150",
                                        "60.00",
                                        "0"};
  EXPECT_EQ(csv_fields(print_sweep_csv_row("exploration speed (mm/s)", p)), csv);
  EXPECT_EQ(csv_fields(print_sweep_csv_header()).size(), csv.size());

  PrintBenchSummary m{.method = "landmarks (default)",
                      .held_out = true,
                      .points = 210.4,
                      .rms_error = 0.0018,
                      .correlation = 0.991,
                      .min_correlation = 0.95,
                      .frames_per_s = 41.26,
                      .cpu_ms_per_frame = 30.5};
  const std::vector<std::string> summary = {"landmarks", "(default)", "held-out", "210",  "0.00180",
                                            "0.9910",    "0.9500",    "41.3",     "30.50"};
  EXPECT_EQ(words(print_summary_table_row(m)), summary);
  EXPECT_EQ(words(print_summary_table_header()).size(), 8u);
}

TEST(CaptureBenchReport, PrintChartKeepsTuningAndHeldOutApart) {
  const XYChart chart = print_bench_chart({print_row("DIS flow", false, 50, 0.003),
                                           print_row("DIS flow", true, 40, 0.004),
                                           print_row("DIS flow", false, 45, 0.002)});
  ASSERT_EQ(chart.series.size(), 2u);
  EXPECT_EQ(chart.series[0].label, "DIS flow, tuning");
  EXPECT_EQ(chart.series[0].x, (std::vector<double>{50, 45}));
  EXPECT_EQ(chart.series[1].label, "DIS flow, held-out");
  EXPECT_EQ(chart.series[1].y, (std::vector<double>{0.004}));
  ASSERT_EQ(chart.y_targets.size(), 1u);
  EXPECT_DOUBLE_EQ(chart.y_targets[0].value, 0.0025);
  EXPECT_EQ(chart.y_targets[0].label, "RMS 0.0025");
}

TEST(CaptureBenchReport, SweepChartsTakeOnlyEveryMethodSweepsWithMeasuredEdges) {
  PrintSweepCharts charts = print_sweep_charts(0.004);
  ASSERT_EQ(charts.by_speed.y_targets.size(), 1u);
  EXPECT_DOUBLE_EQ(charts.by_speed.y_targets[0].value, 0.004);
  EXPECT_TRUE(charts.by_speed.series.empty());
  EXPECT_TRUE(charts.fps_error.series.empty());

  const auto sweep = [](const std::string& name, bool every_method) {
    PrintSweep s;
    s.name = name;
    s.every_method = every_method;
    return s;
  };
  const PrintSweep speed = sweep("exploration speed (mm/s)", true);
  const PrintSweep rate = sweep("camera rate (Hz)", true);
  const PrintSweep noise = sweep("noise sigma", false);
  PrintSweepPoint p{.value = 50, .row = print_row("DIS flow", true, 80, 0.003)};
  add_print_sweep_point(charts, speed, p);
  add_print_sweep_point(charts, noise, p);  // the pipeline alone: in neither chart
  p.value = 120;
  add_print_sweep_point(charts, rate, p);  // not a speed: frames/s chart only
  p.row.eval.edges = 0;                    // nothing measured: in neither chart
  add_print_sweep_point(charts, speed, p);

  ASSERT_EQ(charts.by_speed.series.size(), 1u);
  EXPECT_EQ(charts.by_speed.series[0].label, "DIS flow");
  EXPECT_EQ(charts.by_speed.series[0].x, (std::vector<double>{50}));
  EXPECT_EQ(charts.by_speed.series[0].y, (std::vector<double>{0.003}));
  ASSERT_EQ(charts.fps_error.series.size(), 1u);
  // Error on x, frames/s on y.
  EXPECT_EQ(charts.fps_error.series[0].x, (std::vector<double>{0.003, 0.003}));
  EXPECT_EQ(charts.fps_error.series[0].y, (std::vector<double>{80, 80}));
}

}  // namespace
}  // namespace tactile::capture
