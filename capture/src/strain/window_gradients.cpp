#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

#include "tactile/capture/capture.hpp"
#include "tracking/track_gradient.hpp"

namespace tactile::capture {

namespace {

// The millimetre map's Jacobian at a pixel (exact for the uniform scale; for a homography the
// central difference over one pixel is far finer than the skin's strain).
Eigen::Matrix2d mm_per_px_at(const Calibration& calibration, const Eigen::Vector2d& p) {
  constexpr double h = 0.5;
  const PointMm x0 = to_mm(calibration, p.x() - h, p.y()),
                x1 = to_mm(calibration, p.x() + h, p.y());
  const PointMm y0 = to_mm(calibration, p.x(), p.y() - h),
                y1 = to_mm(calibration, p.x(), p.y() + h);
  Eigen::Matrix2d j;
  j << x1.x_mm - x0.x_mm, y1.x_mm - y0.x_mm, x1.y_mm - x0.y_mm, y1.y_mm - y0.y_mm;
  return j / (2 * h);
}

Eigen::Vector2d position_at(const Track& t, int frame) {
  const auto k = static_cast<std::size_t>(frame - t.first_frame);
  return {t.x_px[k], t.y_px[k]};
}

}  // namespace

void blend_window_gradients(StrainFrame& frame, const TracksById& tracks,
                            const Calibration& calibration, double share) {
  if (!(share >= 0 && share <= 1)) {
    throw std::invalid_argument("blend_window_gradients: share must be 0 to 1");
  }
  if (share == 0) return;
  const int from = frame.frame_from, to = frame.frame_to;
  const auto measured = [&](std::int32_t id) -> const Track* {
    const auto it = tracks.find(id);
    if (it == tracks.end()) return nullptr;
    const Track& t = *it->second;
    const bool covers = t.first_frame <= from && t.last_frame() >= to;
    return covers && has_gradients(t) ? &t : nullptr;
  };
  for (auto& e : frame.edges) {
    const Track* a = measured(e.track_a);
    const Track* b = measured(e.track_b);
    if (!a || !b || !(e.length_from_mm > 0)) continue;
    // Each end's deformation from `from` to `to`; their mean carries the edge along.
    const Eigen::Matrix2d fa = gradient_at(*a, from), fb = gradient_at(*b, from);
    if (std::abs(fa.determinant()) < 1e-6 || std::abs(fb.determinant()) < 1e-6) continue;
    const Eigen::Matrix2d step =
        0.5 * (gradient_at(*a, to) * fa.inverse() + gradient_at(*b, to) * fb.inverse());
    const Eigen::Vector2d edge_px = position_at(*b, from) - position_at(*a, from);
    const Eigen::Vector2d mid_from = 0.5 * (position_at(*a, from) + position_at(*b, from));
    const Eigen::Vector2d mid_to = 0.5 * (position_at(*a, to) + position_at(*b, to));
    const double before = (mm_per_px_at(calibration, mid_from) * edge_px).norm();
    const double after = (mm_per_px_at(calibration, mid_to) * step * edge_px).norm();
    if (!(before > 0) || !std::isfinite(after)) continue;
    const double by_windows = after / before - 1;
    e.rel_change = (1 - share) * e.rel_change + share * by_windows;
    e.length_to_mm = e.length_from_mm * (1 + e.rel_change);
  }
}

}  // namespace tactile::capture
