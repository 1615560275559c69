#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "tactile/capture/baselines.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/contact_strain.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/common/stopwatch.hpp"

namespace tactile::capture {

namespace {

StrainMovie landmarks_default(const PrintSequence& seq) {
  // The settings `tactile capture` picks when given only the scale, and, where the skin slides
  // through the view, its contact map and the strain it keeps (elsewhere neither changes what
  // is measured, and the map's time is left out of the still scenes' frames/s).
  CaptureParams p = with_choice({}, choose_capture_settings(seq.frames[0], seq.spec.px_per_mm));
  p.min_track_frames = std::min(p.min_track_frames, seq.spec.frame_count);
  p.measure_contact = seq.spec.pattern == WarpPattern::full_slip;
  return strain_in_contact(measure_strain(seq.frames, seq.calibration, seq.spec.frame_rate_hz, p));
}

// The capture's shortest track for skin sliding through the view (half the frames a point stays
// in view, at least 3, at most a still contact's), from the scene's known speed.
int sliding_min_track(const PrintWarpSpec& spec) {
  const double px_per_frame = spec.travel_speed_mm_per_s * spec.px_per_mm / spec.frame_rate_hz;
  const double in_view = px_per_frame > 0 ? spec.width_px / px_per_frame : 1e9;
  const int still = RefineParams{}.min_frames;
  return std::clamp(static_cast<int>(std::min<double>(still, std::floor(in_view / 2))), 3, still);
}

StrainMovie from_tracks(const std::vector<Track>& tracks, const PrintSequence& seq) {
  return strain_from_tracks(tracks, static_cast<int>(seq.frames.size()), seq.calibration,
                            seq.spec.frame_rate_hz, 1, CaptureParams{}.max_edge_ratio);
}

}  // namespace

std::vector<PrintBenchMethod> print_bench_methods() {
  std::vector<PrintBenchMethod> m{{"landmarks (default)", landmarks_default}};
  m.push_back({"Lucas-Kanade", [](const PrintSequence& s) {
                 auto p = LucasKanadeParams{};
                 p.min_track_frames = std::min(p.min_track_frames, s.spec.frame_count);
                 if (s.spec.pattern == WarpPattern::full_slip) {
                   // Fair to it where the skin slides through: new corners every frame as
                   // points leave, tracks as short as the capture keeps at that speed.
                   p.reseed_every_frames = 1;
                   p.min_track_frames = std::min(p.min_track_frames, sliding_min_track(s.spec));
                 }
                 return from_tracks(track_lucas_kanade(s.frames, s.calibration, p), s);
               }});
  m.push_back({"DIS flow", [](const PrintSequence& s) {
                 auto p = DisFlowParams{};
                 p.min_track_frames = std::min(p.min_track_frames, s.spec.frame_count);
                 return from_tracks(track_dis_flow(s.frames, s.calibration, p), s);
               }});
  return m;
}

std::vector<PrintBenchCase> print_bench_cases(bool quick) {
  if (quick) return {{WarpPattern::wave, 0.04}, {WarpPattern::wave, 0.08, 25}};
  return {{WarpPattern::rigid, 0.04}, {WarpPattern::stretch, 0.04}, {WarpPattern::compress, 0.04},
          {WarpPattern::bump, 0.04},  {WarpPattern::wave, 0.01},    {WarpPattern::wave, 0.04},
          {WarpPattern::wave, 0.08},  {WarpPattern::wave, 0.08, 25}};
}

std::vector<PrintBenchCase> touch_bench_cases() {
  return {{WarpPattern::pulse, 0.08, 25},
          {WarpPattern::ridge, 0.08, 25},
          {WarpPattern::stick_slip, 0.08, 25},
          {WarpPattern::kernels, 0.08, 25},
          {WarpPattern::wave, 0.08, 25, 1.0}};
}

std::vector<PrintBenchCase> slip_bench_cases() {
  std::vector<PrintBenchCase> cases;
  for (const double speed : {10.0, 25.0, 50.0, 100.0}) {
    cases.push_back({WarpPattern::full_slip, 0.04, speed});
  }
  return cases;
}

std::string case_label(const PrintBenchCase& c) {
  if (c.pattern == WarpPattern::full_slip) {
    return fmt::format("slip-{:.0f}", c.travel_mm_per_s) + (c.contact_loss > 0 ? "+loss" : "");
  }
  return std::string(to_string(c.pattern)) + (c.travel_mm_per_s > 0 ? "-fast" : "") +
         (c.contact_loss > 0 ? "+loss" : "");
}

void set_fast_scene(PrintWarpSpec& s, double travel_mm_per_s) {
  s.travel_speed_mm_per_s = travel_mm_per_s;
  s.slide_x_mm = 2.5 * sequence_duration_s(s);
  s.slide_y_mm = 0;
  s.rotation_deg = 3;
  s.exposure_s = std::min(0.002, 1 / s.frame_rate_hz);
  s.supersample = 2;
}

namespace {

// Full slip as `--slip` runs it: the skin sliding through the view under the glass's static
// 4 % field.
void set_full_slip(PrintWarpSpec& s, double travel_mm_per_s) {
  s.pattern = WarpPattern::full_slip;
  s.strain = 0.04;
  s.travel_speed_mm_per_s = travel_mm_per_s;
}

}  // namespace

PrintWarpSpec print_bench_spec(const PoreTrainingPrint& print, double px_per_mm, int frame_count) {
  PrintWarpSpec s;
  s.source = print.name;
  s.px_per_mm = px_per_mm;
  s.width_px = print.image.width_px;
  s.height_px = print.image.height_px;
  s.frame_count = frame_count;
  return s;
}

PoreTrainingPrint mirrored_to_size(const PoreTrainingPrint& print, int width_px, int height_px) {
  constexpr int kMaxSide = 10000;
  if (width_px < 1 || width_px > kMaxSide || height_px < 1 || height_px > kMaxSide) {
    throw std::invalid_argument(
        fmt::format("frame size {} x {} px is outside 1 to {} px", width_px, height_px, kMaxSide));
  }
  const int w = print.image.width_px, h = print.image.height_px;
  if (w < 1 || h < 1) throw std::invalid_argument(print.name + ": empty image");
  // Index i of the mirrored line in a source line of n: copies alternate forward and backward.
  auto source = [](int i, int n) {
    const int in_pair = i % (2 * n);
    return in_pair < n ? in_pair : 2 * n - 1 - in_pair;
  };
  PoreTrainingPrint out;
  out.name = print.name;
  out.image.width_px = width_px;
  out.image.height_px = height_px;
  out.image.pixels.resize(static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px));
  for (int y = 0; y < height_px; ++y) {
    for (int x = 0; x < width_px; ++x) {
      out.image.pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_px) +
                       static_cast<std::size_t>(x)] = print.image.at(source(x, w), source(y, h));
    }
  }
  // A mark at x (pixel centres at integers) lies at t w + x in a forward copy t and at
  // t w + (w - 1 - x) in a mirrored one.
  for (int ty = 0; ty * h < height_px; ++ty) {
    for (int tx = 0; tx * w < width_px; ++tx) {
      for (const auto& [x, y] : print.pores_px) {
        const double mx = tx * w + (tx % 2 == 0 ? x : w - 1 - x);
        const double my = ty * h + (ty % 2 == 0 ? y : h - 1 - y);
        if (mx >= 0 && my >= 0 && mx <= width_px - 1 && my <= height_px - 1) {
          out.pores_px.push_back({mx, my});
        }
      }
    }
  }
  return out;
}

