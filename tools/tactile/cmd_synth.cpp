// `tactile synth`: render a synthetic fingertip sequence with exact ground truth.

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "command.hpp"
#include "mode_option.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::cli {

namespace {

// pores_NN.txt beside image_NN.*, the PolyU HRF layout, when it exists.
std::optional<std::filesystem::path> marks_beside(const std::filesystem::path& image) {
  const std::string stem = image.stem().string();
  if (stem.rfind("image_", 0) != 0) return std::nullopt;
  const auto marks = image.parent_path() / ("pores_" + stem.substr(6) + ".txt");
  if (std::filesystem::is_regular_file(marks)) return marks;
  return std::nullopt;
}

int synth_from_print(const std::filesystem::path& out_dir, const std::filesystem::path& image,
                     std::optional<std::filesystem::path> marks, capture::PrintWarpSpec warp,
                     const std::string& command_line) {
  if (!marks) marks = marks_beside(image);
  std::vector<std::filesystem::path> writes = {"landmarks.csv", "scene.json"};
  for (int f = 0; f < warp.frame_count; ++f) {
    writes.push_back(capture::frame_file_name(static_cast<std::size_t>(f)));
  }
  refuse_output_over_input({output_folder("OUT_DIR", out_dir, writes)},
                           {{"--from-print", image}, {"--marks", marks.value_or(image)}});
  refuse_stale_frames("OUT_DIR", out_dir, warp.frame_count);
  const capture::GrayImage print = capture::read_image(image);
  warp.source = image.filename().string();
  warp.width_px = print.width_px;
  warp.height_px = print.height_px;
  std::vector<std::array<double, 2>> pores;
  if (marks) pores = capture::read_pore_marks(*marks, print.width_px, print.height_px);
  const auto t0 = std::chrono::steady_clock::now();
  // The warp's own checks know the print's size, not its file.
  const capture::PrintSequence seq = [&] {
    try {
      return capture::render_print_sequence(warp, print, pores);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(fmt::format("--from-print {}: {}", image.string(), e.what()));
    }
  }();
  capture::write_print_sequence(out_dir, seq, image, command_line);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print(
      "synth: {} frames of {} x {} px from {} ({} warp, {:.1f} % peak strain, {} marked pores{}) "
      "-> {} ({:.1f} s)\n",
      seq.frames.size(), warp.width_px, warp.height_px, image.string(),
      capture::to_string(warp.pattern), 100 * warp.strain, pores.size(),
      marks ? " from " + marks->filename().string() : std::string(), out_dir.string(), s);
  return 0;
}

}  // namespace

