// GLFW emulator window; see viewer.hpp.
#include "tactile/display/viewer.hpp"

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

// GLFW reports errors through a callback; keep the last one to put in exceptions. It is
// thread-local because GLFW calls it on the thread that made the failing call.
thread_local std::string g_last_glfw_error;

void on_glfw_error(int code, const char* description) {
  g_last_glfw_error = fmt::format("GLFW error {}: {}", code, description ? description : "?");
}

bool env_set(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0';
}

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

void fill_rect(const PixelRect& r, std::array<std::uint8_t, 3> rgb) {
  glColor3ub(rgb[0], rgb[1], rgb[2]);
  glBegin(GL_QUADS);
  glVertex2d(r.x, r.y);
  glVertex2d(r.x + r.width, r.y);
  glVertex2d(r.x + r.width, r.y + r.height);
  glVertex2d(r.x, r.y + r.height);
  glEnd();
}

void begin_pixels(int width, int height) {
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, height, 0, -1, 1);  // pixel coordinates, y down like the preview image
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.25f, 0.25f, 0.25f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void draw_contactors(const movie::Layout& layout, std::span<const float> frame,
                     double magnification, double strain_scale, const PixelRect& pane) {
  const movie::ViewTransform t = pane_view(layout, magnification, pane);
  const auto px = [&](double x_mm) { return t.origin_x_px + x_mm * t.px_per_mm; };
  const auto py = [&](double y_mm) { return t.origin_y_px + y_mm * t.px_per_mm; };
  const std::vector<movie::ContactorShape> shapes =
      movie::frame_shapes(layout, frame, magnification);
  for (const movie::ContactorShape& c : shapes) {
    const double x0 = px(c.x_mm - c.width_mm / 2), x1 = px(c.x_mm + c.width_mm / 2);
    const double y0 = py(c.y_mm - c.height_mm / 2), y1 = py(c.y_mm + c.height_mm / 2);
    const auto rgb = movie::strain_colour(c.strain, strain_scale);
    glColor3ub(rgb[0], rgb[1], rgb[2]);
    glBegin(GL_QUADS);
    glVertex2d(x0, y0);
    glVertex2d(x1, y0);
    glVertex2d(x1, y1);
    glVertex2d(x0, y1);
    glEnd();
    glColor3ub(0, 0, 0);
    glBegin(GL_LINE_LOOP);
    glVertex2d(x0, y0);
    glVertex2d(x1, y0);
    glVertex2d(x1, y1);
    glVertex2d(x0, y1);
    glEnd();
  }
  // Rest positions: small grey crosses, so displacement is visible even when paused.
  glColor3ub(150, 150, 150);
  glBegin(GL_LINES);
  for (const movie::ContactorShape& c : shapes) {
    const double x = px(c.rest_x_mm), y = py(c.rest_y_mm);
    glVertex2d(x - 3, y);
    glVertex2d(x + 3, y);
    glVertex2d(x, y - 3);
    glVertex2d(x, y + 3);
  }
  glEnd();
  // Scale bar along the pane's bottom: the layout's full deflection at this magnification.
  const double range_um =
      std::max(std::abs(layout.deflection_min_um), std::abs(layout.deflection_max_um));
  const double bar_px = range_um * magnification / 1000.0 * t.px_per_mm;
  const double bar_y = pane.y + pane.height - 6;
  glColor3ub(255, 255, 255);
  glLineWidth(3);
  glBegin(GL_LINES);
  glVertex2d(pane.x + 10, bar_y);
  glVertex2d(pane.x + 10 + bar_px, bar_y);
  glEnd();
  glLineWidth(1);
}

// The field's background: capture's strain maps' dark blue, against which black, grey and
// white edges all stand out.
constexpr std::array<std::uint8_t, 3> kFieldBackground{20, 40, 70};

void draw_field(const movie::SideField& field, const movie::FieldFrame& frame,
                const PixelRect& pane) {
  fill_rect(pane, kFieldBackground);
  const movie::ViewTransform t = pane_field_view(field, pane);
  glLineWidth(3);
  glBegin(GL_LINES);
  for (const movie::FieldSegment& s : frame.segments) {
    const std::uint8_t g = movie::field_grey(s.value, field.full_scale);
    glColor3ub(g, g, g);
    glVertex2d(t.origin_x_px + s.x0_mm * t.px_per_mm, t.origin_y_px + s.y0_mm * t.px_per_mm);
    glVertex2d(t.origin_x_px + s.x1_mm * t.px_per_mm, t.origin_y_px + s.y1_mm * t.px_per_mm);
  }
  glEnd();
  glLineWidth(1);
}

void draw_camera(const CameraView& view, const PixelRect& pane) {
  fill_rect(pane, kFieldBackground);
  if (view.width_px <= 0 || view.height_px <= 0) return;
  const CameraPlacement at = place_camera(view, pane);
  // The image as a texture: one upload a drawn frame (a camera frame is a few hundred KB).
  GLuint texture = 0;
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_2D, texture);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_LUMINANCE, view.width_px, view.height_px, 0, GL_LUMINANCE,
               GL_UNSIGNED_BYTE, view.grey.data());
  glEnable(GL_TEXTURE_2D);
  glColor3ub(255, 255, 255);
  const double x1 = at.x_px + view.width_px * at.scale, y1 = at.y_px + view.height_px * at.scale;
  glBegin(GL_QUADS);
  glTexCoord2d(0, 0);
  glVertex2d(at.x_px, at.y_px);
  glTexCoord2d(1, 0);
  glVertex2d(x1, at.y_px);
  glTexCoord2d(1, 1);
  glVertex2d(x1, y1);
  glTexCoord2d(0, 1);
  glVertex2d(at.x_px, y1);
  glEnd();
  glDisable(GL_TEXTURE_2D);
  glDeleteTextures(1, &texture);
  glLineWidth(2);
  glBegin(GL_LINES);
  for (const CameraEdge& e : view.edges) {
    const auto rgb = movie::strain_colour(e.strain, view.full_scale);
    glColor3ub(rgb[0], rgb[1], rgb[2]);
    glVertex2d(at.x_px + e.x0_px * at.scale, at.y_px + e.y0_px * at.scale);
    glVertex2d(at.x_px + e.x1_px * at.scale, at.y_px + e.y1_px * at.scale);
  }
  glEnd();
  glLineWidth(1);
}

