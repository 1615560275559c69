// GLFW emulator window; see viewer.hpp.
#include "tactile/display/viewer.hpp"
#include "tactile/display/viewer_gl.hpp"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl2.h>
#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "tactile/common/stop_signals.hpp"
#include "tactile/movie/frame_geometry.hpp"

namespace tactile::display {

namespace {

struct PlaybackState {
  bool playing = true;
  bool loop = true;
  double speed = 1;
  double position = 0;  // fractional frame index
  std::int32_t frames = 0;
};

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int /*mods*/) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  auto* s = static_cast<PlaybackState*>(glfwGetWindowUserPointer(window));
  switch (key) {
    case GLFW_KEY_SPACE:
      s->playing = !s->playing;
      break;
    case GLFW_KEY_RIGHT:
      s->playing = false;
      s->position = std::min(std::floor(s->position) + 1, static_cast<double>(s->frames - 1));
      break;
    case GLFW_KEY_LEFT:
      s->playing = false;
      s->position = std::max(std::floor(s->position) - 1, 0.0);
      break;
    case GLFW_KEY_UP:
      s->speed = std::min(s->speed * 2, 64.0);
      break;
    case GLFW_KEY_DOWN:
      s->speed = std::max(s->speed / 2, 1.0 / 64);
      break;
    case GLFW_KEY_L:
      s->loop = !s->loop;
      break;
    case GLFW_KEY_HOME:
      s->position = 0;
      break;
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q:
      glfwSetWindowShouldClose(window, GLFW_TRUE);
      break;
    default:
      break;
  }
}

// Draws the text, counts the frame, reads the pixels back when it is the last one wanted and
// shows it; true when the viewer should close.
bool finish_frame(GLFWwindow* window, int fb_w, int fb_h, std::int64_t exit_after_frames,
                  ViewerResult& result, bool keep_image = false) {
  gl::render_imgui_frame();
  ++result.frames_drawn;
  const bool last = exit_after_frames >= 0 && result.frames_drawn >= exit_after_frames;
  if (last || keep_image) result.last_image = gl::read_pixels(fb_w, fb_h);
  glfwSwapBuffers(window);
  return last;
}

}  // namespace

ViewerResult run_viewer(const movie::TactileMovie& movie, const ViewerOptions& options) {
  validate_movie(movie);
  if (options.field) validate_side_field(*options.field);
  ViewerResult result;
  movie::TactileMovie shown;
  std::int64_t lead_in_frames = 0;  // shown frames before the movie's first (the start ramp)
  std::vector<DeviceTick> states;   // the firmware after each shown frame (through_device)
  if (options.through_device) {
    EmulatedDeviceOptions device = options.device;
    device.layout = movie.layout;
    shown = render_through_device(movie, device, options.play, &result.device_report, &states);
    lead_in_frames = result.device_report.ramp_frames / 2;
  } else {
    shown = movie;
  }
  if (shown.frame_count == 0) throw std::invalid_argument("movie has no frames to show");
  const double magnification =
      options.magnification > 0 ? options.magnification : movie::auto_magnification(shown.layout);
  const double strain_scale = std::max(movie::movie_strain_full_scale(shown), 1e-6);

  const int width_px = options.field ? options.width_px * 2 : options.width_px;

  PlaybackState state;
  state.playing = !options.start_paused;
  state.loop = options.loop;
  state.speed = options.speed > 0 ? options.speed : 1.0;
  state.frames = shown.frame_count;
  state.position = std::clamp(static_cast<double>(lead_in_frames) + options.start_s * shown.rate_hz,
                              0.0, static_cast<double>(shown.frame_count - 1));
  gl::Window win(width_px, options.height_px, options.visible, !options.fixed_step, "tactile view",
                 on_key, &state);
  GLFWwindow* window = win.handle();

  result.shown_frame_count = shown.frame_count;
  double last_time = glfwGetTime();
  std::size_t next_event = 0;
  PointerEvent pointer;
  bool was_pressed = false;
  bool scrubbing = false;
  // A stop request closes the window: the emulated device's output already ends at rest (the
  // movie was rendered through it, ramps included), and nothing physical is left to ramp.
  while (!glfwWindowShouldClose(window) && !stop_requested(options.play.stop_fd)) {
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    const ViewerPanes panes = viewer_panes(fb_w, fb_h, options.field.has_value());

    // Pointer: scripted events, else the mouse (window coordinates scaled to framebuffer).
    if (!options.scripted_pointer.empty()) {
      while (next_event < options.scripted_pointer.size() &&
             options.scripted_pointer[next_event].at_frame <= result.frames_drawn) {
        pointer = options.scripted_pointer[next_event++];
      }
    } else {
      int win_w = 1, win_h = 1;
      glfwGetWindowSize(window, &win_w, &win_h);
      double cx = 0, cy = 0;
      glfwGetCursorPos(window, &cx, &cy);
      pointer.x_px = cx * fb_w / std::max(win_w, 1);
      pointer.y_px = cy * fb_h / std::max(win_h, 1);
      pointer.pressed = glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    }
    if (pointer.pressed && !was_pressed)
      scrubbing = panes.scrub.contains(pointer.x_px, pointer.y_px);
    if (!pointer.pressed) scrubbing = false;
    was_pressed = pointer.pressed;
    if (scrubbing) state.position = scrub_frame(panes.scrub, pointer.x_px, shown.frame_count);

    const auto frame = static_cast<std::int32_t>(
        std::clamp(std::floor(state.position), 0.0, static_cast<double>(shown.frame_count - 1)));
    const double movie_t_s = static_cast<double>(frame - lead_in_frames) / shown.rate_hz;
    gl::begin_pixels(fb_w, fb_h);
    gl::draw_contactors(shown.layout, shown.frame(frame), magnification, strain_scale,
                        panes.contactors);
    if (options.field) {
      result.last_field_frame = movie::field_frame_at(*options.field, movie_t_s);
      gl::draw_field(*options.field, options.field->frames[result.last_field_frame], panes.field);
    }
    gl::draw_scrub(panes.scrub, frame, shown.frame_count);

    gl::begin_info_strip(panes.info);
    ImGui::TextUnformatted(fmt::format("{}   t = {:.3f} s   frame {}/{}{}", shown.layout.name,
                                       movie_t_s, frame + 1, shown.frame_count,
                                       state.playing ? "" : "   (paused)")
                               .c_str());
    ImGui::TextUnformatted(
        fmt::format("speed x{:g}   loop {}   magnification x{:.1f} (white bar: {:g} um)",
                    state.speed, state.loop ? "on" : "off", magnification,
                    std::max(std::abs(shown.layout.deflection_min_um),
                             std::abs(shown.layout.deflection_max_um)))
            .c_str());
    if (options.through_device && static_cast<std::size_t>(frame) < states.size()) {
      const DeviceTick& d = states[static_cast<std::size_t>(frame)];
      result.last_device_tick = d;
      ImGui::TextUnformatted(
          fmt::format("emulated firmware: {}, FIFO {}; so far {} clamped, {} slew-limited, "
                      "{} underruns, {} watchdog trips",
                      !d.started    ? "stopped"
                      : d.streaming ? "streaming"
                                    : "idle (neutral)",
                      d.fifo_fill, d.clamped_samples, d.slew_limited_samples, d.underruns,
                      d.watchdog_trips)
              .c_str());
    } else {
      ImGui::TextUnformatted("raw movie (not through the emulated firmware)");
    }
    ImGui::TextUnformatted(
        "space play/pause  arrows step  up/down speed  L loop  Home start  drag bar: seek");
    ImGui::End();
    if (options.field) {
      ImGui::GetForegroundDrawList()->AddText(
          ImVec2(static_cast<float>(panes.field.x + 8), static_cast<float>(panes.field.y + 4)),
          IM_COL32(230, 230, 230, 255),
          fmt::format("{}\nblack {:+.1f} % compressed .. white {:+.1f} % stretched",
                      options.field->title, -100 * options.field->full_scale,
                      100 * options.field->full_scale)
              .c_str());
    }
    result.last_movie_frame = frame;
    if (finish_frame(window, fb_w, fb_h, options.exit_after_frames, result)) break;
    glfwPollEvents();
    const double now = glfwGetTime();
    if (state.playing && !scrubbing) {
      state.position += options.fixed_step ? 1.0 : (now - last_time) * shown.rate_hz * state.speed;
      if (state.position >= shown.frame_count) {
        if (state.loop) {
          state.position = std::fmod(state.position, shown.frame_count);
        } else {
          state.position = shown.frame_count - 1;
          state.playing = false;
        }
      }
    }
    last_time = now;
  }
  return result;
}

