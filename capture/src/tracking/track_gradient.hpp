#pragma once
// A track's deformation gradients (Track::gradient) as matrices, for the stages that use them:
// the curvature correction (refine.cpp) and the strain's blend (window_gradients.cpp).

#include <Eigen/Dense>
#include <cstddef>

#include "tactile/capture/track.hpp"

namespace tactile::capture {

// Whether the track carries a gradient for every frame it has a position for.
inline bool has_gradients(const Track& t) {
  return t.gradient.size() == t.x_px.size();
}

// The gradient at `frame`, which the track must cover.
inline Eigen::Matrix2d gradient_at(const Track& t, int frame) {
  const auto& g = t.gradient[static_cast<std::size_t>(frame - t.first_frame)];
  Eigen::Matrix2d m;
  m << g[0], g[1], g[2], g[3];
  return m;
}

}  // namespace tactile::capture
