// Strain movie -> the viewer's side field, and finding the strain movie a tactile movie came from.

#include "tactile/mapping/strain_panel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "tactile/capture/strain_map.hpp"
#include "tactile/common/h5.hpp"

namespace tactile::mapping {

movie::SideField strain_side_field(const capture::StrainMovie& strain, const std::string& title) {
  if (strain.frames.empty()) throw std::invalid_argument("strain movie has no strain frames");
  movie::SideField field;
  field.title = title;
  field.full_scale = capture::strain_map_full_scale(strain);
  if (!(field.full_scale > 0)) {
    throw std::invalid_argument("strain movie has no edge with a finite, non-zero strain");
  }
  double min_x = 0, min_y = 0;
  double max_x = strain.field_width_mm, max_y = strain.field_height_mm;
  const double t0 = strain.frames.front().t_s;
  for (const capture::StrainFrame& f : strain.frames) {
    std::unordered_map<std::int32_t, const capture::TrackedPoint*> by_track;
    for (const auto& p : f.points_to) by_track[p.track_id] = &p;
    movie::FieldFrame out;
    out.t_s = f.t_s - t0;
    for (const capture::StrainEdge& e : f.edges) {
      const auto a = by_track.find(e.track_a);
      const auto b = by_track.find(e.track_b);
      if (a == by_track.end() || b == by_track.end()) {
        throw std::invalid_argument(
            fmt::format("strain movie: edge {}-{} of frames {}->{} names a track that is not a "
                        "point of the frame",
                        e.track_a, e.track_b, f.frame_from, f.frame_to));
      }
      out.segments.push_back({a->second->x_mm, a->second->y_mm, b->second->x_mm, b->second->y_mm,
                              std::isfinite(e.rel_change) ? e.rel_change : 0.0});
      min_x = std::min({min_x, a->second->x_mm, b->second->x_mm});
      min_y = std::min({min_y, a->second->y_mm, b->second->y_mm});
      max_x = std::max({max_x, a->second->x_mm, b->second->x_mm});
      max_y = std::max({max_y, a->second->y_mm, b->second->y_mm});
    }
    field.frames.push_back(std::move(out));
  }
  // Points outside the nominal field (tracking near its border) still show.
  for (auto& f : field.frames) {
    for (auto& s : f.segments) {
      s.x0_mm -= min_x;
      s.x1_mm -= min_x;
      s.y0_mm -= min_y;
      s.y1_mm -= min_y;
    }
  }
  field.width_mm = max_x - min_x;
  field.height_mm = max_y - min_y;
  movie::validate_side_field(field);
  return field;
}

std::optional<std::filesystem::path> find_source_strain(
    const movie::TactileMovie& movie, const std::filesystem::path& movie_path,
    const std::filesystem::path& explicit_path) {
  namespace fs = std::filesystem;
  if (!explicit_path.empty()) return explicit_path;
  const fs::path source = movie.provenance.input;
  if (source.empty()) return std::nullopt;
  for (const fs::path& candidate : {source, movie_path.parent_path() / source.filename()}) {
    std::error_code ec;
    if (!fs::is_regular_file(candidate, ec)) continue;
    try {
      H5::H5File f = h5::open_for_reading(candidate);
      if (h5::read_attr_string(f, "format", candidate.string()) == "tactile-strain-movie") {
        return candidate;
      }
    } catch (const std::exception&) {
      // Not an HDF5 strain movie: the provenance names something else (a scene, a folder).
    }
  }
  return std::nullopt;
}

}  // namespace tactile::mapping
