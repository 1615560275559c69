// The emulator window's GLFW window, ImGui frame and drawing; see viewer_gl.hpp.
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
#include <vector>

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

}  // namespace

bool screen_available() {
  if (!env_set("DISPLAY") && !env_set("WAYLAND_DISPLAY")) return false;
  glfwSetErrorCallback(on_glfw_error);
  const bool ok = glfwInit() == GLFW_TRUE;
  if (ok) glfwTerminate();
  return ok;
}

namespace gl {

Window::Window(int width_px, int height_px, bool visible, bool vsync, const char* title,
               KeyCallback on_key, void* user) {
  g_last_glfw_error.clear();
  glfwSetErrorCallback(on_glfw_error);
  if (glfwInit() != GLFW_TRUE) throw std::runtime_error("cannot start GLFW: " + g_last_glfw_error);
  glfw_ = true;
  glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  window_ = glfwCreateWindow(width_px, height_px, title, nullptr, nullptr);
  if (window_ == nullptr) {
    glfwTerminate();
    throw std::runtime_error("cannot open a window: " + g_last_glfw_error);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(vsync ? 1 : 0);
  if (on_key != nullptr) {
    glfwSetWindowUserPointer(window_, user);
    glfwSetKeyCallback(window_, on_key);  // before ImGui, which chains to it
  }
  // Dear ImGui for text and controls, on the legacy OpenGL 2 back end like the drawing.
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's folder
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
  ImGui_ImplOpenGL2_Init();
  imgui_ = true;
}

Window::~Window() {
  if (imgui_) {
    ImGui_ImplOpenGL2_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (window_ != nullptr) glfwDestroyWindow(window_);
  if (glfw_) glfwTerminate();
}

bool Window::should_close() const {
  return glfwWindowShouldClose(window_) != 0;
}

void Window::request_close() const {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}

std::array<int, 2> Window::framebuffer_px() const {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window_, &w, &h);
  return {w, h};
}

float Window::content_scale() const {
  float x = 1, y = 1;
  glfwGetWindowContentScale(window_, &x, &y);
  return std::max(1.0f, std::max(x, y));
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

void outline_rect(double x0, double y0, double x1, double y1, std::array<std::uint8_t, 3> rgb) {
  glColor3ub(rgb[0], rgb[1], rgb[2]);
  glBegin(GL_LINE_LOOP);
  glVertex2d(x0, y0);
  glVertex2d(x1, y0);
  glVertex2d(x1, y1);
  glVertex2d(x0, y1);
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
    outline_rect(x0, y0, x1, y1, {0, 0, 0});
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

void begin_imgui_frame() {
  ImGui_ImplOpenGL2_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
}

void render_imgui_frame() {
  ImGui::Render();
  ImGui_ImplOpenGL2_RenderDrawData(ImGui::GetDrawData());
}

// Starts an ImGui frame with the text strip's window over `pane` (close it with ImGui::End).
void begin_info_strip(const PixelRect& pane) {
  begin_imgui_frame();
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(pane.x), static_cast<float>(pane.y)));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(pane.width), static_cast<float>(pane.height)));
  ImGui::Begin("info", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
}

}  // namespace gl

}  // namespace tactile::display