std::string print_number(const std::string& file_name) {
  const auto stem = std::filesystem::path(file_name).stem().string();
  return stem.substr(stem.find('_') + 1);
}

PrintBenchRow run_print_bench(const PrintBenchMethod& method, const PrintSequence& seq) {
  PrintBenchRow r;
  r.method = method.name;
  const Stopwatch clock;
  const StrainMovie movie = method.run(seq);
  const double s = clock.wall_s();
  const double cpu_s = clock.cpu_s();
  const auto frames = static_cast<double>(seq.frames.size());
  r.frames_per_s = s > 0 ? frames / s : 0.0;
  r.cpu_ms_per_frame = 1e3 * cpu_s / frames;
  r.eval = evaluate_strain(movie, ground_truth_of(seq));
  return r;
}

std::vector<PrintBenchRow> bench_prints(const std::vector<PoreTrainingPrint>& prints,
                                        const std::vector<PrintBenchMethod>& methods,
                                        const PrintBenchOptions& options,
                                        const std::function<void(const PrintBenchRow&)>& on_row) {
  const std::set<std::string> held(options.held_out.begin(), options.held_out.end());
  const std::size_t used = std::min(options.method_count, methods.size());
  std::vector<PrintBenchRow> rows;
  for (const auto& p : prints) {
    const std::string nn = print_number(p.name);
    for (const auto& c : options.cases) {
      auto spec = print_bench_spec(p, options.px_per_mm, options.frame_count);
      spec.pattern = c.pattern;
      spec.strain = c.strain;
      if (c.pattern == WarpPattern::full_slip) {
        spec.travel_speed_mm_per_s = c.travel_mm_per_s;
      } else if (c.travel_mm_per_s > 0) {
        set_fast_scene(spec, c.travel_mm_per_s);
      }
      spec.contact_loss = c.contact_loss;
      const PrintSequence seq = render_print_sequence(spec, p.image, p.pores_px);
      for (std::size_t k = 0; k < used; ++k) {
        PrintBenchRow r = run_print_bench(methods[k], seq);
        r.print = nn;
        r.held_out = held.count(nn) > 0;
        r.pattern = case_label(c);
        r.strain = c.strain;
        on_row(r);
        rows.push_back(std::move(r));
      }
    }
  }
  return rows;
}

