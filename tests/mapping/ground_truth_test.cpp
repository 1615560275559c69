// Mapping the exact strain of the synthetic bump scene (capture's scene model, no images, no
// measurement noise): the "integrated" method must put the source strain between neighbouring
// contactors (the acceptance test of issue 5, run early on the first version).

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

#include "tactile/capture/synth.hpp"
#include "tactile/mapping/map.hpp"

namespace tactile::mapping {
namespace {

using capture::PointMm;

// Ground-truth strain movie: a material grid of skin points (spacing h_mm) seen at each pair of
// consecutive frames, kept where the skin touches the glass in both, triangulated on the grid.
capture::StrainMovie ground_truth_movie(const capture::SceneSpec& spec, double h_mm) {
  capture::StrainMovie movie;
  movie.frame_rate_hz = spec.frame_rate_hz;
  movie.camera_frame_count = spec.frame_count;
  movie.field_width_mm = spec.field_width_mm;
  movie.field_height_mm = spec.field_height_mm;
  movie.calibration = capture::true_calibration(spec);
  movie.source = "ground truth: synthetic bump scene";
  const double slide_mm = spec.speed_mm_per_s * spec.frame_count / spec.frame_rate_hz;
  const int nx = static_cast<int>((spec.field_width_mm + slide_mm + 2) / h_mm) + 1;
  const int ny = static_cast<int>((spec.field_height_mm + 2) / h_mm) + 1;
  for (int f = 0; f + 1 < spec.frame_count; ++f) {
    capture::StrainFrame sf;
    sf.frame_from = f;
    sf.frame_to = f + 1;
    sf.t_s = (f + 1) / spec.frame_rate_hz;
    std::vector<int> index(static_cast<std::size_t>(nx * ny), -1);
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const PointMm skin{-slide_mm - 1 + i * h_mm, -1 + j * h_mm};
        const auto a = capture::skin_to_image(spec, skin, f);
        const auto b = capture::skin_to_image(spec, skin, f + 1);
        if (a.x_mm < 0 || a.x_mm > spec.field_width_mm || a.y_mm < 0 ||
            a.y_mm > spec.field_height_mm || !capture::in_contact(spec, a, f) ||
            !capture::in_contact(spec, b, f + 1)) {
          continue;
        }
        const int id = j * nx + i;
        index[static_cast<std::size_t>(id)] = static_cast<int>(sf.points_from.size());
        sf.points_from.push_back({id, f, {}, 0, 0, a.x_mm, a.y_mm});
        sf.points_to.push_back({id, f + 1, {}, 0, 0, b.x_mm, b.y_mm});
      }
    }
    const auto at = [&](int i, int j) { return index[static_cast<std::size_t>(j * nx + i)]; };
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        const int p = at(i, j), q = at(i + 1, j), r = at(i + 1, j + 1), s = at(i, j + 1);
        if (p >= 0 && q >= 0 && r >= 0) sf.triangles.push_back({{p, q, r}});
        if (p >= 0 && r >= 0 && s >= 0) sf.triangles.push_back({{p, r, s}});
      }
    }
    movie.frames.push_back(std::move(sf));  // no edges: the field measures them from positions
  }
  return movie;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(GroundTruthBump, IntegratedReproducesTheSourceStrainAlongTheAxis) {
  capture::SceneSpec spec;  // the demo scene: bump 0.5 mm high, 3 mm wide, 2.4 mm/s, 60 Hz
  spec.frame_count = 60;    // one second is enough to cross the contactors and keeps this fast
  const auto movie = ground_truth_movie(spec, 0.3);
  display::Layout layout;  // STReSS geometry, built here so this test needs no display code
  layout.name = "stress";
  layout.rows = 10;
  layout.cols = 10;
  MappingParams params;
  params.method = "integrated";
  params.rate_hz = 60;  // one display frame per camera frame: compare without interpolation
  layout.max_rate_hz = 700;
  const auto out = map_strain_movie(movie, layout, params);
  ASSERT_EQ(out.frame_count, static_cast<std::int32_t>(movie.frames.size()));

  const auto placement = default_placement(movie);
  std::vector<double> got, want;
  for (std::int32_t f = 0; f < out.frame_count; ++f) {
    const auto frame = out.frame(f);
    const auto& sf = movie.frames[static_cast<std::size_t>(f)];
    for (std::int32_t r = 0; r < 10; ++r) {
      for (std::int32_t c = 0; c + 1 < 10; ++c) {
        const float d0 = frame[static_cast<std::size_t>(r * 10 + c)];
        const float d1 = frame[static_cast<std::size_t>(r * 10 + c + 1)];
        if (std::abs(d0) >= 50 || std::abs(d1) >= 50) continue;  // saturated: not comparable
        const auto a = contactor_position_mm(layout, placement, r, c);
        const auto b = contactor_position_mm(layout, placement, r, c + 1);
        // The skin's true extension between the two contactors from frame_from to frame_to.
        const double rel = capture::true_rel_change(spec, a, b, sf.frame_from, sf.frame_to);
        if (!capture::in_contact(spec, a, sf.frame_from) ||
            !capture::in_contact(spec, b, sf.frame_from)) {
          continue;
        }
        got.push_back(d1 - d0);
        want.push_back(1000 * rel * layout.pitch_x_mm);
      }
    }
  }
  ASSERT_GT(got.size(), 1000u);
  const double rho = correlation(got, want);
  std::cout << "[ result ] ground-truth bump, integrated: correlation " << rho << " over "
            << got.size() << " contactor pairs\n";
  EXPECT_GE(rho, 0.95);
}

TEST(GroundTruthBump, ProportionalFollowsTheLocalSourceStrain) {
  capture::SceneSpec spec;
  spec.frame_count = 60;
  const auto movie = ground_truth_movie(spec, 0.3);
  display::Layout layout;
  layout.name = "stress";
  layout.rows = 10;
  layout.cols = 10;
  MappingParams params;
  params.rate_hz = 60;
  const auto out = map_strain_movie(movie, layout, params);
  const auto placement = default_placement(movie);
  std::vector<double> got, want;
  for (std::int32_t f = 0; f < out.frame_count; ++f) {
    const auto& sf = movie.frames[static_cast<std::size_t>(f)];
    for (std::int32_t r = 0; r < 10; ++r) {
      for (std::int32_t c = 0; c < 10; ++c) {
        const auto p = contactor_position_mm(layout, placement, r, c);
        if (!capture::in_contact(spec, p, sf.frame_from)) continue;
        // Local x-strain: a short (0.3 mm, one grid spacing) segment centred on the contactor.
        const double rel = capture::true_rel_change(
            spec, {p.x_mm - 0.15, p.y_mm}, {p.x_mm + 0.15, p.y_mm}, sf.frame_from, sf.frame_to);
        got.push_back(out.frame(f)[static_cast<std::size_t>(r * 10 + c)]);
        want.push_back(1000 * rel);
      }
    }
  }
  ASSERT_GT(got.size(), 1000u);
  const double rho = correlation(got, want);
  std::cout << "[ result ] ground-truth bump, proportional: correlation " << rho << " over "
            << got.size() << " contactors\n";
  EXPECT_GE(rho, 0.9);
}

}  // namespace
}  // namespace tactile::mapping
