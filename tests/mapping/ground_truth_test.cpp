// Mapping the exact strain of the synthetic bump scene (capture's scene model, no images, no
// measurement noise): the "integrated" method must put the source strain between neighbouring
// contactors.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "tactile/capture/ground_truth.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/mapping/fidelity.hpp"
#include "tactile/mapping/map.hpp"

namespace tactile::mapping {
namespace {

using capture::PointMm;

capture::StrainMovie ground_truth_movie(const capture::SceneSpec& spec, double h_mm) {
  return capture::ground_truth_strain_movie(spec, h_mm);
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
  movie::Layout layout;  // STReSS geometry, built here so this test needs no display code
  layout.name = "stress";
  layout.rows = 10;
  layout.cols = 10;
  MappingParams params;
  params.method = MappingMethod::integrated;
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
  movie::Layout layout;
  layout.name = "stress";
  layout.rows = 10;
  layout.cols = 10;
  MappingParams params;
  params.method = MappingMethod::proportional;
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

// Accumulated strain along the tracks (Lagrangian): contactor pair (a, b) sits where the skin was
// in the reference frame, so the truth is the skin's extension from frame 0 to the frame shown.
TEST(GroundTruthBump, AccumulatedAlongTracksReproducesTheStrainFromTheReferenceFrame) {
  capture::SceneSpec spec;
  spec.frame_count = 45;
  const auto movie = ground_truth_movie(spec, 0.3);
  movie::Layout layout;
  layout.name = "stress";
  layout.rows = 10;
  layout.cols = 10;
  layout.deflection_min_um = -400;  // room for the larger accumulated strain: no saturation
  layout.deflection_max_um = 400;
  MappingParams params;
  params.method = MappingMethod::integrated;
  params.strain = StrainMode::accumulated;
  params.accumulate.reference_frame = 0;
  params.rate_hz = 60;
  params.slew_limit_um_per_s = 1e7;  // compare the method, not the limits
  const auto source = strain_source(movie, params);
  ASSERT_EQ(source.frames.size(), 44u);
  EXPECT_EQ(source.frames.back().frame_from, 0);
  EXPECT_EQ(source.frames.back().frame_to, 44);
  const auto result = map_strain_frames(source, layout, params);
  const auto& out = result.movie;
  ASSERT_EQ(out.frame_count, 44);
  std::vector<double> got, want;
  double biggest = 0;
  for (std::int32_t f = 0; f < out.frame_count; ++f) {
    const auto frame = out.frame(f);
    const int frame_to = f + 1;
    for (std::int32_t r = 0; r < 10; ++r) {
      for (std::int32_t c = 0; c + 1 < 10; ++c) {
        const auto a = contactor_position_mm(layout, result.placement, r, c);
        const auto b = contactor_position_mm(layout, result.placement, r, c + 1);
        // Skin that was under both contactors at frame 0 and still touches the glass.
        if (!capture::in_contact(spec, a, 0) || !capture::in_contact(spec, b, 0)) continue;
        const auto a_now =
            capture::skin_to_image(spec, capture::image_to_skin(spec, a, 0), frame_to);
        const auto b_now =
            capture::skin_to_image(spec, capture::image_to_skin(spec, b, 0), frame_to);
        if (!capture::in_contact(spec, a_now, frame_to) ||
            !capture::in_contact(spec, b_now, frame_to)) {
          continue;
        }
        const double rel = capture::true_rel_change(spec, a, b, 0, frame_to);
        biggest = std::max(biggest, std::abs(rel));
        got.push_back(frame[static_cast<std::size_t>(r * 10 + c + 1)] -
                      frame[static_cast<std::size_t>(r * 10 + c)]);
        want.push_back(1000 * rel * layout.pitch_x_mm);
      }
    }
  }
  ASSERT_GT(got.size(), 1000u);
  const double rho = correlation(got, want);
  std::cout << "[ result ] ground-truth bump, accumulated along tracks, integrated: correlation "
            << rho << " over " << got.size() << " pairs (largest true strain " << biggest << ")\n";
  EXPECT_GE(rho, 0.95);
  // The fidelity metric measures the same thing against the (accumulated) source field.
  const auto m =
      fidelity(out, source, result.placement, result.um_per_strain, params.slew_limit_um_per_s);
  std::cout << "[ result ] fidelity: correlation " << m.strain_correlation << ", RMS error "
            << m.strain_rms_error << " (source RMS " << m.source_strain_rms << ")\n";
  EXPECT_GE(m.strain_correlation, 0.95);
  EXPECT_LT(m.strain_rms_error, 0.3 * m.source_strain_rms);
}

}  // namespace
}  // namespace tactile::mapping
