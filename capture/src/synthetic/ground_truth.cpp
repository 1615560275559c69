// Exact strain movies of the synthetic scenes, from capture's skin kinematics.

#include "tactile/capture/ground_truth.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace tactile::capture {

StrainMovie ground_truth_strain_movie(const SceneSpec& spec, double grid_spacing_mm) {
  validate_scene(spec);
  if (!(grid_spacing_mm > 0) || !std::isfinite(grid_spacing_mm)) {
    throw std::invalid_argument(
        fmt::format("ground truth: grid spacing {} mm must be positive", grid_spacing_mm));
  }
  const double h = grid_spacing_mm;
  StrainMovie movie;
  movie.frame_rate_hz = spec.frame_rate_hz;
  movie.span_frames = 1;
  movie.camera_frame_count = spec.frame_count;
  movie.field_width_mm = spec.field_width_mm;
  movie.field_height_mm = spec.field_height_mm;
  movie.calibration = capture::true_calibration(spec);
  movie.provenance = make_provenance({}, "synthetic ground truth",
                                     nlohmann::json{{"scene", to_string(spec.scene)},
                                                    {"speed_mm_per_s", spec.speed_mm_per_s},
                                                    {"frames", spec.frame_count},
                                                    {"seed", spec.seed},
                                                    {"grid_spacing_mm", h}}
                                         .dump());
  // The skin that ever enters the field: the field itself plus the distance slid, with a margin.
  const double slide_mm = std::abs(spec.speed_mm_per_s) * spec.frame_count / spec.frame_rate_hz;
  const int nx = static_cast<int>((spec.field_width_mm + slide_mm + 2) / h) + 1;
  const int ny = static_cast<int>((spec.field_height_mm + 2) / h) + 1;
  const auto skin_of = [&](int i, int j) {
    return capture::PointMm{-slide_mm - 1 + i * h, -1 + j * h};
  };
  const auto visible = [&](const capture::PointMm& p, int f) {
    return p.x_mm >= 0 && p.x_mm <= spec.field_width_mm && p.y_mm >= 0 &&
           p.y_mm <= spec.field_height_mm && capture::in_contact(spec, p, f);
  };
  // Image positions of every grid point in every frame, NaN where not visible.
  const auto points = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  std::vector<capture::PointMm> at(points * static_cast<std::size_t>(spec.frame_count));
  for (int f = 0; f < spec.frame_count; ++f) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        auto p = skin_to_image(spec, skin_of(i, j), f);
        if (!visible(p, f)) p = {std::nan(""), std::nan("")};
        at[static_cast<std::size_t>(f) * points + static_cast<std::size_t>(j * nx + i)] = p;
      }
    }
  }
  const auto pos = [&](int id, int f) -> const capture::PointMm& {
    return at[static_cast<std::size_t>(f) * points + static_cast<std::size_t>(id)];
  };
  for (int id = 0; id < nx * ny; ++id) {
    for (int f = 0; f < spec.frame_count; ++f) {
      const auto& p = pos(id, f);
      if (!std::isnan(p.x_mm)) movie.tracks.push_back({id, f, {}, 0, 0, p.x_mm, p.y_mm});
    }
  }
  for (int f = 0; f + 1 < spec.frame_count; ++f) {
    capture::StrainFrame sf;
    sf.frame_from = f;
    sf.frame_to = f + 1;
    sf.t_s = (f + 1) / spec.frame_rate_hz;
    std::vector<int> index(points, -1);
    for (int id = 0; id < nx * ny; ++id) {
      const auto& a = pos(id, f);
      const auto& b = pos(id, f + 1);
      if (std::isnan(a.x_mm) || std::isnan(b.x_mm)) continue;
      index[static_cast<std::size_t>(id)] = static_cast<int>(sf.points_from.size());
      sf.points_from.push_back({id, f, {}, 0, 0, a.x_mm, a.y_mm});
      sf.points_to.push_back({id, f + 1, {}, 0, 0, b.x_mm, b.y_mm});
    }
    const auto idx = [&](int i, int j) { return index[static_cast<std::size_t>(j * nx + i)]; };
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        const int p = idx(i, j), q = idx(i + 1, j), r = idx(i + 1, j + 1), s = idx(i, j + 1);
        if (p >= 0 && q >= 0 && r >= 0) sf.triangles.push_back({{p, q, r}});
        if (p >= 0 && r >= 0 && s >= 0) sf.triangles.push_back({{p, r, s}});
      }
    }
    movie.frames.push_back(std::move(sf));
  }
  return movie;
}

}  // namespace tactile::capture
