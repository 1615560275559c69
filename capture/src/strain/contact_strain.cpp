#include "tactile/capture/contact_strain.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace tactile::capture {

namespace {

// Per camera frame, grid.rows x grid.columns: 1 where a cell is out of contact or within
// `margin` cells of one.
std::vector<std::uint8_t> near_gap(const ContactMap& map, std::int32_t margin) {
  const ContactGrid& g = map.grid;
  const std::size_t cells = static_cast<std::size_t>(g.cells());
  std::vector<std::uint8_t> near(map.in_contact.size(), 0);
  for (std::int32_t f = 0; f < map.frame_count(); ++f) {
    const std::size_t first = static_cast<std::size_t>(f) * cells;
    for (std::int32_t r = 0; r < g.rows; ++r) {
      for (std::int32_t c = 0; c < g.columns; ++c) {
        if (map.in_contact[first + static_cast<std::size_t>(r * g.columns + c)] != 0) continue;
        for (std::int32_t rr = std::max(0, r - margin); rr <= std::min(g.rows - 1, r + margin);
             ++rr) {
          for (std::int32_t cc = std::max(0, c - margin); cc <= std::min(g.columns - 1, c + margin);
               ++cc) {
            near[first + static_cast<std::size_t>(rr * g.columns + cc)] = 1;
          }
        }
      }
    }
  }
  return near;
}

bool is_near_gap(const std::vector<std::uint8_t>& near, const ContactMap& map, std::int32_t frame,
                 double x_px, double y_px) {
  const ContactGrid& g = map.grid;
  if (frame < 0 || frame >= map.frame_count()) return false;
  // A point a tracker placed just outside the image belongs to the cell at the border.
  const auto cell_of = [&g](double v, std::int32_t count) {
    const double i = std::floor(v / g.cell_px);
    return static_cast<std::int32_t>(std::clamp(i, 0.0, static_cast<double>(count - 1)));
  };
  const std::size_t at =
      static_cast<std::size_t>(frame) * static_cast<std::size_t>(g.cells()) +
      static_cast<std::size_t>(cell_of(y_px, g.rows) * g.columns + cell_of(x_px, g.columns));
  return near[at] != 0;
}

}  // namespace

bool skin_slides_through_view(const StrainMovie& movie) {
  const auto settings = nlohmann::json::parse(movie.provenance.parameters_json, nullptr, false);
  return settings.is_object() && settings.value("frames_in_view", 0.0) > 0;
}

StrainMovie strain_in_contact(StrainMovie movie) {
  if (!skin_slides_through_view(movie)) return movie;
  const auto settings = nlohmann::json::parse(movie.provenance.parameters_json, nullptr, false);
  const std::int32_t smoothing = std::max(0, settings.value("smoothing_half_window_used", 0));
  return without_strain_near_gaps(std::move(movie), kGapMarginCells, smoothing);
}

StrainMovie without_strain_near_gaps(StrainMovie movie, std::int32_t margin_cells,
                                     std::int32_t window_frames) {
  const ContactMap& map = movie.contact;
  if (!map.measured()) return movie;
  const std::vector<std::uint8_t> near = near_gap(map, margin_cells);
  // The camera frames in which each track stood at or near a gap.
  std::unordered_map<std::int32_t, std::vector<std::int32_t>> near_frames;
  for (const StrainFrame& f : movie.frames) {
    for (const auto* side : {&f.points_from, &f.points_to}) {
      for (const TrackedPoint& p : *side) {
        if (is_near_gap(near, map, p.frame, p.x_px, p.y_px))
          near_frames[p.track_id].push_back(p.frame);
      }
    }
  }
  if (near_frames.empty()) return movie;
  const auto near_in = [&](std::int32_t track, std::int32_t first, std::int32_t last) {
    const auto it = near_frames.find(track);
    return it != near_frames.end() &&
           std::any_of(it->second.begin(), it->second.end(),
                       [&](std::int32_t g) { return g >= first && g <= last; });
  };
  for (StrainFrame& f : movie.frames) {
    const std::int32_t first = std::min(f.frame_from, f.frame_to) - window_frames;
    const std::int32_t last = std::max(f.frame_from, f.frame_to) + window_frames;
    std::vector<std::uint8_t> left_out(f.points_from.size(), 0);
    std::unordered_set<std::int32_t> left_out_tracks;
    for (std::size_t i = 0; i < f.points_from.size(); ++i) {
      const std::int32_t track = f.points_from[i].track_id;
      if (near_in(track, first, last)) {
        left_out[i] = 1;
        left_out_tracks.insert(track);
      }
    }
    if (left_out_tracks.empty()) continue;
    std::erase_if(f.edges, [&](const StrainEdge& e) {
      return left_out_tracks.count(e.track_a) > 0 || left_out_tracks.count(e.track_b) > 0;
    });
    std::erase_if(f.triangles, [&](const StrainTriangle& t) {
      return std::any_of(t.point_index.begin(), t.point_index.end(), [&](std::int32_t p) {
        return p >= 0 && static_cast<std::size_t>(p) < left_out.size() &&
               left_out[static_cast<std::size_t>(p)] != 0;
      });
    });
  }
  return movie;
}

}  // namespace tactile::capture
