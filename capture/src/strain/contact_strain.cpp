#include "tactile/capture/contact_strain.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace tactile::capture {

namespace {

// Per camera frame, grid.rows x grid.columns: 1 where a cell is out of contact or within
// `margin` cells of one. A frame the map did not see (a live session dropped it) makes no claim.
std::vector<std::uint8_t> near_gap(const ContactMap& map, std::int32_t margin) {
  const std::size_t cells = static_cast<std::size_t>(map.grid.cells());
  std::vector<std::uint8_t> near;
  near.reserve(map.in_contact.size());
  for (std::int32_t f = 0; f < map.frame_count(); ++f) {
    if (!map.seen(f)) {
      near.insert(near.end(), cells, 0);
      continue;
    }
    const auto frame =
        std::span(map.in_contact).subspan(static_cast<std::size_t>(f) * cells, cells);
    const std::vector<std::uint8_t> one = cells_near_gap(map.grid, frame, margin);
    near.insert(near.end(), one.begin(), one.end());
  }
  return near;
}

// A point a tracker placed just outside the image belongs to the cell at the border.
std::size_t cell_at(const ContactGrid& g, double x_px, double y_px) {
  const auto cell_of = [&g](double v, std::int32_t count) {
    const double i = std::floor(v / g.cell_px);
    return static_cast<std::int32_t>(std::clamp(i, 0.0, static_cast<double>(count - 1)));
  };
  return static_cast<std::size_t>(cell_of(y_px, g.rows) * g.columns + cell_of(x_px, g.columns));
}

bool is_near_gap(const std::vector<std::uint8_t>& near, const ContactMap& map, std::int32_t frame,
                 double x_px, double y_px) {
  if (frame < 0 || frame >= map.frame_count()) return false;
  return near[static_cast<std::size_t>(frame) * static_cast<std::size_t>(map.grid.cells()) +
              cell_at(map.grid, x_px, y_px)] != 0;
}

// Erases the frame's edges on a track of `left_out_tracks` and its triangles with a corner among
// the points marked in `left_out` (indices into points_from); returns how many edges went.
std::int64_t erase_strain_of(StrainFrame& f, const std::vector<std::uint8_t>& left_out,
                             const std::unordered_set<std::int32_t>& left_out_tracks) {
  const std::size_t edges = f.edges.size();
  std::erase_if(f.edges, [&](const StrainEdge& e) {
    return left_out_tracks.count(e.track_a) > 0 || left_out_tracks.count(e.track_b) > 0;
  });
  std::erase_if(f.triangles, [&](const StrainTriangle& t) {
    return std::any_of(t.point_index.begin(), t.point_index.end(), [&](std::int32_t p) {
      return p >= 0 && static_cast<std::size_t>(p) < left_out.size() &&
             left_out[static_cast<std::size_t>(p)] != 0;
    });
  });
  return static_cast<std::int64_t>(edges - f.edges.size());
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
    erase_strain_of(f, left_out, left_out_tracks);
  }
  return movie;
}

std::vector<Track> tracks_clear_of_gaps(const std::vector<Track>& tracks, const ContactMap& map,
                                        std::int32_t margin_cells) {
  if (!map.measured()) return tracks;
  const std::vector<std::uint8_t> near = near_gap(map, margin_cells);
  std::vector<Track> clear;
  for (const Track& t : tracks) {
    bool near_any = false;
    for (std::size_t k = 0; k < t.x_px.size() && !near_any; ++k) {
      near_any = is_near_gap(near, map, t.first_frame + static_cast<std::int32_t>(k), t.x_px[k],
                             t.y_px[k]);
    }
    if (!near_any) clear.push_back(t);
  }
  return clear;
}

std::vector<std::uint8_t> cells_near_gap(const ContactGrid& g,
                                         std::span<const std::uint8_t> in_contact,
                                         std::int32_t margin) {
  if (in_contact.size() != static_cast<std::size_t>(g.cells())) {
    throw std::invalid_argument(fmt::format("cells_near_gap: {} cells given for a grid of {} x {}",
                                            in_contact.size(), g.columns, g.rows));
  }
  std::vector<std::uint8_t> near(in_contact.size(), 0);
  for (std::int32_t r = 0; r < g.rows; ++r) {
    for (std::int32_t c = 0; c < g.columns; ++c) {
      if (in_contact[static_cast<std::size_t>(r * g.columns + c)] != 0) continue;
      for (std::int32_t rr = std::max(0, r - margin); rr <= std::min(g.rows - 1, r + margin);
           ++rr) {
        for (std::int32_t cc = std::max(0, c - margin); cc <= std::min(g.columns - 1, c + margin);
             ++cc) {
          near[static_cast<std::size_t>(rr * g.columns + cc)] = 1;
        }
      }
    }
  }
  return near;
}

std::int64_t leave_out_strain_near_gaps(StrainFrame& f, const ContactGrid& grid,
                                        std::span<const std::uint8_t> near_from,
                                        std::span<const std::uint8_t> near_to) {
  const auto cells = static_cast<std::size_t>(grid.cells());
  if (grid.cells() <= 0 || near_from.size() != cells || near_to.size() != cells) {
    throw std::invalid_argument(
        fmt::format("leave_out_strain_near_gaps: {} and {} cells given for a grid of {} x {}",
                    near_from.size(), near_to.size(), grid.columns, grid.rows));
  }
  std::vector<std::uint8_t> left_out(f.points_from.size(), 0);
  std::unordered_set<std::int32_t> left_out_tracks;
  for (std::size_t i = 0; i < f.points_from.size(); ++i) {
    const TrackedPoint& a = f.points_from[i];
    bool near = near_from[cell_at(grid, a.x_px, a.y_px)] != 0;
    if (!near && i < f.points_to.size()) {
      near = near_to[cell_at(grid, f.points_to[i].x_px, f.points_to[i].y_px)] != 0;
    }
    if (near) {
      left_out[i] = 1;
      left_out_tracks.insert(a.track_id);
    }
  }
  return left_out_tracks.empty() ? 0 : erase_strain_of(f, left_out, left_out_tracks);
}

}  // namespace tactile::capture
