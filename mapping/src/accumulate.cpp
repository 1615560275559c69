// Lagrangian accumulation: strain from a reference frame to every later frame along the tracks.

#include "tactile/mapping/accumulate.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "tactile/capture/capture.hpp"

namespace tactile::mapping {

std::int32_t last_reference_frame(const capture::StrainMovie& movie) {
  std::int32_t last_frame = movie.camera_frame_count - 1;
  for (const auto& p : movie.tracks) last_frame = std::max(last_frame, p.frame);
  return last_frame;
}

capture::StrainMovie accumulate_along_tracks(const capture::StrainMovie& movie,
                                             const AccumulateOptions& options) {
  if (movie.tracks.empty()) {
    throw std::invalid_argument(fmt::format(
        "accumulate: strain movie '{}' has no tracks to follow (accumulated strain needs the "
        "tracked positions)",
        origin_of(movie.provenance)));
  }
  if (!(movie.frame_rate_hz > 0)) {
    throw std::invalid_argument(
        fmt::format("accumulate: frame rate {} Hz must be positive", movie.frame_rate_hz));
  }
  const std::int32_t last_frame = last_reference_frame(movie);
  const std::int32_t reference = options.reference_frame >= 0
                                     ? options.reference_frame
                                     : (movie.frames.empty() ? 0 : movie.frames.front().frame_from);
  if (reference < 0 || reference > last_frame) {
    throw std::invalid_argument(fmt::format(
        "accumulate: reference frame {} outside the movie's frames 0..{}", reference, last_frame));
  }

  // Points sorted by (track, frame): each track is then one run, searched by bisection.
  std::vector<capture::TrackedPoint> points = movie.tracks;
  std::sort(points.begin(), points.end(), [](const auto& a, const auto& b) {
    return a.track_id != b.track_id ? a.track_id < b.track_id : a.frame < b.frame;
  });
  struct Run {
    std::size_t begin, end;
    const capture::TrackedPoint* at_reference;
  };
  std::vector<Run> runs;  // only the tracks alive at the reference frame
  for (std::size_t i = 0; i < points.size();) {
    std::size_t j = i;
    while (j < points.size() && points[j].track_id == points[i].track_id) ++j;
    const auto it = std::lower_bound(points.begin() + static_cast<std::ptrdiff_t>(i),
                                     points.begin() + static_cast<std::ptrdiff_t>(j), reference,
                                     [](const auto& p, std::int32_t f) { return p.frame < f; });
    if (it != points.begin() + static_cast<std::ptrdiff_t>(j) && it->frame == reference) {
      runs.push_back({i, j, &*it});
    }
    i = j;
  }

  capture::StrainMovie out;
  out.frame_rate_hz = movie.frame_rate_hz;
  out.span_frames = 0;  // varies: frame_to - reference
  out.camera_frame_count = movie.camera_frame_count;
  out.field_width_mm = movie.field_width_mm;
  out.field_height_mm = movie.field_height_mm;
  out.calibration = movie.calibration;
  out.provenance = movie.provenance;
  out.provenance.method =
      fmt::format("{}, accumulated along tracks from frame {}", movie.provenance.method, reference);
  out.tracks = movie.tracks;
  for (std::int32_t f = reference + 1; f <= last_frame; ++f) {
    capture::StrainFrame sf;
    sf.frame_from = reference;
    sf.frame_to = f;
    sf.t_s = f / movie.frame_rate_hz;
    for (const auto& run : runs) {
      const auto end = points.begin() + static_cast<std::ptrdiff_t>(run.end);
      const auto it =
          std::lower_bound(points.begin() + static_cast<std::ptrdiff_t>(run.begin), end, f,
                           [](const auto& p, std::int32_t frame) { return p.frame < frame; });
      if (it == end || it->frame != f) continue;
      sf.points_from.push_back(*run.at_reference);
      sf.points_to.push_back(*it);
    }
    if (sf.points_from.size() < 3) continue;
    capture::triangulate_strain(sf.points_from, sf.points_to, options.max_edge_ratio, sf.edges,
                                sf.triangles);
    out.frames.push_back(std::move(sf));
  }
  return out;
}

}  // namespace tactile::mapping
