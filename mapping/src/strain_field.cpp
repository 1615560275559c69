// Builds the piecewise-constant strain field of one StrainFrame and its point-location bins.

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {
namespace {

std::uint64_t edge_key(std::int32_t a, std::int32_t b) {
  const auto lo = static_cast<std::uint32_t>(std::min(a, b));
  const auto hi = static_cast<std::uint32_t>(std::max(a, b));
  return (static_cast<std::uint64_t>(lo) << 32) | hi;
}

double distance_mm(const capture::TrackedPoint& a, const capture::TrackedPoint& b) {
  const double dx = b.x_mm - a.x_mm;
  const double dy = b.y_mm - a.y_mm;
  return std::sqrt(dx * dx + dy * dy);
}

using Vertices = std::array<capture::PointMm, 3>;

const Vertices& vertices_of(const FieldTriangle& t) {
  return t.vertex_mm;
}
const Vertices& vertices_of(const Vertices& v) {
  return v;
}

// Bins over FieldTriangles or bare vertex triples (the geometry-only pass of build_strain_field).
template <typename Triangle>
TriangleBins make_bins(const std::vector<Triangle>& triangles) {
  TriangleBins bins;
  if (triangles.empty()) return bins;
  double x_min = vertices_of(triangles[0])[0].x_mm;
  double x_max = x_min;
  double y_min = vertices_of(triangles[0])[0].y_mm;
  double y_max = y_min;
  for (const auto& t : triangles) {
    for (const auto& v : vertices_of(t)) {
      x_min = std::min(x_min, v.x_mm);
      x_max = std::max(x_max, v.x_mm);
      y_min = std::min(y_min, v.y_mm);
      y_max = std::max(y_max, v.y_mm);
    }
  }
  // About one bin per triangle keeps both the bin lists and the number of empty bins short.
  const double width = std::max(x_max - x_min, 1e-9);
  const double height = std::max(y_max - y_min, 1e-9);
  const double count = static_cast<double>(triangles.size());
  bins.bin_size_mm = std::max(std::sqrt(width * height / count), 1e-6);
  bins.x0_mm = x_min;
  bins.y0_mm = y_min;
  bins.bins_x = std::clamp(static_cast<std::int32_t>(std::ceil(width / bins.bin_size_mm)), 1, 4096);
  bins.bins_y =
      std::clamp(static_cast<std::int32_t>(std::ceil(height / bins.bin_size_mm)), 1, 4096);

  const auto bin_of = [&](double v, double origin, std::int32_t n) {
    const auto i = static_cast<std::int32_t>(std::floor((v - origin) / bins.bin_size_mm));
    return std::clamp(i, 0, n - 1);
  };
  // Two passes (count, then fill) build the compressed rows without per-bin vectors.
  const auto total_bins = static_cast<std::size_t>(bins.bins_x) * bins.bins_y;
  std::vector<std::int32_t> counts(total_bins + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const auto& v = vertices_of(triangles[t]);
      const double tx0 = std::min({v[0].x_mm, v[1].x_mm, v[2].x_mm});
      const double tx1 = std::max({v[0].x_mm, v[1].x_mm, v[2].x_mm});
      const double ty0 = std::min({v[0].y_mm, v[1].y_mm, v[2].y_mm});
      const double ty1 = std::max({v[0].y_mm, v[1].y_mm, v[2].y_mm});
      for (auto by = bin_of(ty0, bins.y0_mm, bins.bins_y);
           by <= bin_of(ty1, bins.y0_mm, bins.bins_y); ++by) {
        for (auto bx = bin_of(tx0, bins.x0_mm, bins.bins_x);
             bx <= bin_of(tx1, bins.x0_mm, bins.bins_x); ++bx) {
          const auto b = static_cast<std::size_t>(by) * bins.bins_x + bx;
          if (pass == 0) {
            ++counts[b + 1];
          } else {
            bins.triangle_index[static_cast<std::size_t>(counts[b]++)] =
                static_cast<std::int32_t>(t);
          }
        }
      }
    }
    if (pass == 0) {
      for (std::size_t b = 0; b < total_bins; ++b) counts[b + 1] += counts[b];
      bins.bin_start = counts;
      bins.triangle_index.assign(static_cast<std::size_t>(counts[total_bins]), 0);
    }
  }
  return bins;
}

}  // namespace