void add_synth(CLI::App& app, Action& action, const std::string& command_line) {
  struct Options {
    std::filesystem::path out_dir;
    capture::SceneSpec spec;
    std::optional<std::filesystem::path> print;
    std::optional<std::filesystem::path> marks;
    capture::PrintWarpSpec warp;
    double strain_pct = 4.0;
    double exposure_ms = 0;
    std::optional<double> slide_speed_mm_per_s;
    std::optional<double> turn_rate_deg_per_s;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "synth",
      "Render a synthetic prism (FTIR) fingerprint sequence with exact ground truth.\n"
      "Writes frame_NNN.png, calibration/dot_grid.png (0.5 mm grid through the same camera),\n"
      "landmarks.csv (true position of every landmark in every frame) and scene.json.\n"
      "With --from-print IMAGE: a real print moved by a known smooth warp (slide, rotation and a\n"
      "strain pattern) and filmed with blur, noise and a brightness drift, so that `tactile\n"
      "evaluate` scores a capture of real skin against the exact warp.");
  sub->add_option("OUT_DIR", opt->out_dir, "Folder to write into (created if missing)")->required();
  add_scene_options(*sub, opt->spec, true);
  auto* from = sub->add_option("--from-print", opt->print,
                               "A real fingerprint image (ridges dark) to warp instead of a "
                               "synthetic scene")
                   ->check(CLI::ExistingFile);
  auto needs_print = [from](CLI::Option* o) { return o->needs(from); };
  needs_print(sub->add_option("--px-per-mm", opt->warp.px_per_mm,
                              "--from-print: the print's scale, pixels per millimetre")
                  ->check(within(5.0, 500.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--marks", opt->marks,
                              "--from-print: hand-marked pores ('row col' per line, 1-based) to\n"
                              "carry through the warp as landmarks.csv; default pores_NN.txt\n"
                              "beside image_NN.*, when there is one")
                  ->check(CLI::ExistingFile));
  needs_print(add_mode_option(*sub, "--warp", opt->warp.pattern, capture::kWarpPatternNames,
                              "--from-print: strain pattern: rigid (slide and rotation only),\n"
                              "stretch (along x), compress (along y), bump (radial), wave\n"
                              "(travelling along x), pulse (a bump crossing along x), ridge\n"
                              "(compression ahead of a sliding edge), stick-slip (rim loads and\n"
                              "slips around a sticking centre), kernels (random smooth field),\n"
                              "full-slip (the skin slides through the view at --travel-speed,\n"
                              "strained by a static field; the print mirrored without end)"));
  needs_print(sub->add_option("--strain-pct", opt->strain_pct,
                              "--from-print: peak strain of the pattern, per cent")
                  ->check(within(-20.0, 20.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--warp-width", opt->warp.width_mm,
                              "--from-print: width (FWHM) of the pattern, or the wavelength, mm")
                  ->check(within(0.5, 50.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--slide-x", opt->warp.slide_x_mm,
                              "--from-print: slide along x over the sequence, mm")
                  ->check(within(-5.0, 5.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--slide-y", opt->warp.slide_y_mm,
                              "--from-print: slide along y over the sequence, mm")
                  ->check(within(-5.0, 5.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--turn", opt->warp.rotation_deg,
                              "--from-print: rotation over the sequence, degrees")
                  ->check(within(-30.0, 30.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--blur", opt->warp.blur_sigma_px,
                              "--from-print: camera blur, pixels (sigma)")
                  ->check(within(0.0, 10.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--drift", opt->warp.brightness_drift,
                              "--from-print: change of exposure over the sequence (0.06 = 6 %)")
                  ->check(within(-0.5, 0.5))
                  ->capture_default_str());
  needs_print(sub->add_option("--travel-speed", opt->warp.travel_speed_mm_per_s,
                              "--from-print: speed at which the pattern crosses the field, mm/s\n"
                              "(0: wave, pulse and ridge take the whole sequence)")
                  ->check(within(0.0, 1000.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--rate-hz", opt->warp.frame_rate_hz, "--from-print: camera rate, Hz")
                  ->check(within(1.0, 100000.0))
                  ->capture_default_str());
  // The old spelling, hidden from --help and kept for scripts written against it (a hidden
  // option has no name in CLI11's messages, so its need of --from-print is checked below).
  sub->add_option_function<double>(
         "--rate",
         [opt](double rate_hz) {
           fmt::print(stderr, "tactile synth: warning: --rate is deprecated; use --rate-hz\n");
           opt->warp.frame_rate_hz = rate_hz;
         },
         "")
      ->check(within(1.0, 100000.0))
      ->group("");
  needs_print(sub->add_option("--exposure-ms", opt->exposure_ms,
                              "--from-print: shutter time, ms (motion blur; at most one frame)")
                  ->check(within(0.0, 1000.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--supersample", opt->warp.supersample,
                              "--from-print: samples per pixel side over the pixel's area")
                  ->check(within(1, 8))
                  ->capture_default_str());
  needs_print(sub->add_option("--contact-loss", opt->warp.contact_loss,
                              "--from-print: a region lifts off mid-sequence and lands again,\n"
                              "0 (none) to 1 (fully lifted)")
                  ->check(within(0.0, 1.0))
                  ->capture_default_str());
  needs_print(sub->add_option("--slide-speed", opt->slide_speed_mm_per_s,
                              "--from-print: slide along x in mm/s (instead of --slide-x)")
                  ->check(within(-1000.0, 1000.0))
                  ->excludes("--slide-x"));
  needs_print(sub->add_option("--turn-rate", opt->turn_rate_deg_per_s,
                              "--from-print: rotation in degrees/s (instead of --turn)")
                  ->check(within(-10000.0, 10000.0))
                  ->excludes("--turn"));
  sub->callback([opt, &action, sub, &command_line] {
    // Checked here, not with CLI11's excludes: that would list the hidden option's empty name
    // under --rate-hz in --help ("Excludes: ").
    if (sub->count("--rate") > 0 && sub->count("--rate-hz") > 0) {
      throw CLI::ExcludesError("--rate", "--rate-hz");
    }
    if (opt->print) {
      for (const char* scene_only :
           {"--scene", "--speed", "--height", "--width", "--contact-semi-x", "--rotation",
            "--lateral-amplitude", "--stick-ratio"}) {
        if (sub->count(scene_only) > 0) {
          throw CLI::ValidationError(scene_only, "describes a synthetic scene, not --from-print");
        }
      }
      if (sub->count("--frames") > 0) opt->warp.frame_count = opt->spec.frame_count;
      if (sub->count("--noise") > 0) opt->warp.noise_sigma = opt->spec.noise_sigma;
      if (sub->count("--seed") > 0) opt->warp.seed = opt->spec.seed;
      if (opt->warp.pattern == capture::WarpPattern::full_slip &&
          !(opt->warp.travel_speed_mm_per_s > 0)) {
        throw CLI::ValidationError("--warp full-slip",
                                   "needs --travel-speed above 0 (the skin's speed through the "
                                   "view, mm/s)");
      }
      opt->warp.strain = opt->strain_pct / 100;
      opt->warp.exposure_s = opt->exposure_ms / 1000;
      const double duration_s = capture::sequence_duration_s(opt->warp);
      if (opt->slide_speed_mm_per_s) opt->warp.slide_x_mm = *opt->slide_speed_mm_per_s * duration_s;
      if (opt->turn_rate_deg_per_s) opt->warp.rotation_deg = *opt->turn_rate_deg_per_s * duration_s;
      action = [opt, &command_line] {
        return synth_from_print(opt->out_dir, *opt->print, opt->marks, opt->warp, command_line);
      };
      return;
    }
    if (sub->count("--rate") > 0) throw CLI::RequiresError("--rate", "--from-print");
    action = [opt, &command_line] {
      capture::validate_scene(opt->spec);
      refuse_output_over_input({output_folder("OUT_DIR", opt->out_dir, {})}, {});
      refuse_stale_frames("OUT_DIR", opt->out_dir, opt->spec.frame_count);
      Progress progress;
      const auto t0 = std::chrono::steady_clock::now();
      const capture::SyntheticSequence seq = capture::render_sequence(
          opt->spec, [&](int done, int total) { progress("render", done, total); });
      progress.finish();
      std::filesystem::create_directories(opt->out_dir);
      capture::write_sequence(opt->out_dir, seq, command_line);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print(
          "synth: {} frames of {} x {} px ({} scene) and {} landmark positions -> {} ({:.1f} s)\n",
          seq.frames.size(), opt->spec.width_px, opt->spec.height_px, to_string(opt->spec.scene),
          seq.landmarks.size(), opt->out_dir.string(), s);
      return 0;
    };
  });
}

}  // namespace tactile::cli
