// The live session's bench; see bench_live.hpp.

#include "tactile/live/bench_live.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "live_source.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/track.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/live/live_request.hpp"

namespace tactile::live {

std::vector<LiveBenchCase> live_bench_cases(bool quick) {
  if (quick) return {{320, 240, 60}, {320, 240, 120}, {640, 484, 60}};
  std::vector<LiveBenchCase> cases;
  for (const auto& [w, h] : {std::pair{320, 240}, std::pair{640, 484}}) {
    for (const double rate : {30.0, 60.0, 120.0, 240.0}) cases.push_back({w, h, rate});
  }
  return cases;
}

namespace {

bool case_in_range(const LiveBenchCase& c) {
  return c.width_px >= 64 && c.width_px <= 4096 && c.height_px >= 64 && c.height_px <= 4096 &&
         std::isfinite(c.camera_rate_hz) && c.camera_rate_hz >= 1 && c.camera_rate_hz <= 1000;
}

std::string case_range_error(const LiveBenchCase& c) {
  return fmt::format(
      "case {} x {} px at {:g} Hz: sizes must be from 64 to 4096 px, rates from 1 to 1000 Hz",
      c.width_px, c.height_px, c.camera_rate_hz);
}

}  // namespace

LiveBenchCase parse_live_bench_case(const std::string& text) {
  const std::size_t x = text.find('x');
  const std::size_t at = text.find('@');
  LiveBenchCase c;
  // from_chars: no locale, no overflow into a wrapped number, and the whole field must be read.
  const auto whole = [&](std::size_t from, std::size_t to, auto& value) {
    const char* end = text.data() + to;
    const auto [ptr, ec] = std::from_chars(text.data() + from, end, value);
    return from < to && ec == std::errc() && ptr == end;
  };
  if (x == std::string::npos || at == std::string::npos || at < x || !whole(0, x, c.width_px) ||
      !whole(x + 1, at, c.height_px) || !whole(at + 1, text.size(), c.camera_rate_hz)) {
    throw std::invalid_argument(
        fmt::format("case '{}': expected WIDTHxHEIGHT@RATE, e.g. 640x484@60 (pixels, Hz)", text));
  }
  if (!case_in_range(c)) throw std::invalid_argument(case_range_error(c));
  return c;
}

namespace {

void check(const LiveBenchOptions& o) {
  const auto in = [](double v, double lo, double hi) {
    return std::isfinite(v) && v >= lo && v <= hi;
  };
  if (!in(o.seconds, 0.5, 600)) {
    throw std::invalid_argument(
        fmt::format("seconds: {} is out of range: must be from 0.5 to 600", o.seconds));
  }
  if (!in(o.travel_mm_per_s, 1, 500)) {
    throw std::invalid_argument(
        fmt::format("travel: {} mm/s is out of range: must be from 1 to 500", o.travel_mm_per_s));
  }
  if (!in(o.strain, 0.001, 0.2)) {
    throw std::invalid_argument(
        fmt::format("strain: {} is out of range: must be from 0.001 to 0.2", o.strain));
  }
  if (o.cases.empty()) throw std::invalid_argument("no cases to measure");
  if (o.delivery_rate_hz && !in(*o.delivery_rate_hz, 1, 1000)) {
    throw std::invalid_argument(fmt::format(
        "delivery rate: {} Hz is out of range: must be from 1 to 1000", *o.delivery_rate_hz));
  }
  for (const auto& c : o.cases) {
    if (!case_in_range(c)) throw std::invalid_argument(case_range_error(c));
  }
}

}  // namespace

std::vector<LiveBenchRow> bench_live(const capture::PoreTrainingPrint& print,
                                     const LiveBenchOptions& options,
                                     const std::function<void(const LiveBenchRow&)>& on_row) {
  check(options);
  std::vector<LiveBenchRow> rows;
  for (const auto& scene : options.cases) {
    const capture::PoreTrainingPrint sized =
        capture::mirrored_to_size(print, scene.width_px, scene.height_px);
    const int frames =
        std::max(capture::kMinTrackFrames,
                 static_cast<int>(std::lround(options.seconds * scene.camera_rate_hz)));
    capture::PrintWarpSpec spec = capture::print_bench_spec(sized, options.px_per_mm, frames);
    spec.pattern = capture::WarpPattern::wave;
    spec.strain = options.strain;
    spec.frame_rate_hz = scene.camera_rate_hz;
    capture::set_fast_scene(spec, options.travel_mm_per_s);
    // The scene's finger slides 2.5 mm/s; the warp bounds a slide to 5 mm over the sequence,
    // so a session longer than 1.8 s slides more slowly (the wave's speed is unchanged).
    spec.slide_x_mm = std::min(spec.slide_x_mm, 4.5);
    const capture::PrintSequence sequence =
        capture::render_print_sequence(spec, sized.image, sized.pores_px);

    LiveRequest request;
    request.source = fmt::format("memory://{}", print.name);
    request.capture.px_per_mm = options.px_per_mm;
    const double delivery_hz = options.delivery_rate_hz.value_or(scene.camera_rate_hz);
    request.capture.rate_hz = delivery_hz;
    const ResolvedLive session = resolve(request, OptionSpelling::cli);
    display::EmulatedDevice device(emulated_display_options(session.layout));

    // The session's strain as its recording keeps it: strain frames of one span, every point.
    capture::StrainMovie movie;
    movie.frame_rate_hz = scene.camera_rate_hz;
    movie.span_frames = 1;
    movie.camera_frame_count = frames;
    movie.calibration = sequence.calibration;
    movie.field_width_mm = scene.width_px / options.px_per_mm;
    movie.field_height_mm = scene.height_px / options.px_per_mm;
    // Every point as handed out, sorted once at the end: the callback runs on the session's
    // processing thread, in its latency, so it only appends.
    std::vector<capture::TrackedPoint> points;
    LiveCallbacks callbacks;
    callbacks.strain = [&](const capture::StrainFrame& f) {
      points.insert(points.end(), f.points_from.begin(), f.points_from.end());
      points.insert(points.end(), f.points_to.begin(), f.points_to.end());
      if (f.frame_to - f.frame_from == 1) movie.frames.push_back(f);
    };
    std::atomic<bool> stop{false};
    const Clock::time_point start = Clock::now();
    const auto source = open_in_memory(sequence.frames, delivery_hz, start);
    LiveBenchRow row;
    row.scene = scene;
    row.summary = run_live_from(*source, start, session, device, stop, callbacks, {});
    // A point handed out twice (the step into its frame and the step out of it) keeps the last.
    const auto key = [](const capture::TrackedPoint& p) { return std::pair(p.track_id, p.frame); };
    std::stable_sort(points.begin(), points.end(),
                     [&](const auto& a, const auto& b) { return key(a) < key(b); });
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (i + 1 < points.size() && key(points[i + 1]) == key(points[i])) continue;
      movie.tracks.push_back(points[i]);
    }
    const capture::GroundTruth truth = capture::ground_truth_of(sequence);
    row.live = capture::evaluate_strain(movie, truth);
    row.batch = capture::run_print_bench(capture::print_bench_methods().front(), sequence).eval;
    on_row(row);
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string live_bench_table_header() {
  return fmt::format(
      "{:>9} {:>5} {:>6} {:>6} {:>5} {:>7} {:>7} {:>7} {:>9} {:>6} {:>9} {:>6} {:>6}\n", "frame",
      "Hz", "in", "done", "drop", "p50_ms", "p99_ms", "max_ms", "live_rms", "live_r", "batch_rms",
      "batch_r", "ratio");
}

std::string live_bench_table_row(const LiveBenchRow& r) {
  const auto& s = r.summary;
  return fmt::format(
      "{:>4} x {:<3} {:>5.0f} {:>6} {:>6} {:>5} {:>7.2f} {:>7.2f} {:>7.2f} {:>9.5f} {:>6.3f} "
      "{:>9.5f} {:>6.3f} {:>6.2f}\n",
      r.scene.width_px, r.scene.height_px, r.scene.camera_rate_hz, s.frames_in, s.frames_processed,
      s.frames_dropped, s.latency_p50_ms, s.latency_p99_ms, s.latency_max_ms, r.live.rms_error,
      r.live.correlation, r.batch.rms_error, r.batch.correlation,
      r.batch.rms_error > 0 ? r.live.rms_error / r.batch.rms_error : NAN);
}

std::string live_bench_csv_header() {
  return "width_px,height_px,camera_rate_hz,frames_in,frames_processed,frames_dropped,"
         "latency_p50_ms,latency_p99_ms,latency_max_ms,wait_p50_ms,track_p50_ms,strain_p50_ms,"
         "map_p50_ms,send_p50_ms,live_rms_error,"
         "live_correlation,live_median_points,batch_rms_error,batch_correlation";
}

std::string live_bench_csv_row(const LiveBenchRow& r) {
  const auto& s = r.summary;
  return fmt::format(
      "{},{},{:g},{},{},{},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.3f},{:.6g},{:.5f},{:"
      ".0f},"
      "{:.6g},{:.5f}\n",
      r.scene.width_px, r.scene.height_px, r.scene.camera_rate_hz, s.frames_in, s.frames_processed,
      s.frames_dropped, s.latency_p50_ms, s.latency_p99_ms, s.latency_max_ms, s.wait_p50_ms,
      s.track_p50_ms, s.strain_p50_ms, s.map_p50_ms, s.send_p50_ms, r.live.rms_error,
      r.live.correlation, r.live.median_tracked_points, r.batch.rms_error, r.batch.correlation);
}

XYChart live_bench_chart(const std::vector<LiveBenchRow>& rows) {
  XYChart chart{.title = "Live session: latency against strain accuracy (8 % wave)",
                .x = {.label = "latency p99 (ms)", .scale = AxisScale::log},
                .y = {.label = "edge strain RMS error", .scale = AxisScale::log},
                .y_targets = {{.value = capture::kPrintStrainTarget,
                               .label = fmt::format("RMS {:g}", capture::kPrintStrainTarget)}},
                .width = 960,
                .height = 600};
  for (const auto& r : rows) {
    add_point(chart,
              fmt::format("{} x {} px (points: 30, 60, 120, 240 Hz)", r.scene.width_px,
                          r.scene.height_px),
              r.summary.latency_p99_ms, r.live.rms_error);
  }
  return chart;
}

}  // namespace tactile::live
