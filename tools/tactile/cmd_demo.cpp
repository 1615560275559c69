// `tactile demo`: the whole pipeline on the built-in scene, each stage computed from the last.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "command.hpp"
#include "mode_option.hpp"
#include "progress.hpp"
#include "request_options.hpp"
#include "tactile/capture/calibrate.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/capture/synth_request.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/version.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/mapping/fidelity.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

struct DemoOptions {
  fs::path out = "tactile-demo";
  bool keep = false;
  bool headless = false;
  std::string layout = "stress";
  capture::SceneRequest scene_request;
  capture::SceneSpec scene;  // the request's scene, when the command line is read
  // Frame-to-frame strains are fractions of a percent; scaling the movie to 80 % of the range
  // makes the demo feelable whatever the scene. p99 rather than peak: a few badly tracked
  // triangles must not shrink the whole movie.
  mapping::MappingParams mapping = [] {
    mapping::MappingParams p;
    p.normalisation = mapping::Normalisation::p99;
    p.peak_fraction = 0.8;
    return p;
  }();
};

class StageTimer {
 public:
  // One aligned line per stage: number, name, what it produced, time it took.
  void report(int number, const char* stage, const std::string& what) {
    fmt::print("  {} {:<11} {:<62} {:6.2f} s\n", number, stage, what, lap_s());
  }

 private:
  double lap_s() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

int run_demo(DemoOptions& opt, const std::string& command_line) {
  const movie::Layout layout = movie::layout_by_name(opt.layout);
  capture::validate_scene(opt.scene);
  mapping::resolve_mapping_params(opt.mapping, layout);  // fail before any work
  refuse_output_over_input({output_folder("--out", opt.out, {})}, {});
  if (opt.keep) {
    capture::refuse_stale_frames(fmt::format("--out {}: its frames folder", opt.out.string()),
                                 opt.out / "frames", opt.scene.frame_count);
  }
  fs::create_directories(opt.out);
  Progress progress;
  StageTimer timer;
  const auto total_start = std::chrono::steady_clock::now();

  fmt::print("demo: {} scene, {} frames at {:g} Hz, sliding at {:g} mm/s\n",
             to_string(opt.scene.scene), opt.scene.frame_count, opt.scene.frame_rate_hz,
             opt.scene.speed_mm_per_s);
  const capture::SyntheticSequence seq = capture::render_sequence(
      opt.scene, [&](int done, int total) { progress("synthesise", done, total); });
  progress.finish();
  timer.report(1, "synthesise",
               fmt::format("{} frames of {} x {} px", seq.frames.size(), opt.scene.width_px,
                           opt.scene.height_px));
  if (opt.keep) capture::write_sequence(opt.out / "frames", seq, command_line);

  // Calibrate from the dot grid image, as a user would: the true calibration is not used.
  const capture::Calibration calibration = capture::calibrate_dot_grid(seq.dot_grid, 0.5);
  capture::write_calibration_json(opt.out / "calibration.json", calibration);
  timer.report(2, "calibrate",
               fmt::format("{:.2f} px/mm from the 0.5 mm dot grid", 1.0 / calibration.mm_per_px));

  capture::StrainMovie strain = capture::measure_strain(
      seq.frames, calibration, opt.scene.frame_rate_hz, capture::CaptureParams{},
      [&](const std::string& stage, int done, int total) { progress(stage, done, total); });
  progress.finish();
  // Measured from frames rendered in memory: no input file; the scene is in the parameters.
  auto settings = nlohmann::json::parse(strain.provenance.parameters_json);
  settings["scene"] = to_string(opt.scene.scene);
  settings["seed"] = opt.scene.seed;
  strain.provenance.parameters_json = settings.dump();
  strain.provenance.command_line = command_line;
  std::size_t edges = 0;
  for (const auto& f : strain.frames) edges += f.edges.size();
  const std::size_t tracks = [&] {
    std::int32_t max_id = -1;
    for (const auto& p : strain.tracks) max_id = std::max(max_id, p.track_id);
    return static_cast<std::size_t>(max_id + 1);
  }();
  timer.report(
      3, "capture",
      fmt::format("{} tracks, {} strain frames, {:.0f} edges per frame", tracks,
                  strain.frames.size(),
                  strain.frames.empty() ? 0.0 : static_cast<double>(edges) / strain.frames.size()));
  const fs::path strain_path = opt.out / "strain.h5";
  capture::write_strain_movie(strain_path, strain);
  if (opt.keep) {
    fs::create_directories(opt.out / "csv");
    capture::export_strain_csv(opt.out / "csv", strain);
  }

  opt.mapping.program_version = kVersion;
  const capture::StrainMovie source = mapping::strain_source(strain, opt.mapping);
  mapping::MappingResult mapped = mapping::map_strain_frames(source, layout, opt.mapping);
  movie::TactileMovie& movie = mapped.movie;
  movie.provenance.input = strain_path.string();
  movie.provenance.command_line = command_line;
  timer.report(
      4, "map",
      fmt::format("{} frames of {} x {} ({}) at {:g} Hz, method {}", movie.frame_count, layout.rows,
                  layout.cols, layout.name, movie.rate_hz, to_string(opt.mapping.method)));
  // What the user will feel against what was measured: the strain the movie imposes between
  // neighbouring contactors, compared with the measured strain (mapping/fidelity.hpp).
  const mapping::FidelityMetrics fit =
      mapping::fidelity(movie, source, mapped.placement, mapped.um_per_strain,
                        opt.mapping.slew_limit_um_per_s, opt.mapping.field);
  fmt::print("    {}\n", mapping::describe_fidelity(fit));
  const fs::path movie_path = opt.out / "movie.h5";
  movie::write_tactile_movie(movie_path, movie);
  if (opt.keep) movie::export_tactile_csv(opt.out / "csv" / "movie.csv", movie);

  fmt::print("  5 play\n");
  display::ResolvedPlay choice;
  choice.headless = opt.headless;
  choice.preview_png = opt.out / "preview.png";
  display::play_anywhere(
      movie, choice, [](const std::string& text) { fmt::print("{}", text); },
      display::with_window(display::usb_play_backends()));
  fmt::print("demo: done in {:.1f} s; files in {}/ ({}strain.h5, movie.h5{})\n",
             std::chrono::duration<double>(std::chrono::steady_clock::now() - total_start).count(),
             opt.out.string(),
             opt.keep ? "frames/, csv/, calibration.json, " : "calibration.json, ",
             fs::exists(choice.preview_png) ? ", preview.png" : "");
  return 0;
}

}  // namespace

