#pragma once
// Scene options shared by `tactile synth` and `tactile demo`.

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

#include "mode_option.hpp"
#include "number_checks.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::cli {

// Refuses, before any work, to write a sequence of `frame_count` frames into `dir` (given by
// `option`) when it already holds images this run would not replace: `capture` and `evaluate`
// read every image of a folder as one sequence, so frames left by a longer earlier run, or any
// other image there, would silently join the new ones. Nothing is deleted for the user.
void refuse_stale_frames(const std::string& option, const std::filesystem::path& dir,
                         int frame_count);

// `print_too`: the command also makes sequences from a print (synth --from-print).
inline void add_scene_options(CLI::App& sub, capture::SceneSpec& spec, bool print_too = false) {
  add_mode_option(sub, "--scene", spec.scene, capture::kSceneNames,
                  "Scene: bump, hole, flat-slide (slide over a feature or flat glass), "
                  "flat-rotate (press and twist), flat-stick-slip (push back and forth with a "
                  "sticking centre)");
  // With prints there are two defaults, one per kind of sequence: said in words, as a single
  // "[180]" would be wrong for a print.
  sub.add_option("--frames", spec.frame_count,
                 print_too ? fmt::format("Number of camera frames (default {} for a scene, {} "
                                         "with --from-print)",
                                         capture::SceneSpec{}.frame_count,
                                         capture::PrintWarpSpec{}.frame_count)
                           : fmt::format("Number of camera frames (default {})",
                                         capture::SceneSpec{}.frame_count))
      ->check(within(2, 100000));
  sub.add_option("--speed", spec.speed_mm_per_s, "Sliding speed in mm/s")
      ->check(within(0.0, 100.0))
      ->capture_default_str();
  sub.add_option("--height", spec.feature_height_mm, "Bump height / hole depth in mm")
      ->check(within(0.0, 5.0))
      ->capture_default_str();
  sub.add_option("--width", spec.feature_width_mm, "Bump / hole width (FWHM) in mm")
      ->check(within(0.1, 50.0))
      ->capture_default_str();
  sub.add_option("--contact-semi-x", spec.contact_semi_x_mm,
                 "Half-width of the fingertip contact patch along the slide, mm")
      ->check(within(0.5, 20.0))
      ->capture_default_str();
  sub.add_option("--rotation", spec.rotation_deg, "flat-rotate: twist at the last frame, degrees")
      ->check(within(-45.0, 45.0))
      ->capture_default_str();
  sub.add_option("--lateral-amplitude", spec.lateral_amplitude_mm,
                 "flat-stick-slip: peak rim displacement, mm")
      ->check(within(-3.0, 3.0))
      ->capture_default_str();
  sub.add_option("--stick-ratio", spec.stick_ratio,
                 "flat-rotate, flat-stick-slip: stick radius / contact radius")
      ->check(within(0.0, 0.9))
      ->capture_default_str();
  sub.add_option("--noise", spec.noise_sigma, "Camera noise, grey levels (sigma)")
      ->check(within(0.0, 128.0))
      ->capture_default_str();
  sub.add_option("--seed", spec.seed, "Random seed (same seed, same images)")
      ->check(seed_number())
      ->capture_default_str();
}

}  // namespace tactile::cli