ViewerResult run_live_viewer(const movie::Layout& layout,
                             const std::function<std::optional<LiveFrame>()>& next,
                             const LiveViewerOptions& options) {
  const double magnification =
      options.magnification > 0 ? options.magnification : movie::auto_magnification(layout);
  // Neighbours at opposite ends of the range: full colour.
  const double strain_scale = std::max(layout.deflection_max_um - layout.deflection_min_um, 1e-3) *
                              1e-3 / std::min(layout.pitch_x_mm, layout.pitch_y_mm);
  gl::Window win(options.width_px, options.height_px, options.visible, true, "tactile live");
  GLFWwindow* window = win.handle();
  ViewerResult result;
  const auto n = static_cast<std::size_t>(layout.contactor_count());
  while (!glfwWindowShouldClose(window)) {
    const std::optional<LiveFrame> frame = next();
    if (!frame) break;
    if (frame->deflection_um.size() != n) {
      throw std::invalid_argument(fmt::format("live frame has {} deflections; layout '{}' has {}",
                                              frame->deflection_um.size(), layout.name, n));
    }
    if (frame->camera) {
      const CameraView& c = *frame->camera;
      if (c.width_px <= 0 || c.height_px <= 0 ||
          c.grey.size() != static_cast<std::size_t>(c.width_px) * c.height_px) {
        throw std::invalid_argument(fmt::format("live camera view of {} x {} px has {} pixels",
                                                c.width_px, c.height_px, c.grey.size()));
      }
    }
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    const ViewerPanes panes = viewer_panes(fb_w, fb_h, frame->camera.has_value());
    gl::begin_pixels(fb_w, fb_h);
    gl::draw_contactors(layout, frame->deflection_um, magnification, strain_scale,
                        panes.contactors);
    if (frame->camera) gl::draw_camera(*frame->camera, panes.field);
    gl::begin_info_strip(panes.info);
    for (const std::string& line : frame->lines) ImGui::TextUnformatted(line.c_str());
    ImGui::End();
    if (finish_frame(window, fb_w, fb_h, options.exit_after_frames, result,
                     options.keep_last_image)) {
      break;
    }
    glfwPollEvents();
  }
  return result;
}

}  // namespace tactile::display