void add_demo(CLI::App& app, Action& action, const std::string& command_line) {
  auto opt = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand(
      "demo",
      "The whole pipeline on a built-in scene: a fingertip slides at 2.4 mm/s over a Gaussian\n"
      "bump (0.5 mm high, 3 mm wide), 180 frames at 60 Hz; calibrate, extract and track\n"
      "landmarks, measure strain, map onto a 10 x 10 STReSS grid at 700 Hz, and play it.\n"
      "Writes calibration.json, strain.h5 and movie.h5 (and preview.png when headless) to --out.");
  sub->add_option("--out", opt->out, "Folder for the files the demo writes")->capture_default_str();
  sub->add_flag("--keep", opt->keep,
                "Also keep every intermediate: frames/ (PNG + ground truth), csv/ (tracks, edges, "
                "movie)");
  sub->add_flag("--headless", opt->headless,
                "Play into the emulated device and write a preview, even if a screen exists");
  sub->add_option("--layout", opt->layout,
                  fmt::format("Contactor layout: {}", fmt::join(movie::kBuiltinLayoutNames, ", ")))
      ->check(CLI::IsMember(std::vector<std::string>(movie::kBuiltinLayoutNames.begin(),
                                                     movie::kBuiltinLayoutNames.end())))
      ->capture_default_str();
  add_mode_option(*sub, "--method", opt->mapping.method, mapping::kMappingMethodNames,
                  "Mapping method (see tactile map --help); the demo prints how well the movie\n"
                  "reproduces the measured strain");
  add_request_options(*sub, std::shared_ptr<capture::SceneRequest>(opt, &opt->scene_request),
                      capture::scene_options());
  sub->callback([opt, &action, &command_line] {
    opt->scene = capture::scene_spec(opt->scene_request);
    action = [opt, &command_line] { return run_demo(*opt, command_line); };
  });
}

}  // namespace tactile::cli
