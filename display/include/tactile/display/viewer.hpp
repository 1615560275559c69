#pragma once
// tactile::display_viewer, the one display library that links GLFW, OpenGL and Dear ImGui.
// The on-screen emulator window (GLFW, legacy OpenGL, Dear ImGui for text): contactors at
// their rest positions displaced by their magnified deflection, coloured by stretch/compression
// between neighbours; beside them, when given, the source field (side_field.hpp) at the same
// movie time. By default it shows what the emulated firmware outputs for the movie (ramps,
// clamps, slew limits, watchdog included), not the raw movie.
//
// Window, top to bottom: a text strip (time, frame, speed, loop, magnification, the emulated
// firmware's counters), the contactors (left) and the field (right, when given), a scrub bar.
// Fed live (run_live_viewer), the right pane may show a camera's frame with its edges instead.
// Keys: space play/pause, right/left step one frame (and pause), up/down double/halve speed,
// L toggle loop, Home back to the start, Esc or Q close. Mouse: click or drag in the scrub bar
// to seek.

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/display/emulated_device.hpp"
#include "tactile/display/player.hpp"
#include "tactile/movie/side_field.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

struct PlayBackends;  // play_anywhere.hpp

// A rectangle of the window in framebuffer pixels, y down.
struct PixelRect {
  int x = 0;
  int y = 0;
  int width = 0;
  int height = 0;
  bool contains(double px, double py) const {
    return px >= x && px < x + width && py >= y && py < y + height;
  }
};

struct ViewerPanes {
  PixelRect info;        // text strip along the top
  PixelRect contactors;  // the array
  PixelRect field;       // the side field (empty without one)
  PixelRect scrub;       // seek bar along the bottom
};

// Where the viewer draws what in a width x height framebuffer.
ViewerPanes viewer_panes(int width_px, int height_px, bool with_field);

// The frame a click at x_px in the scrub bar seeks to: the bar's left edge is frame 0, its
// right edge the last frame, nearest frame in between (clamped outside the bar).
std::int32_t scrub_frame(const PixelRect& bar, double x_px, std::int32_t frame_count);

// Where frame `frame` puts the scrub bar's handle (its x in pixels).
double scrub_handle_x(const PixelRect& bar, std::int32_t frame, std::int32_t frame_count);

// fit_view() into a pane: the same transform, offset to the pane's corner.
movie::ViewTransform pane_view(const movie::Layout& layout, double magnification,
                               const PixelRect& pane);
movie::ViewTransform pane_field_view(const movie::SideField& field, const PixelRect& pane);

// A pointer state fed to the viewer instead of the real mouse from drawn frame `at_frame` on
// (tests and recordings drive the scrub bar with these, through the same code as the mouse).
struct PointerEvent {
  std::int64_t at_frame = 0;
  double x_px = 0;
  double y_px = 0;
  bool pressed = false;
};

struct ViewerOptions {
  bool through_device = true;    // show the emulated device's output instead of the raw movie
  EmulatedDeviceOptions device;  // its layout is replaced by the movie's
  PlayOptions play;
  double speed = 1.0;  // playback speed relative to the movie's rate
  // Off unless asked for: `view --loop` is a flag, which can only turn it on.
  bool loop = false;
  bool start_paused = false;
  double start_s = 0;  // movie time of the first frame shown (after the device's start ramp)
  int width_px = 800;  // doubled when a field is shown beside the array
  int height_px = 800;
  bool visible = true;
  double magnification = 0;  // 0 = movie::auto_magnification(layout)
  // For tests and recordings: advance exactly one movie frame per drawn window frame instead
  // of following the wall clock, and close after this many drawn frames (-1 = run until the
  // user closes the window).
  bool fixed_step = false;
  std::int64_t exit_after_frames = -1;
  std::vector<PointerEvent> scripted_pointer;  // in drawn-frame order; empty = the real mouse
  std::optional<movie::SideField> field;       // drawn beside the array, synchronised in time
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
  RenderedImage last_image;          // pixels of the last drawn frame, read back from OpenGL
  std::size_t last_field_frame = 0;  // index into options.field->frames, when given
  PlaybackReport device_report;      // the emulated firmware's counters (through_device)
  DeviceTick last_device_tick;       // its state at the last drawn frame, as the text shows it
};

// Writes the image as a PNG (a screenshot of the window). Throws std::runtime_error naming the
// file when it cannot be written, std::invalid_argument for an empty image.
void write_png(const std::filesystem::path& png, const RenderedImage& image);

// True when a display server is named (DISPLAY or WAYLAND_DISPLAY) and GLFW initialises.
bool screen_available();

// `backends` with the emulator window added (screen_available, run_viewer), for play_anywhere
// to open when no display takes the movie: what `tactile play` plays with.
PlayBackends with_window(PlayBackends backends);

// Opens the window and plays until closed (or exit_after_frames). Throws std::runtime_error
// naming the GLFW error when no window can be opened, std::invalid_argument for a movie the
// emulated device cannot play or an invalid side field.
ViewerResult run_viewer(const movie::TactileMovie& movie, const ViewerOptions& options = {});

// An edge of the skin between two tracked landmarks, in camera pixels, with its strain.
struct CameraEdge {
  float x0_px = 0, y0_px = 0, x1_px = 0, y1_px = 0;
  float strain = 0;  // relative length change
};

// A camera's frame with what was measured on it, drawn beside the contactors.
struct CameraView {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> grey;  // width x height, row-major
  std::vector<CameraEdge> edges;   // coloured by strain as the contactors are
  double full_scale = 0.01;        // |strain| drawn in full colour
};

// Where a camera view's image lands in `pane` (aspect kept, centred): origin and scale.
struct CameraPlacement {
  double x_px = 0, y_px = 0, scale = 1;
};
CameraPlacement place_camera(const CameraView& view, const PixelRect& pane);

// A live source instead of a movie (e.g. an emulated device on the network): what to show now.
struct LiveFrame {
  std::vector<float> deflection_um;  // row-major, one per contactor of the layout
  std::vector<std::string> lines;    // text for the strip along the top
  std::optional<CameraView> camera;  // shown in the right pane when given
};

struct LiveViewerOptions {
  int width_px = 800;
  int height_px = 800;
  bool visible = true;
  double magnification = 0;             // 0 = movie::auto_magnification(layout)
  std::int64_t exit_after_frames = -1;  // for tests: close after this many drawn frames
  // Read every drawn frame back into ViewerResult::last_image (a screenshot of a window whose
  // last frame is not known in advance, at the cost of a read-back a frame).
  bool keep_last_image = false;
};

// Opens the window and draws what `next` returns, once per drawn frame (at the screen's
// refresh rate), until the window is closed, `next` returns nothing, or exit_after_frames.
// Throws std::runtime_error when no window can be opened, std::invalid_argument for a frame
// of the wrong size.
ViewerResult run_live_viewer(const movie::Layout& layout,
                             const std::function<std::optional<LiveFrame>()>& next,
                             const LiveViewerOptions& options = {});

}  // namespace tactile::display
