#pragma once
// `tactile author`: the mapping's choices in a panel (made from mapping::map_options(), the
// table `map` and Python read), re-mapped in the background on every change (remapper.hpp),
// the strain field and the contactor array side by side at the scrubbed time, the fidelity
// figures and a chart of them over time, contactors that saturate (red) or are slew-limited
// (yellow) outlined, A/B, audition on whatever `play` would choose, and Save (save.hpp).
//
// Keys (also listed by H): space play/pause, left/right step, Home start; M / shift+M next /
// previous method, N normalisation, T strain mode, Y layout, G / shift+G gain x2 / /2, F /
// shift+F peak fraction +/- 0.1, E / shift+E reference frame +/- 10, R rate (the layout's own, a
// half, a quarter); P pin
// the current mapping as A, Tab show A / the current one (B); Enter audition from the scrubbed
// time (again: stop, ramping to rest), O audition looped or once; S save; H or F1 help; Esc or
// Q close. Every key has a control in the panel for the mouse.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/author/outcome.hpp"
#include "tactile/author/save.hpp"
#include "tactile/display/play_anywhere.hpp"

namespace tactile::author {

struct AuthorWindowOptions {
  std::filesystem::path strain_file;  // what Save's experiment names as its source
  std::filesystem::path out_dir;      // where Save writes
  std::string name = "authored";      // the saved experiment's name
  int width_px = 1400;
  int height_px = 860;
  bool visible = true;
  // Draw once the first mappings are made, write the window as this PNG and close.
  std::optional<std::filesystem::path> screenshot;
  std::int64_t exit_after_frames = -1;  // for tests: close after this many drawn frames
  int stop_fd = -1;                     // readable: close (an audition under way ramps to rest)
  // Where an audition plays besides the emulated device (no window: this is the window).
  display::PlayBackends audition_backends;
  // Set: auditions play on this Latero and nowhere else (a mapping for the latero layout).
  std::optional<display::LateroPlayTarget> audition_latero;
  // Events as lines a person reads (and tests parse): each mapping shown, pin, audition, save.
  std::function<void(const std::string&)> say;
};

struct AuthorWindowResult {
  std::int64_t frames_drawn = 0;
  double drawing_s = 0;  // from the first drawn frame to the last
  // Per change: from the change (key, click) to the first drawn frame showing its mapping.
  std::vector<double> change_to_view_ms;
  std::optional<Saved> saved;                  // the last Save
  std::vector<display::PlayResult> auditions;  // in order
  mapping::MapRequest current;
  std::optional<mapping::MapRequest> a;
};

// Opens the window on `strain` with `current` (and `a` pinned, when given) and runs until it
// is closed. Throws std::runtime_error when no window can be opened.
AuthorWindowResult run_author_window(std::shared_ptr<const capture::StrainMovie> strain,
                                     const mapping::MapRequest& current,
                                     const std::optional<mapping::MapRequest>& a,
                                     const AuthorWindowOptions& options);

}  // namespace tactile::author
