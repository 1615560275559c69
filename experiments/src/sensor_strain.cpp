// Ground-truth skin strain of the simulated fingertip (see sensor_strain.hpp).

#include "tactile/experiments/sensor_strain.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "tactile/perception/sensor_contact.hpp"

namespace tactile::experiments {

// The composing layer: it speaks every module's vocabulary.
using namespace tactile::capture;
using namespace tactile::perception;
namespace {

struct SkinPoint {
  double x_mm, y_mm, z_mm;  // lateral position on the pad and depth below it
};

double length_mm(const SkinPoint& a, const SkinPoint& b) {
  return std::sqrt((a.x_mm - b.x_mm) * (a.x_mm - b.x_mm) + (a.y_mm - b.y_mm) * (a.y_mm - b.y_mm) +
                   (a.z_mm - b.z_mm) * (a.z_mm - b.z_mm));
}

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

}  // namespace

StrainMovie simulate_skin_strain(const SurfaceFeature& feature, Procedure procedure,
                                 std::uint64_t seed, const SensorModel& m,
                                 const SkinStrainOptions& o) {
  if (!(o.grid_spacing_mm > 0) || !(o.half_length_mm > 0) || !(o.half_width_mm > 0) ||
      !std::isfinite(o.grid_spacing_mm + o.half_length_mm + o.half_width_mm))
    throw std::invalid_argument(
        fmt::format("skin strain: grid spacing {} mm and half extents {} x {} mm must be positive",
                    o.grid_spacing_mm, o.half_length_mm, o.half_width_mm));
  constexpr double kRateHz = 100.0;  // the sensor's row rate: the balance steps at this rate
  const TrialVariation variation = draw_variation(seed, m.variation);
  std::vector<contact::Pose> poses = contact::plan(procedure, variation, m, kRateHz);
  const double kappa = contact::arm_stiffness(procedure, m);

  const int nx = static_cast<int>(std::floor(2 * o.half_length_mm / o.grid_spacing_mm + 1e-9)) + 1;
  const int ny = static_cast<int>(std::floor(2 * o.half_width_mm / o.grid_spacing_mm + 1e-9)) + 1;
  const auto nodes = static_cast<std::size_t>(nx * ny);
  const auto rest = [&](int i, int j) {
    return std::array<double, 2>{-o.half_length_mm + i * o.grid_spacing_mm,
                                 -o.half_width_mm + j * o.grid_spacing_mm};
  };
  // Grid edges as node pairs; the diagonal (i, j)-(i+1, j+1) splits each cell.
  std::vector<std::array<std::int32_t, 2>> edges;
  std::vector<StrainTriangle> triangles;
  const auto id = [&](int i, int j) { return static_cast<std::int32_t>(j * nx + i); };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) edges.push_back({id(i, j), id(i + 1, j)});
      if (j + 1 < ny) edges.push_back({id(i, j), id(i, j + 1)});
      if (i + 1 < nx && j + 1 < ny) {
        edges.push_back({id(i, j), id(i + 1, j + 1)});
        triangles.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}});
        triangles.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}});
      }
    }

  StrainMovie movie;
  movie.frame_rate_hz = kRateHz;
  movie.span_frames = o.from_rest ? 0 : 1;
  movie.camera_frame_count = static_cast<std::int32_t>(poses.size());
  movie.field_width_mm = 2 * o.half_length_mm;
  movie.field_height_mm = 2 * o.half_width_mm;
  movie.calibration.method = "skin model (pad coordinates)";
  movie.provenance = make_provenance(
      {}, "skin strain of the simulated fingertip",
      nlohmann::json{{"procedure", procedure_name(procedure)},
                     {"trial", seed},
                     {"curvature", feature.curvature == Curvature::planar    ? "planar"
                                   : feature.curvature == Curvature::conical ? "conical"
                                                                             : "spherical"},
                     {"signed_footprint_mm", feature.signed_footprint_mm()},
                     {"from_rest", o.from_rest}}
          .dump());

  // The skin surface of every frame: lateral position (rest position + drag) and indentation.
  const auto skin_at = [&](const contact::Pose& p, double drag_mm, std::vector<SkinPoint>& out) {
    const double sliding_x = procedure == Procedure::distal_proximal ? 1.0 : 0.0;
    const double sliding_y = procedure == Procedure::radial_ulnar ? 1.0 : 0.0;
    out.resize(nodes);
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const auto [x, y] = rest(i, j);
        const double u = contact::indentation_mm(feature, p, m, x, y);
        out[static_cast<std::size_t>(id(i, j))] = {x + drag_mm * u * sliding_x,
                                                   y + drag_mm * u * sliding_y, -u};
      }
  };
  const auto tracked = [&](const std::vector<SkinPoint>& skin, std::int32_t frame) {
    std::vector<TrackedPoint> points(nodes);
    for (std::size_t k = 0; k < nodes; ++k)
      points[k] = {static_cast<std::int32_t>(k),
                   frame,
                   FeatureType::pore,
                   0,
                   0,
                   skin[k].x_mm + o.half_length_mm,
                   skin[k].y_mm + o.half_width_mm};
    return points;
  };

  double depth = 0, slid_mm = 0;
  std::vector<SkinPoint> reference, previous, current;
  std::vector<TrackedPoint> reference_points;
  for (std::size_t f = 0; f < poses.size(); ++f) {
    contact::Pose p = poses[f];
    depth = contact::balance_depth(feature, p, p.depth_mm, depth, m, kappa);
    p.depth_mm = depth;
    slid_mm += p.slide_mm_s / kRateHz;
    // Sliding friction drags the skin with the plate, in proportion to the local load (the
    // Winkler skin's pressure is its indentation); the drag builds up over the first millimetre
    // of sliding and static friction holds it when the motion stops.
    const double drag_mm = o.drag_per_mm * smoothstep(slid_mm / o.drag_build_up_mm);
    skin_at(p, drag_mm, current);
    const auto frame = static_cast<std::int32_t>(f);
    if (f == 0) {
      reference = current;
      reference_points = tracked(current, 0);
    } else {
      const std::vector<SkinPoint>& from = o.from_rest ? reference : previous;
      StrainFrame sf;
      sf.frame_from = o.from_rest ? 0 : frame - 1;
      sf.frame_to = frame;
      sf.t_s = static_cast<double>(f) / kRateHz;
      sf.points_from = o.from_rest ? reference_points : tracked(previous, frame - 1);
      sf.points_to = tracked(current, frame);
      sf.edges.reserve(edges.size());
      for (const auto& [a, b] : edges) {
        const double l0 =
            length_mm(from[static_cast<std::size_t>(a)], from[static_cast<std::size_t>(b)]);
        const double l1 =
            length_mm(current[static_cast<std::size_t>(a)], current[static_cast<std::size_t>(b)]);
        sf.edges.push_back({a, b, l0, l1, (l1 - l0) / l0});
      }
      sf.triangles = triangles;
      movie.frames.push_back(std::move(sf));
    }
    std::swap(previous, current);
  }
  return movie;
}

}  // namespace tactile::experiments
