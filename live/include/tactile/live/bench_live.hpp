#pragma once
// The live session measured: latency and drops against frame size and camera rate, and the
// accuracy of its causal strain against the exact truth and against the batch capture of the
// same frames. Each case is a real print mirrored to the frame size and moved by the fast
// scene (an 8 % wave crossing at the speed of touch, filmed with a 2 ms exposure while the
// finger slides and turns), held in memory and handed to the session at the camera's rate as a
// camera would (no file decoding), played into the emulated display on the real clock.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/pore_training.hpp"
#include "tactile/common/chart.hpp"
#include "tactile/live/live_session.hpp"

namespace tactile::live {

struct LiveBenchCase {
  int width_px = 320;
  int height_px = 240;
  double camera_rate_hz = 60;
};

// 320 x 240 and 640 x 484, each at 30, 60, 120 and 240 Hz (quick: both sizes at 60 Hz and
// 320 x 240 at 120 Hz).
std::vector<LiveBenchCase> live_bench_cases(bool quick);

// A case written as WIDTHxHEIGHT@RATE (e.g. "640x484@60"); throws std::invalid_argument naming
// what is wrong (the form, or a size out of 64-4096 px or a rate out of 1-1000 Hz).
LiveBenchCase parse_live_bench_case(const std::string& text);

struct LiveBenchOptions {
  double seconds = 10;          // of skin per case
  double travel_mm_per_s = 25;  // the wave's speed across the contact
  double strain = 0.08;         // the wave's peak strain
  double px_per_mm = 47;        // the prints' scale
  std::vector<LiveBenchCase> cases = live_bench_cases(false);
  // The rate the frames are handed to the session at; unset: the case's camera rate. The scene
  // is filmed at the case's rate either way: a slower hand-over (a test under sanitizers) drops
  // no frame where the processing is slower than the camera, and measures accuracy only.
  std::optional<double> delivery_rate_hz;
};

struct LiveBenchRow {
  LiveBenchCase scene;
  LiveSummary summary;        // frames, drops, latency by stage
  capture::Evaluation live;   // the session's strain against the truth
  capture::Evaluation batch;  // `tactile capture`'s defaults on the same frames
};

// Every case on `print` in order; on_row sees each row as soon as it is measured. Throws
// std::invalid_argument for options out of range.
std::vector<LiveBenchRow> bench_live(const capture::PoreTrainingPrint& print,
                                     const LiveBenchOptions& options,
                                     const std::function<void(const LiveBenchRow&)>& on_row);

// What the bench reports, built from its rows as plain text and a chart description (the
// command line prints them and writes the files): the table's column names and one line per row
// (ratio: the live strain error over the batch's), the CSV header (without its newline) and rows,
// and latency p99 against the live strain error, a series per frame size, with
// capture::kPrintStrainTarget as the goal.
std::string live_bench_table_header();
std::string live_bench_table_row(const LiveBenchRow& row);
std::string live_bench_csv_header();
std::string live_bench_csv_row(const LiveBenchRow& row);
XYChart live_bench_chart(const std::vector<LiveBenchRow>& rows);

}  // namespace tactile::live