// Scrub bar colours: the played part, the rest, and the handle.
constexpr std::array<std::uint8_t, 3> kScrubPlayed{70, 130, 200};
constexpr std::array<std::uint8_t, 3> kScrubRest{40, 40, 40};

void draw_scrub(const PixelRect& bar, std::int32_t frame, std::int32_t frames) {
  fill_rect(bar, kScrubRest);
  const double x = scrub_handle_x(bar, frame, frames);
  fill_rect({bar.x, bar.y, static_cast<int>(std::lround(x)) - bar.x, bar.height}, kScrubPlayed);
  fill_rect({static_cast<int>(std::lround(x)) - 1, bar.y - 3, 3, bar.height + 6}, {255, 255, 255});
}

RenderedImage read_pixels(int width, int height) {
  RenderedImage img;
  img.width = width;
  img.height = height;
  img.rgb.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  std::vector<std::uint8_t> bottom_up(img.rgb.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  const auto row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y) {
    std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(row * (height - 1 - y)), row,
                img.rgb.begin() + static_cast<std::ptrdiff_t>(row * y));
  }
  return img;
}

// glfwTerminate on every exit path.
struct GlfwSession {
  GlfwSession() {
    glfwSetErrorCallback(on_glfw_error);
    ok = glfwInit() == GLFW_TRUE;
  }
  ~GlfwSession() {
    if (ok) glfwTerminate();
  }
  bool ok = false;
};

// Dear ImGui on the window for text (legacy OpenGL 2 back end, like the drawing); also owns
// the window so that ImGui shuts down before it goes.
struct ImGuiSession {
  explicit ImGuiSession(GLFWwindow* w) : window(w) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL2_Init();
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL2_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
  GLFWwindow* window;
};

// Opens the window (after `session` initialised GLFW) and makes its GL context current.
GLFWwindow* open_window(int width_px, int height_px, bool visible, bool vsync) {
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(width_px, height_px, "tactile view", nullptr, nullptr);
  if (window == nullptr) throw std::runtime_error("cannot open a window: " + g_last_glfw_error);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(vsync ? 1 : 0);
  return window;
}

// Starts an ImGui frame with the text strip's window over `pane` (close it with ImGui::End).
void begin_info_strip(const PixelRect& pane) {
  ImGui_ImplOpenGL2_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(pane.x), static_cast<float>(pane.y)));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(pane.width), static_cast<float>(pane.height)));
  ImGui::Begin("info", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
}

// Draws the text, counts the frame, reads the pixels back when it is the last one wanted and
// shows it; true when the viewer should close.
bool finish_frame(GLFWwindow* window, int fb_w, int fb_h, std::int64_t exit_after_frames,
                  ViewerResult& result, bool keep_image = false) {
  ImGui::Render();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
  ++result.frames_drawn;
  const bool last = exit_after_frames >= 0 && result.frames_drawn >= exit_after_frames;
  if (last || keep_image) result.last_image = read_pixels(fb_w, fb_h);
  glfwSwapBuffers(window);
  return last;
}

}  // namespace

bool screen_available() {
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) return false;
  GlfwSession session;
  return session.ok;
}

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

  g_last_glfw_error.clear();
  GlfwSession session;
  if (!session.ok) throw std::runtime_error("cannot start GLFW: " + g_last_glfw_error);
  const int width_px = options.field ? options.width_px * 2 : options.width_px;
  GLFWwindow* window =
      open_window(width_px, options.height_px, options.visible, !options.fixed_step);

  PlaybackState state;
  state.playing = !options.start_paused;
  state.loop = options.loop;
  state.speed = options.speed > 0 ? options.speed : 1.0;
  state.frames = shown.frame_count;
  state.position = std::clamp(static_cast<double>(lead_in_frames) + options.start_s * shown.rate_hz,
                              0.0, static_cast<double>(shown.frame_count - 1));
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, on_key);  // before ImGui, which chains to it
  ImGuiSession gui(window);

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
    begin_pixels(fb_w, fb_h);
    draw_contactors(shown.layout, shown.frame(frame), magnification, strain_scale,
                    panes.contactors);
    if (options.field) {
      result.last_field_frame = movie::field_frame_at(*options.field, movie_t_s);
      draw_field(*options.field, options.field->frames[result.last_field_frame], panes.field);
    }
    draw_scrub(panes.scrub, frame, shown.frame_count);

    begin_info_strip(panes.info);
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
  g_last_glfw_error.clear();
  GlfwSession session;
  if (!session.ok) throw std::runtime_error("cannot start GLFW: " + g_last_glfw_error);
  GLFWwindow* window = open_window(options.width_px, options.height_px, options.visible, true);
  ImGuiSession gui(window);
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
    begin_pixels(fb_w, fb_h);
    draw_contactors(layout, frame->deflection_um, magnification, strain_scale, panes.contactors);
    if (frame->camera) draw_camera(*frame->camera, panes.field);
    begin_info_strip(panes.info);
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
