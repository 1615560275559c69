#include <fmt/format.h>

#include <chrono>
#include <exception>

#include "tactile/capture/baselines.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/common/stopwatch.hpp"

namespace tactile::capture {

void SweepFailures::note(double value, bool accurate, bool enough) {
  if (!accurate && accuracy_at < 0) accuracy_at = value;
  if (!enough && yield_at < 0) yield_at = value;
}

std::string SweepFailures::summary(const std::string& name, double last_value) const {
  auto where = [&](double v) {
    return v >= 0 ? fmt::format("fails at {}", v) : fmt::format("holds up to {}", last_value);
  };
  return fmt::format("  -> {}: strain error {}; landmark yield {}\n", name, where(accuracy_at),
                     where(yield_at));
}

namespace {

StrainMovie from_tracks(const std::vector<Track>& tracks, const std::vector<GrayImage>& frames,
                        const Calibration& c, double rate_hz) {
  const CaptureParams defaults;
  return strain_from_tracks(tracks, static_cast<int>(frames.size()), c, rate_hz, 1,
                            defaults.max_edge_ratio);
}

}  // namespace

std::vector<SceneBenchMethod> scene_bench_methods(bool quick) {
  std::vector<SceneBenchMethod> m;
  auto pipeline = [](CaptureParams p) {
    return [p](const std::vector<GrayImage>& f, const Calibration& c, double rate) {
      return measure_strain(f, c, rate, p);
    };
  };
  m.push_back({"pores, 2 threads", pipeline({})});
  CaptureParams one_thread;
  one_thread.threads = 1;
  m.push_back({"pores, 1 thread", pipeline(one_thread)});
  if (!quick) {
    CaptureParams optimal;
    optimal.assignment = Assignment::optimal;
    m.push_back({"pores, optimal match", pipeline(optimal)});
    CaptureParams with_minutiae;
    with_minutiae.features.find_minutiae = true;
    m.push_back({"pores + minutiae", pipeline(with_minutiae)});
    // The ridge-blob pore detector (trained on real 1200 dpi prints) is left out: at about
    // 3 frames/s on 640 x 484 it is a detector for single images, not for sequences.
  }
  m.push_back(
      {"Lucas-Kanade", [](const std::vector<GrayImage>& f, const Calibration& c, double rate) {
         return from_tracks(track_lucas_kanade(f, c), f, c, rate);
       }});
  m.push_back({"DIS flow", [](const std::vector<GrayImage>& f, const Calibration& c, double rate) {
                 return from_tracks(track_dis_flow(f, c), f, c, rate);
               }});
  return m;
}

SceneBenchResult run_scene_bench(const SceneBenchMethod& method, const SyntheticSequence& seq) {
  SceneBenchResult r{method.name, seq.spec.scene, static_cast<int>(seq.frames.size()), 0, 0, {},
                     {}};
  try {
    const Stopwatch clock;
    const StrainMovie movie = method.run(seq.frames, seq.calibration, seq.spec.frame_rate_hz);
    r.cpu_seconds = clock.cpu_s();
    r.seconds = clock.wall_s();
    r.eval = evaluate_strain(movie, {seq.spec, seq.calibration, seq.landmarks, {}});
  } catch (const std::exception& e) {
    r.error = e.what();
  }
  return r;
}

std::vector<SceneBenchResult> bench_scenes(
    int frame_count, const std::vector<SceneBenchMethod>& methods,
    const std::function<void(const SceneBenchResult&)>& on_result) {
  std::vector<SceneBenchResult> results;
  for (const Scene scene : kScenes) {
    SceneSpec spec;
    spec.scene = scene;
    spec.frame_count = frame_count;
    const auto seq = render_sequence(spec);
    for (const auto& m : methods) {
      results.push_back(run_scene_bench(m, seq));
      on_result(results.back());
    }
  }
  return results;
}

std::vector<SceneSweep> scene_sweeps() {
  return {
      {"noise (grey levels)",
       {2, 4, 8, 12, 16, 24, 32, 48},
       [](SceneSpec& s, double v) { s.noise_sigma = v; }},
      {"blur (px)",
       {0.9, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0},
       [](SceneSpec& s, double v) { s.blur_sigma_px = v; }},
      {"contrast",
       {1.0, 0.6, 0.4, 0.25, 0.15, 0.1, 0.05},
       [](SceneSpec& s, double v) { s.contrast = v; }},
      {"speed (mm/s)",
       {2.4, 5, 10, 20, 30, 40, 60},
       [](SceneSpec& s, double v) { s.speed_mm_per_s = v; }},
      {"pore size (x nominal)",
       {1.0, 0.75, 0.6, 0.5, 0.4, 0.3},
       [](SceneSpec& s, double v) {
         s.pore_min_diameter_mm *= v;
         s.pore_max_diameter_mm *= v;
       }},
      {"bump height (mm), loss of contact",
       {0.5, 1.0, 1.5, 2.0, 2.5, 3.0},
       [](SceneSpec& s, double v) { s.feature_height_mm = v; }},
      {"contact patch size (x nominal)",
       {1.0, 0.8, 0.6, 0.5, 0.4, 0.3},
       [](SceneSpec& s, double v) {
         s.contact_semi_x_mm *= v;
         s.contact_semi_y_mm *= v;
       }},
  };
}

SweepFailures run_scene_sweep(const SceneSweep& sweep, const SceneBenchMethod& method,
                              int frame_count, const SweepLimits& limits,
                              const std::function<void(const SceneSweepPoint&)>& on_point) {
  SweepFailures failures;
  for (const double v : sweep.values) {
    SceneSpec spec;
    spec.frame_count = frame_count;
    sweep.apply(spec, v);
    SceneSweepPoint p;
    p.value = v;
    try {
      p.result = run_scene_bench(method, render_sequence(spec));
    } catch (const std::exception& e) {  // a spec the renderer refuses
      p.result.error = e.what();
    }
    p.result.scene = spec.scene;
    p.result.frames = frame_count;
    const auto& r = p.result;
    p.accurate = r.error.empty() && r.eval.edges > 0 && r.eval.rms_error <= limits.max_rms;
    p.enough = r.error.empty() && r.eval.median_tracked_points >= limits.min_points;
    on_point(p);
    failures.note(v, p.accurate, p.enough);
    if (failures.both_failed()) break;
  }
  return failures;
}

}  // namespace tactile::capture
