// The only translation unit that includes CGAL (it is template-heavy; one file keeps builds fast).
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "tactile/capture/capture.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<std::int32_t, Kernel>;
using DataStructure =
    CGAL::Triangulation_data_structure_2<VertexBase, CGAL::Triangulation_face_base_2<Kernel>>;
using Delaunay = CGAL::Delaunay_triangulation_2<Kernel, DataStructure>;
}  // namespace

void triangulate_strain(const std::vector<TrackedPoint>& from, const std::vector<TrackedPoint>& to,
                        double max_edge_ratio, std::vector<StrainEdge>& edges,
                        std::vector<StrainTriangle>& triangles) {
  if (from.size() != to.size()) {
    throw std::invalid_argument("triangulate_strain: from and to differ in size");
  }
  edges.clear();
  triangles.clear();
  if (from.size() < 3) return;
  std::vector<std::pair<Kernel::Point_2, std::int32_t>> points;
  points.reserve(from.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    points.emplace_back(Kernel::Point_2(from[i].x_mm, from[i].y_mm), static_cast<std::int32_t>(i));
  }
  Delaunay dt(points.begin(), points.end());

  struct Raw {
    std::int32_t a, b;
    double length_from;
  };
  std::vector<Raw> raw;
  const auto add_raw = [&](std::int32_t a, std::int32_t b) {
    if (a > b) std::swap(a, b);
    const auto& pa = from[static_cast<std::size_t>(a)];
    const auto& pb = from[static_cast<std::size_t>(b)];
    raw.push_back({a, b, std::hypot(pb.x_mm - pa.x_mm, pb.y_mm - pa.y_mm)});
  };
  if (dt.dimension() == 2) {
    // CGAL's edge iterator gives each edge from whichever of its two faces lies lower in memory,
    // so the edges' order changed from run to run (the same edges, but files that differ and
    // sums in another order). Each edge is taken here from the face whose third point comes
    // first in `from` (or from its one finite face on the hull): the faces' own order depends
    // only on the points, so the same points give the same edges in the same order.
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
      for (int i = 0; i < 3; ++i) {
        const auto other = f->neighbor(i);
        if (!dt.is_infinite(other) &&
            other->vertex(other->index(f))->info() < f->vertex(i)->info()) {
          continue;
        }
        add_raw(f->vertex(Delaunay::cw(i))->info(), f->vertex(Delaunay::ccw(i))->info());
      }
    }
  } else {
    // Points on one line: edges but no faces. Their order is sorted for the same reason.
    for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
      add_raw(e->first->vertex(Delaunay::cw(e->second))->info(),
              e->first->vertex(Delaunay::ccw(e->second))->info());
    }
    std::sort(raw.begin(), raw.end(),
              [](const Raw& x, const Raw& y) { return std::tie(x.a, x.b) < std::tie(y.a, y.b); });
  }
  if (raw.empty()) return;  // all points collinear or coincident
  std::vector<double> lengths;
  for (const auto& r : raw) lengths.push_back(r.length_from);
  const double bound = max_edge_ratio * median(std::move(lengths));

  // Whether an edge is kept depends only on its length, so faces test their edges directly.
  auto edge_kept = [&](std::int32_t a, std::int32_t b) {
    const auto& pa = from[static_cast<std::size_t>(a)];
    const auto& pb = from[static_cast<std::size_t>(b)];
    const double length = std::hypot(pb.x_mm - pa.x_mm, pb.y_mm - pa.y_mm);
    return length <= bound && length > 0;
  };
  for (const auto& r : raw) {
    if (!(r.length_from <= bound && r.length_from > 0)) continue;
    const auto& qa = to[static_cast<std::size_t>(r.a)];
    const auto& qb = to[static_cast<std::size_t>(r.b)];
    const double length_to = std::hypot(qb.x_mm - qa.x_mm, qb.y_mm - qa.y_mm);
    edges.push_back({from[static_cast<std::size_t>(r.a)].track_id,
                     from[static_cast<std::size_t>(r.b)].track_id, r.length_from, length_to,
                     (length_to - r.length_from) / r.length_from});
  }
  for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f) {
    const std::int32_t a = f->vertex(0)->info();
    const std::int32_t b = f->vertex(1)->info();
    const std::int32_t c = f->vertex(2)->info();
    if (edge_kept(a, b) && edge_kept(b, c) && edge_kept(c, a)) triangles.push_back({{a, b, c}});
  }
}

}  // namespace tactile::capture
