// GLFW emulator window; see viewer.hpp.
#include "tactile/display/viewer.hpp"

#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "tactile/display/frame_geometry.hpp"

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

void draw_frame(const Layout& layout, std::span<const float> frame, double magnification,
                double strain_scale, int width, int height) {
  glViewport(0, 0, width, height);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, height, 0, -1, 1);  // pixel coordinates, y down like the preview image
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glClearColor(0.25f, 0.25f, 0.25f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const ViewTransform t = fit_view(layout, magnification, width, height);
  const auto px = [&](double x_mm) { return t.origin_x_px + x_mm * t.px_per_mm; };
  const auto py = [&](double y_mm) { return t.origin_y_px + y_mm * t.px_per_mm; };
  const std::vector<ContactorShape> shapes = frame_shapes(layout, frame, magnification);
  for (const ContactorShape& c : shapes) {
    const double x0 = px(c.x_mm - c.width_mm / 2), x1 = px(c.x_mm + c.width_mm / 2);
    const double y0 = py(c.y_mm - c.height_mm / 2), y1 = py(c.y_mm + c.height_mm / 2);
    const auto rgb = strain_colour(c.strain, strain_scale);
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
  for (const ContactorShape& c : shapes) {
    const double x = px(c.rest_x_mm), y = py(c.rest_y_mm);
    glVertex2d(x - 3, y);
    glVertex2d(x + 3, y);
    glVertex2d(x, y - 3);
    glVertex2d(x, y + 3);
  }
  glEnd();
  // Scale bar along the bottom: the layout's full deflection at the current magnification.
  const double range_um =
      std::max(std::abs(layout.deflection_min_um), std::abs(layout.deflection_max_um));
  const double bar_px = range_um * magnification / 1000.0 * t.px_per_mm;
  glColor3ub(255, 255, 255);
  glLineWidth(3);
  glBegin(GL_LINES);
  glVertex2d(10, height - 12);
  glVertex2d(10 + bar_px, height - 12);
  glEnd();
  glLineWidth(1);
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

}  // namespace

bool screen_available() {
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) return false;
  GlfwSession session;
  return session.ok;
}

ViewerResult run_viewer(const TactileMovie& movie, const ViewerOptions& options) {
  validate(movie);
  TactileMovie shown;
  if (options.through_device) {
    EmulatedDeviceOptions device = options.device;
    device.layout = movie.layout;
    shown = render_through_device(movie, device, options.play);
  } else {
    shown = movie;
  }
  if (shown.frame_count == 0) throw std::invalid_argument("movie has no frames to show");
  const double magnification =
      options.magnification > 0 ? options.magnification : auto_magnification(shown.layout);
  const double strain_scale = std::max(movie_strain_full_scale(shown), 1e-6);

  g_last_glfw_error.clear();
  GlfwSession session;
  if (!session.ok) throw std::runtime_error("cannot start GLFW: " + g_last_glfw_error);
  glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window =
      glfwCreateWindow(options.width_px, options.height_px, "tactile view", nullptr, nullptr);
  if (window == nullptr) throw std::runtime_error("cannot open a window: " + g_last_glfw_error);
  glfwMakeContextCurrent(window);
  glfwSwapInterval(options.fixed_step ? 0 : 1);

  PlaybackState state;
  state.playing = !options.start_paused;
  state.loop = options.loop;
  state.speed = options.speed > 0 ? options.speed : 1.0;
  state.frames = shown.frame_count;
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, on_key);

  ViewerResult result;
  result.shown_frame_count = shown.frame_count;
  double last_time = glfwGetTime();
  std::int32_t titled_frame = -1;
  while (!glfwWindowShouldClose(window)) {
    const auto frame = static_cast<std::int32_t>(
        std::clamp(std::floor(state.position), 0.0, static_cast<double>(shown.frame_count - 1)));
    int fb_w = 0, fb_h = 0;
    glfwGetFramebufferSize(window, &fb_w, &fb_h);
    draw_frame(shown.layout, shown.frame(frame), magnification, strain_scale, fb_w, fb_h);
    result.last_movie_frame = frame;
    ++result.frames_drawn;
    const bool last =
        options.exit_after_frames >= 0 && result.frames_drawn >= options.exit_after_frames;
    if (last) result.last_image = read_pixels(fb_w, fb_h);
    glfwSwapBuffers(window);
    if (last) break;
    if (frame != titled_frame) {
      // Text stays out of the GL drawing (legacy GL has no fonts); the title carries it.
      glfwSetWindowTitle(window,
                         fmt::format("tactile view - {} - t = {:.3f} s - frame {}/{} - x{:.1f} - "
                                     "speed {:g}{}{}",
                                     shown.layout.name, frame / shown.rate_hz, frame + 1,
                                     shown.frame_count, magnification, state.speed,
                                     state.loop ? " - loop" : "", state.playing ? "" : " - paused")
                             .c_str());
      titled_frame = frame;
    }
    glfwPollEvents();
    const double now = glfwGetTime();
    if (state.playing) {
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
  glfwDestroyWindow(window);
  return result;
}

}  // namespace tactile::display
