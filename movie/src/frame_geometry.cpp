// Contactor shapes and strain colours; see frame_geometry.hpp.
#include "tactile/movie/frame_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace tactile::movie {

std::vector<double> neighbour_strain(const Layout& layout, std::span<const float> frame_um) {
  const std::int32_t rows = layout.rows;
  const std::int32_t cols = layout.cols;
  const bool along_x = layout.axis == DeflectionAxis::x;
  const double pitch_um = 1000.0 * (along_x ? layout.pitch_x_mm : layout.pitch_y_mm);
  const std::int32_t n_axis = along_x ? cols : rows;
  std::vector<double> strain(frame_um.size(), 0.0);
  for (std::int32_t r = 0; r < rows; ++r) {
    for (std::int32_t c = 0; c < cols; ++c) {
      const std::int32_t k = along_x ? c : r;
      if (n_axis < 2) continue;
      const std::int32_t lo = std::max(k - 1, 0);
      const std::int32_t hi = std::min(k + 1, n_axis - 1);
      const auto at = [&](std::int32_t j) {
        return static_cast<double>(along_x ? frame_um[static_cast<std::size_t>(r * cols + j)]
                                           : frame_um[static_cast<std::size_t>(j * cols + c)]);
      };
      strain[static_cast<std::size_t>(r * cols + c)] = (at(hi) - at(lo)) / ((hi - lo) * pitch_um);
    }
  }
  return strain;
}

double auto_magnification(const Layout& layout) {
  const double pitch_um =
      1000.0 * (layout.axis == DeflectionAxis::x ? layout.pitch_x_mm : layout.pitch_y_mm);
  const double range_um =
      std::max(std::abs(layout.deflection_min_um), std::abs(layout.deflection_max_um));
  return range_um > 0 ? 0.4 * pitch_um / range_um : 1.0;
}

double auto_magnification(const TactileMovie& movie) {
  float peak_um = 0;
  for (float d : movie.deflection_um) peak_um = std::max(peak_um, std::abs(d));
  if (!(peak_um > 0)) return auto_magnification(movie.layout);
  const Layout& layout = movie.layout;
  const double pitch_um =
      1000.0 * (layout.axis == DeflectionAxis::x ? layout.pitch_x_mm : layout.pitch_y_mm);
  return 0.4 * pitch_um / peak_um;
}

std::vector<ContactorShape> frame_shapes(const Layout& layout, std::span<const float> frame_um,
                                         double magnification) {
  const std::vector<double> strain = neighbour_strain(layout, frame_um);
  std::vector<ContactorShape> shapes(frame_um.size());
  for (std::int32_t r = 0; r < layout.rows; ++r) {
    for (std::int32_t c = 0; c < layout.cols; ++c) {
      const auto i = static_cast<std::size_t>(r * layout.cols + c);
      ContactorShape& s = shapes[i];
      s.rest_x_mm = c * layout.pitch_x_mm;
      s.rest_y_mm = r * layout.pitch_y_mm;
      const double shift_mm = frame_um[i] * magnification / 1000.0;
      s.x_mm = s.rest_x_mm + (layout.axis == DeflectionAxis::x ? shift_mm : 0.0);
      s.y_mm = s.rest_y_mm + (layout.axis == DeflectionAxis::y ? shift_mm : 0.0);
      s.width_mm = layout.contactor_width_mm;
      s.height_mm = layout.contactor_height_mm;
      s.strain = strain[i];
    }
  }
  return shapes;
}

ViewTransform fit_view(const Layout& l, double magnification, int width_px, int height_px) {
  const double reach_mm = magnification *
                          std::max(std::abs(l.deflection_min_um), std::abs(l.deflection_max_um)) /
                          1000.0;
  const double w_mm = (l.cols - 1) * l.pitch_x_mm + l.contactor_width_mm +
                      (l.axis == DeflectionAxis::x ? 2 * reach_mm : 0);
  const double h_mm = (l.rows - 1) * l.pitch_y_mm + l.contactor_height_mm +
                      (l.axis == DeflectionAxis::y ? 2 * reach_mm : 0);
  ViewTransform t;
  t.px_per_mm = 0.88 * std::min(width_px / w_mm, height_px / h_mm);
  t.origin_x_px = (width_px - (l.cols - 1) * l.pitch_x_mm * t.px_per_mm) / 2;
  t.origin_y_px = (height_px - (l.rows - 1) * l.pitch_y_mm * t.px_per_mm) / 2;
  return t;
}

std::array<std::uint8_t, 3> strain_colour(double strain, double full_scale) {
  const double t = full_scale > 0 ? std::clamp(strain / full_scale, -1.0, 1.0) : 0.0;
  // White fades to saturated red (stretch) or blue (compression).
  const auto fade = static_cast<std::uint8_t>(std::lround(255.0 * (1.0 - std::abs(t))));
  if (t >= 0) return {255, fade, fade};
  return {fade, fade, 255};
}

double movie_strain_full_scale(const TactileMovie& movie) {
  double peak = 0;
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    for (double s : neighbour_strain(movie.layout, movie.frame(f)))
      peak = std::max(peak, std::abs(s));
  }
  return peak;
}

}  // namespace tactile::movie
