// `tactile synth`: render a synthetic fingertip sequence with exact ground truth.

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>

#include "command.hpp"
#include "progress.hpp"
#include "scene_options.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::cli {

void add_synth(CLI::App& app, Action& action) {
  struct Options {
    std::filesystem::path out_dir;
    capture::SceneSpec spec;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "synth",
      "Render a synthetic prism (FTIR) fingerprint sequence with exact ground truth.\n"
      "Writes frame_NNN.png, calibration/dot_grid.png (0.5 mm grid through the same camera),\n"
      "landmarks.csv (true position of every landmark in every frame) and scene.json.");
  sub->add_option("OUT_DIR", opt->out_dir, "Folder to write into (created if missing)")->required();
  add_scene_options(*sub, opt->spec);
  sub->callback([opt, &action] {
    action = [opt] {
      capture::validate(opt->spec);
      Progress progress;
      const auto t0 = std::chrono::steady_clock::now();
      const capture::SyntheticSequence seq = capture::render_sequence(
          opt->spec, [&](int done, int total) { progress("render", done, total); });
      progress.finish();
      std::filesystem::create_directories(opt->out_dir);
      capture::write_sequence(opt->out_dir, seq);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print(
          "synth: {} frames of {} x {} px ({} scene) and {} landmark positions -> {} ({:.1f} s)\n",
          seq.frames.size(), opt->spec.width_px, opt->spec.height_px, opt->spec.scene,
          seq.landmarks.size(), opt->out_dir.string(), s);
      return 0;
    };
  });
}

}  // namespace tactile::cli
