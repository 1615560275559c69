#pragma once
// The on-screen emulator window (GLFW, legacy OpenGL): contactors at their rest positions
// displaced by their magnified deflection, coloured by stretch/compression between
// neighbours. By default it shows what the emulated firmware outputs for the movie (ramps,
// clamps, slew limits, watchdog included), not the raw movie.
//
// Keys: space play/pause, right/left step one frame (and pause), up/down double/halve speed,
// L toggle loop, Home back to the start, Esc or Q close.

#include <array>
#include <cstdint>
#include <vector>

#include "tactile/display/emulated_device.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/tactile_movie.hpp"

namespace tactile::display {

struct ViewerOptions {
  bool through_device = true;    // show the emulated device's output instead of the raw movie
  EmulatedDeviceOptions device;  // its layout is replaced by the movie's
  PlayOptions play;
  double speed = 1.0;  // playback speed relative to the movie's rate
  bool loop = true;
  bool start_paused = false;
  int width_px = 800;
  int height_px = 800;
  bool visible = true;
  double magnification = 0;  // 0 = auto_magnification(layout)
  // For tests and recordings: advance exactly one movie frame per drawn window frame instead
  // of following the wall clock, and close after this many drawn frames (-1 = run until the
  // user closes the window).
  bool fixed_step = false;
  std::int64_t exit_after_frames = -1;
};

struct RenderedImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
  std::array<std::uint8_t, 3> at(int x, int y) const {
    const auto i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x)) *
                   3;
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

struct ViewerResult {
  std::int64_t frames_drawn = 0;
  std::int32_t last_movie_frame = 0;  // index into the shown frames (device output if through)
  std::int32_t shown_frame_count = 0;
  RenderedImage last_image;  // pixels of the last drawn frame, read back from OpenGL
};

// True when a display server is named (DISPLAY or WAYLAND_DISPLAY) and GLFW initialises.
bool screen_available();

// Opens the window and plays until closed (or exit_after_frames). Throws std::runtime_error
// naming the GLFW error when no window can be opened, std::invalid_argument for a movie the
// emulated device cannot play.
ViewerResult run_viewer(const TactileMovie& movie, const ViewerOptions& options = {});

}  // namespace tactile::display