std::vector<PrintBenchSummary> summarise_print_bench(const std::vector<PrintBenchRow>& rows,
                                                     const std::vector<std::string>& method_names) {
  std::vector<PrintBenchSummary> out;
  for (const auto& name : method_names) {
    for (const bool h : {false, true}) {
      std::vector<double> pts, rms, corr, fps, cpu;
      for (const auto& r : rows) {
        if (r.method != name || r.held_out != h) continue;
        pts.push_back(r.eval.median_tracked_points);
        rms.push_back(r.eval.rms_error);
        fps.push_back(r.frames_per_s);
        cpu.push_back(r.cpu_ms_per_frame);
        // The rigid warp has no strain, so no correlation.
        if (r.pattern != "rigid") corr.push_back(r.eval.correlation);
      }
      if (pts.empty()) continue;
      out.push_back({name, h, median(pts), median(rms), median(corr),
                     corr.empty() ? 0.0 : *std::min_element(corr.begin(), corr.end()), median(fps),
                     median(cpu)});
    }
  }
  return out;
}

std::vector<PrintSweep> print_sweeps() {
  return {
      {"noise (grey levels)",
       {2, 4, 8, 12, 16, 24, 32},
       [](PrintWarpSpec& s, double v) { s.noise_sigma = v; }},
      {"blur (px)",
       {0.7, 1.0, 1.5, 2.0, 3.0, 4.0},
       [](PrintWarpSpec& s, double v) { s.blur_sigma_px = v; }},
      {"strain (%)",
       {1, 2, 4, 8, 12, 16, 20},
       [](PrintWarpSpec& s, double v) { s.strain = v / 100; }},
      {"slide over the sequence (mm)",
       {0.25, 0.5, 1, 2, 3, 5},
       [](PrintWarpSpec& s, double v) { s.slide_x_mm = v; }},
      // The fast scene (8 % wave) at rising exploration speed, camera at 60 Hz ...
      {"exploration speed at 60 Hz (mm/s)",
       {5, 10, 15, 20, 25, 35, 50, 70, 100},
       [](PrintWarpSpec& s, double v) {
         s.strain = 0.08;
         set_fast_scene(s, v);
       },
       true},
      // ... and at 25 mm/s with a slower and slower camera.
      {"camera rate at 25 mm/s (Hz)",
       {240, 120, 90, 60, 45, 30, 20},
       [](PrintWarpSpec& s, double v) {
         s.strain = 0.08;
         s.frame_rate_hz = v;
         set_fast_scene(s, 25);
       },
       true},
      // Full slip (the skin sliding through the view under the glass's static 4 % field, as
      // `--slip`), faster and faster at 60 Hz ...
      {"full-slip speed at 60 Hz (mm/s)",
       {10, 25, 50, 100, 150, 200, 300, 400},
       [](PrintWarpSpec& s, double v) { set_full_slip(s, v); },
       true},
      // ... and at 50 mm/s with a slower and slower camera.
      {"full-slip camera rate at 50 mm/s (Hz)",
       {240, 120, 90, 60, 45, 30, 20, 15},
       [](PrintWarpSpec& s, double v) {
         s.frame_rate_hz = v;
         set_full_slip(s, 50);
       },
       true},
  };
}

SweepFailures run_print_sweep(const PrintSweep& sweep, const PrintBenchMethod& method,
                              const PoreTrainingPrint& print, const PrintBenchOptions& options,
                              const SweepLimits& limits,
                              const std::function<void(const PrintSweepPoint&)>& on_point) {
  SweepFailures failures;
  for (const double v : sweep.values) {
    auto spec = print_bench_spec(print, options.px_per_mm, options.frame_count);
    sweep.apply(spec, v);
    PrintSweepPoint p;
    p.value = v;
    p.row = run_print_bench(method, render_print_sequence(spec, print.image, {}));
    p.accurate = p.row.eval.edges > 0 && p.row.eval.rms_error <= limits.max_rms;
    p.enough = p.row.eval.median_tracked_points >= limits.min_points;
    on_point(p);
    failures.note(v, p.accurate, p.enough);
    if (failures.both_failed()) break;
  }
  return failures;
}

}  // namespace tactile::capture
