#include "tactile/capture/pore_score.hpp"

#include <cmath>
#include <utility>

namespace tactile::capture {

namespace {

// Index of the point of `pts` nearest (x, y) and its distance; pts.size() when there is none.
template <class Points, class X, class Y>
std::pair<std::size_t, double> nearest(double x, double y, const Points& pts, X px, Y py) {
  std::size_t best = pts.size();
  double best_d = 1e30;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = std::hypot(px(pts[i]) - x, py(pts[i]) - y);
    if (d < best_d) {
      best_d = d;
      best = i;
    }
  }
  return {best, best_d};
}

}  // namespace

PoreScore score_pores(const std::vector<Feature>& found,
                      const std::vector<std::array<double, 2>>& marked_px, double bound_px) {
  const auto fx = [](const Feature& f) { return f.x_px; };
  const auto fy = [](const Feature& f) { return f.y_px; };
  const auto mx = [](const std::array<double, 2>& m) { return m[0]; };
  const auto my = [](const std::array<double, 2>& m) { return m[1]; };
  PoreScore s{static_cast<int>(marked_px.size()), static_cast<int>(found.size()), 0};
  for (std::size_t i = 0; i < found.size(); ++i) {
    const auto [m, d] = nearest(found[i].x_px, found[i].y_px, marked_px, mx, my);
    if (m == marked_px.size() || d > bound_px) continue;
    const auto [back, d_back] = nearest(marked_px[m][0], marked_px[m][1], found, fx, fy);
    if (back == i) ++s.matched;
  }
  return s;
}

PoreScore score_ridge_blob_pores(const PoreTrainingPrint& print, double px_per_mm,
                                 const RidgeBlobParams& params) {
  FeatureParams p;
  p.pore_detector = PoreDetector::ridge_blob;
  p.ridge_blob = params;
  p.find_minutiae = false;
  p.border_margin_mm = 0.0;
  return score_pores(extract_features(print.image, px_per_mm, p), print.pores_px,
                     kPoreMatchRadiusMm * px_per_mm);
}

}  // namespace tactile::capture
