#pragma once
// The emulator window's drawing, shared by the windows built on it (the viewer, the live viewer,
// the authoring window): a GLFW window with Dear ImGui on it, legacy OpenGL in framebuffer
// pixels (y down), the contactor array and the side field as the viewer draws them, and reading
// a drawn frame back. Part of tactile_display_viewer, the one library that links GLFW, OpenGL
// and Dear ImGui; a program that includes this header links it.

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "tactile/display/viewer.hpp"

struct GLFWwindow;

namespace tactile::display::gl {

// GLFW initialised, one window with its GL context current and Dear ImGui on it; everything
// undone in the destructor, ImGui first. Throws std::runtime_error naming GLFW's error when
// GLFW does not start or no window opens.
class Window {
 public:
  // `on_key`, when given, is installed before ImGui (which chains to it) with `user` as the
  // window's user pointer. vsync off: frames as fast as drawn (tests, fixed-step playback).
  using KeyCallback = void (*)(GLFWwindow*, int key, int scancode, int action, int mods);
  Window(int width_px, int height_px, bool visible, bool vsync, const char* title,
         KeyCallback on_key = nullptr, void* user = nullptr);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  GLFWwindow* handle() const { return window_; }
  bool should_close() const;
  void request_close() const;
  // The framebuffer's size in pixels (differs from the window's on a scaled screen).
  std::array<int, 2> framebuffer_px() const;
  // The window content's scale (1 on a 96 dpi screen, 2 on a HiDPI one), for text and controls.
  float content_scale() const;

 private:
  GLFWwindow* window_ = nullptr;
  bool glfw_ = false;
  bool imgui_ = false;
};

// Clears the framebuffer and sets up pixel coordinates, y down.
void begin_pixels(int width_px, int height_px);
void fill_rect(const PixelRect& r, std::array<std::uint8_t, 3> rgb);
// The outline of the rectangle from (x0, y0) to (x1, y1), in pixels.
void outline_rect(double x0, double y0, double x1, double y1, std::array<std::uint8_t, 3> rgb);
// The array at its deflections, magnified, coloured by neighbour strain up to strain_scale, rest
// positions as grey crosses and a white scale bar of the layout's full deflection.
void draw_contactors(const movie::Layout& layout, std::span<const float> frame_um,
                     double magnification, double strain_scale, const PixelRect& pane);
void draw_field(const movie::SideField& field, const movie::FieldFrame& frame,
                const PixelRect& pane);
void draw_camera(const CameraView& view, const PixelRect& pane);
void draw_scrub(const PixelRect& bar, std::int32_t frame, std::int32_t frames);
// The back buffer's pixels, top row first.
RenderedImage read_pixels(int width_px, int height_px);

// Starts an ImGui frame (call after begin_pixels, draw ImGui, then finish_imgui_frame).
void begin_imgui_frame();
// Renders ImGui's frame over the drawing.
void render_imgui_frame();
// Starts an ImGui frame with a text strip over `pane` (close it with ImGui::End).
void begin_info_strip(const PixelRect& pane);

}  // namespace tactile::display::gl
