#include "tactile/movie/side_field.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tactile::movie {

std::uint8_t field_grey(double value, double full_scale) {
  const double t = std::clamp(0.5 + 0.5 * value / full_scale, 0.0, 1.0);
  return static_cast<std::uint8_t>(std::lround(255.0 * t));
}

std::size_t field_frame_at(const SideField& field, double t_s) {
  if (field.frames.empty()) throw std::invalid_argument("side field has no frames");
  const auto after = std::upper_bound(field.frames.begin(), field.frames.end(), t_s,
                                      [](double t, const FieldFrame& f) { return t < f.t_s; });
  return after == field.frames.begin() ? 0
                                       : static_cast<std::size_t>(after - field.frames.begin()) - 1;
}

ViewTransform fit_field(const SideField& field, int width_px, int height_px) {
  const double margin = 0.06;
  const double usable_w = width_px * (1 - 2 * margin);
  const double usable_h = height_px * (1 - 2 * margin);
  ViewTransform t;
  t.px_per_mm = std::min(usable_w / field.width_mm, usable_h / field.height_mm);
  t.origin_x_px = (width_px - field.width_mm * t.px_per_mm) / 2;
  t.origin_y_px = (height_px - field.height_mm * t.px_per_mm) / 2;
  return t;
}

void validate_side_field(const SideField& field) {
  if (field.frames.empty()) throw std::invalid_argument("side field has no frames");
  if (!(field.full_scale > 0) || !std::isfinite(field.full_scale)) {
    throw std::invalid_argument(
        fmt::format("side field: full scale must be a positive number, got {}", field.full_scale));
  }
  if (!(field.width_mm > 0) || !(field.height_mm > 0) || !std::isfinite(field.width_mm) ||
      !std::isfinite(field.height_mm)) {
    throw std::invalid_argument(fmt::format("side field: extent must be positive, got {} x {} mm",
                                            field.width_mm, field.height_mm));
  }
  for (std::size_t i = 0; i < field.frames.size(); ++i) {
    const FieldFrame& f = field.frames[i];
    if (!std::isfinite(f.t_s) || (i > 0 && !(f.t_s > field.frames[i - 1].t_s))) {
      throw std::invalid_argument(fmt::format(
          "side field: frame {} starts at {} s, not after the previous frame", i, f.t_s));
    }
    for (const FieldSegment& s : f.segments) {
      if (!std::isfinite(s.x0_mm) || !std::isfinite(s.y0_mm) || !std::isfinite(s.x1_mm) ||
          !std::isfinite(s.y1_mm)) {
        throw std::invalid_argument(
            fmt::format("side field: frame {} has a segment with a non-finite end", i));
      }
    }
  }
}

}  // namespace tactile::movie