StrainField build_strain_field(const capture::StrainFrame& frame, const StrainFieldOptions& options,
                               std::span<const capture::PointMm> only_at) {
  const auto& from = frame.points_from;
  const auto& to = frame.points_to;
  if (!to.empty() && to.size() != from.size()) {
    throw std::invalid_argument(
        fmt::format("strain frame {}->{}: {} points_to for {} points_from (must match)",
                    frame.frame_from, frame.frame_to, to.size(), from.size()));
  }
  std::vector<Vertices> geometry(frame.triangles.size());
  for (std::size_t t = 0; t < frame.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      const auto i = frame.triangles[t].point_index[k];
      if (i < 0 || static_cast<std::size_t>(i) >= from.size()) {
        throw std::invalid_argument(
            fmt::format("strain frame {}->{}: triangle point index {} outside the {} points_from",
                        frame.frame_from, frame.frame_to, i, from.size()));
      }
      const auto& p = from[static_cast<std::size_t>(i)];
      geometry[t][k] = {p.x_mm, p.y_mm};
    }
  }
  // Which triangles to solve: all, or only those holding a requested point (every triangle
  // holding it, so that a rejected one does not mask a point on its edge with a good one).
  std::vector<char> wanted(geometry.size(), only_at.empty() ? 1 : 0);
  if (!only_at.empty()) {
    const auto geometry_bins = make_bins(geometry);
    for (const auto& q : only_at) {
      for_each_candidate(geometry_bins, q.x_mm, q.y_mm, [&](std::int32_t t) {
        if (triangle_contains(geometry[static_cast<std::size_t>(t)], q.x_mm, q.y_mm)) {
          wanted[static_cast<std::size_t>(t)] = 1;
        }
        return false;
      });
    }
  }

  // The keys of the edges the wanted triangles need, sorted; each edge of the frame is looked up
  // among them once. Sorting only these (a fraction of the frame's edges when the field is built
  // for a few contactors) is what keeps the per-frame cost low.
  const auto key_of = [&](std::size_t t, std::size_t k) {
    const auto& tri = frame.triangles[t];
    return edge_key(from[static_cast<std::size_t>(tri.point_index[k])].track_id,
                    from[static_cast<std::size_t>(tri.point_index[(k + 1) % 3])].track_id);
  };
  std::vector<std::uint64_t> keys;
  for (std::size_t t = 0; t < frame.triangles.size(); ++t) {
    if (!wanted[t]) continue;
    for (std::size_t k = 0; k < 3; ++k) keys.push_back(key_of(t, k));
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<double> change_of_key(keys.size(), std::nan(""));
  for (const auto& e : frame.edges) {
    const auto key = edge_key(e.track_a, e.track_b);
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it != keys.end() && *it == key) {
      change_of_key[static_cast<std::size_t>(it - keys.begin())] = e.rel_change;
    }
  }
  const auto find_change = [&](std::uint64_t key) -> const double* {
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    if (it == keys.end() || *it != key) return nullptr;
    const double* value = &change_of_key[static_cast<std::size_t>(it - keys.begin())];
    return std::isnan(*value) ? nullptr : value;
  };

  StrainField field;
  field.t_s = frame.t_s;
  field.triangles.reserve(frame.triangles.size());
  for (std::size_t t = 0; t < frame.triangles.size(); ++t) {
    if (!wanted[t]) continue;
    const auto& tri = frame.triangles[t];
    const auto& vertex = geometry[t];
    std::array<double, 3> change{};
    bool known = true;
    for (std::size_t k = 0; k < 3 && known; ++k) {
      const auto ia = static_cast<std::size_t>(tri.point_index[k]);
      const auto ib = static_cast<std::size_t>(tri.point_index[(k + 1) % 3]);
      if (const double* known_change =
              find_change(edge_key(from[ia].track_id, from[ib].track_id))) {
        change[k] = *known_change;
      } else if (!to.empty() && distance_mm(from[ia], from[ib]) > 0) {
        // The edge list is the measurement; positions are the fallback for a writer that
        // stored triangles without every edge.
        change[k] = distance_mm(to[ia], to[ib]) / distance_mm(from[ia], from[ib]) - 1.0;
      } else {
        known = false;
      }
    }
    const auto strain =
        known ? triangle_strain(vertex, change, options.min_triangle_quality) : std::nullopt;
    if (strain) {
      field.triangles.push_back({vertex, *strain});
    } else {
      ++field.rejected_triangle_count;
    }
  }
  field.bins = make_bins(field.triangles);
  return field;
}

}  // namespace tactile::mapping
