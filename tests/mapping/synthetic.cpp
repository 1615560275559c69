#include "synthetic.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace tactile::mapping::testing {

capture::StrainFrame make_frame(const GridSpec& grid, const Displacement& displacement, double t_s,
                                std::int32_t frame_from, std::int32_t frame_to) {
  const auto nx = static_cast<std::int32_t>(std::floor(grid.width_mm / grid.spacing_mm)) + 1;
  const auto ny = static_cast<std::int32_t>(std::floor(grid.height_mm / grid.spacing_mm)) + 1;
  std::mt19937 rng(grid.seed);
  std::uniform_real_distribution<double> jitter(-grid.jitter_fraction * grid.spacing_mm,
                                                grid.jitter_fraction * grid.spacing_mm);
  capture::StrainFrame frame;
  frame.frame_from = frame_from;
  frame.frame_to = frame_to;
  frame.t_s = t_s;
  for (std::int32_t j = 0; j < ny; ++j) {
    for (std::int32_t i = 0; i < nx; ++i) {
      const double x = i * grid.spacing_mm + jitter(rng);
      const double y = j * grid.spacing_mm + jitter(rng);
      const auto u = displacement(x, y, t_s);
      const std::int32_t id = j * nx + i;
      frame.points_from.push_back({id, frame_from, capture::FeatureType::pore, 0, 0, x, y});
      frame.points_to.push_back(
          {id, frame_to, capture::FeatureType::pore, 0, 0, x + u.x_mm, y + u.y_mm});
    }
  }
  const auto add_edge = [&](std::int32_t a, std::int32_t b) {
    const auto& pa = frame.points_from[static_cast<std::size_t>(a)];
    const auto& pb = frame.points_from[static_cast<std::size_t>(b)];
    const auto& qa = frame.points_to[static_cast<std::size_t>(a)];
    const auto& qb = frame.points_to[static_cast<std::size_t>(b)];
    const double from = std::hypot(pb.x_mm - pa.x_mm, pb.y_mm - pa.y_mm);
    const double to = std::hypot(qb.x_mm - qa.x_mm, qb.y_mm - qa.y_mm);
    frame.edges.push_back({a, b, from, to, (to - from) / from});
  };
  for (std::int32_t j = 0; j < ny; ++j) {
    for (std::int32_t i = 0; i < nx; ++i) {
      const std::int32_t p = j * nx + i;
      if (i + 1 < nx) add_edge(p, p + 1);
      if (j + 1 < ny) add_edge(p, p + nx);
      if (i + 1 < nx && j + 1 < ny) {
        add_edge(p, p + nx + 1);
        frame.triangles.push_back({{p, p + 1, p + nx + 1}});
        frame.triangles.push_back({{p, p + nx + 1, p + nx}});
      }
    }
  }
  return frame;
}

capture::StrainMovie make_movie(const GridSpec& grid, const Displacement& displacement,
                                std::int32_t frames, double frame_rate_hz) {
  capture::StrainMovie movie;
  movie.frame_rate_hz = frame_rate_hz;
  movie.span_frames = 1;
  movie.camera_frame_count = frames + 1;
  movie.field_width_mm = grid.width_mm;
  movie.field_height_mm = grid.height_mm;
  movie.provenance.input = "synthetic test grid";
  for (std::int32_t k = 1; k <= frames; ++k) {
    movie.frames.push_back(make_frame(grid, displacement, k / frame_rate_hz, k - 1, k));
  }
  return movie;
}

void add_tracks(capture::StrainMovie& movie) {
  for (const auto& p : movie.frames.front().points_from) movie.tracks.push_back(p);
  for (const auto& f : movie.frames) {
    for (const auto& p : f.points_to) movie.tracks.push_back(p);
  }
  std::stable_sort(movie.tracks.begin(), movie.tracks.end(),
                   [](const auto& a, const auto& b) { return a.track_id < b.track_id; });
}

movie::Layout grid_layout(std::int32_t rows, std::int32_t cols, double pitch_x_mm,
                          double pitch_y_mm, movie::DeflectionAxis axis) {
  movie::Layout layout;
  layout.name = "test";
  layout.rows = rows;
  layout.cols = cols;
  layout.pitch_x_mm = pitch_x_mm;
  layout.pitch_y_mm = pitch_y_mm;
  layout.axis = axis;
  layout.deflection_min_um = -50;
  layout.deflection_max_um = 50;
  layout.max_rate_hz = 700;  // the rate mappings use when none is given, as for STReSS
  return layout;
}

}  // namespace tactile::mapping::testing
