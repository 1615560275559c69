#pragma once
// `synth` as a request: a synthetic scene (SceneSpec) or a real print moved by an exact warp
// (PrintWarpSpec), its option table (read by the command line and the Python module alike) and
// resolve(), which holds the rules between the options (a scene's options are not a print's),
// and run_synth(), which checks the output folder and writes the sequence. The defaults are
// SceneSpec's and PrintWarpSpec's member initialisers: an option left unset takes them, and the
// help shows them from there.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/option_table.hpp"

namespace tactile::capture {

// What a person may ask of a synthetic scene (`synth`, `demo`); unset: SceneSpec's default.
struct SceneRequest {
  std::optional<Scene> scene;
  std::optional<int> frames;  // unset: the kind of sequence's own default length
  std::optional<double> speed_mm_per_s;
  std::optional<double> height_mm;
  std::optional<double> width_mm;
  std::optional<double> contact_semi_x_mm;
  std::optional<double> rotation_deg;
  std::optional<double> lateral_amplitude_mm;
  std::optional<double> stick_ratio;
  // Camera noise and seed: a print's sequence takes them too.
  std::optional<double> noise;
  std::optional<std::uint64_t> seed;
};

const std::vector<OptionRow<SceneRequest>>& scene_options();

// SceneSpec with every option that is set.
SceneSpec scene_spec(const SceneRequest& request);

// A print's warp; unset: PrintWarpSpec's default.
struct WarpRequest {
  std::optional<double> px_per_mm;
  std::optional<WarpPattern> warp;
  std::optional<double> strain_pct;
  std::optional<double> warp_width_mm;
  std::optional<double> slide_x_mm;
  std::optional<double> slide_y_mm;
  std::optional<double> turn_deg;
  std::optional<double> blur_px;
  std::optional<double> drift;
  std::optional<double> travel_speed_mm_per_s;
  std::optional<double> rate_hz;
  std::optional<double> exposure_ms;
  std::optional<int> supersample;
  std::optional<double> contact_loss;
  std::optional<double> patch_speed_mm_per_s;
  std::optional<double> patch_breathing;
  std::optional<double> slide_speed_mm_per_s;  // instead of slide_x_mm
  std::optional<double> turn_rate_deg_per_s;   // instead of turn_deg
};

struct SynthRequest {
  std::filesystem::path out_dir;
  SceneRequest scene;
  std::optional<std::filesystem::path> from_print;
  std::optional<std::filesystem::path> marks;  // unset: pores_NN.txt beside image_NN.*, if any
  WarpRequest print;
};

const std::vector<OptionRow<SynthRequest>>& synth_options();

// A request made ready to run: exactly one of `scene` and `warp`.
struct ResolvedSynth {
  std::filesystem::path out_dir;
  std::optional<SceneSpec> scene;
  std::optional<PrintWarpSpec> warp;  // its print's size is filled in when the print is read
  std::filesystem::path print;
  std::optional<std::filesystem::path> marks;
  OptionSpelling spelling = OptionSpelling::cli;  // for the messages of run_synth
};

// Checks every value and the rules between them (RequestError in the front end's spelling):
// a scene's options not with a print, a print's only with one, a speed instead of a distance
// (not both), full slip with a travel speed; finds the marks beside a PolyU print.
ResolvedSynth resolve(const SynthRequest& request, OptionSpelling spelling);

struct SynthSummary {
  int frames = 0;
  int width_px = 0;
  int height_px = 0;
  std::size_t landmark_positions = 0;  // a scene's every landmark in every frame
  std::size_t marked_pores = 0;        // a print's marks
  double seconds = 0;
  std::string text;  // the line a front end prints, "synth: 30 frames of ..."
};

// Refuses an output folder over an input or holding stale frames, renders, writes frame_NNN.png,
// landmarks.csv and scene.json (write_sequence, write_print_sequence). `progress` is told of
// each rendered frame of a scene.
SynthSummary run_synth(const ResolvedSynth& synth, const std::string& command_line,
                       const std::function<void(int done, int total)>& progress = {});

// Refuses, before any work, to write a sequence of `frame_count` frames into `dir` (given by
// `option`) when it already holds images this run would not replace: `capture` and `evaluate`
// read every image of a folder as one sequence, so frames left by a longer earlier run, or any
// other image there, would silently join the new ones. Nothing is deleted for the user.
void refuse_stale_frames(const std::string& option, const std::filesystem::path& dir,
                         int frame_count);

}  // namespace tactile::capture
