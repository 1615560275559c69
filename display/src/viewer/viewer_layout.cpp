// Where the viewer draws what (viewer.hpp): panes, scrub bar, pane transforms.
#include <algorithm>
#include <cmath>

#include "tactile/display/viewer.hpp"

namespace tactile::display {

namespace {

constexpr int kInfoHeightPx = 76;   // four lines of ImGui's default 13 px font, with padding
constexpr int kScrubHeightPx = 20;  // the seek bar
constexpr int kScrubMarginPx = 10;  // around the seek bar

}  // namespace

ViewerPanes viewer_panes(int width_px, int height_px, bool with_field) {
  ViewerPanes p;
  p.info = {0, 0, width_px, std::min(kInfoHeightPx, height_px)};
  const int scrub_y = std::max(p.info.height, height_px - kScrubMarginPx - kScrubHeightPx);
  p.scrub = {kScrubMarginPx, scrub_y, std::max(1, width_px - 2 * kScrubMarginPx), kScrubHeightPx};
  const int middle_y = p.info.height;
  const int middle_h = std::max(1, scrub_y - kScrubMarginPx - middle_y);
  if (with_field) {
    const int half = width_px / 2;
    p.contactors = {0, middle_y, half, middle_h};
    p.field = {half, middle_y, width_px - half, middle_h};
  } else {
    p.contactors = {0, middle_y, width_px, middle_h};
  }
  return p;
}

std::int32_t scrub_frame(const PixelRect& bar, double x_px, std::int32_t frame_count) {
  if (frame_count <= 1 || bar.width <= 1) return 0;
  const double f = std::clamp((x_px - bar.x) / (bar.width - 1), 0.0, 1.0);
  return static_cast<std::int32_t>(std::lround(f * (frame_count - 1)));
}

double scrub_handle_x(const PixelRect& bar, std::int32_t frame, std::int32_t frame_count) {
  if (frame_count <= 1) return bar.x;
  return bar.x + static_cast<double>(frame) / (frame_count - 1) * (bar.width - 1);
}

movie::ViewTransform pane_view(const movie::Layout& layout, double magnification,
                               const PixelRect& pane) {
  movie::ViewTransform t = movie::fit_view(layout, magnification, pane.width, pane.height);
  t.origin_x_px += pane.x;
  t.origin_y_px += pane.y;
  return t;
}

movie::ViewTransform pane_field_view(const movie::SideField& field, const PixelRect& pane) {
  movie::ViewTransform t = movie::fit_field(field, pane.width, pane.height);
  t.origin_x_px += pane.x;
  t.origin_y_px += pane.y;
  return t;
}

CameraPlacement place_camera(const CameraView& view, const PixelRect& pane) {
  CameraPlacement at;
  if (view.width_px <= 0 || view.height_px <= 0) return at;
  at.scale = std::min(static_cast<double>(pane.width) / view.width_px,
                      static_cast<double>(pane.height) / view.height_px);
  at.x_px = pane.x + (pane.width - view.width_px * at.scale) / 2;
  at.y_px = pane.y + (pane.height - view.height_px * at.scale) / 2;
  return at;
}

}  // namespace tactile::display
