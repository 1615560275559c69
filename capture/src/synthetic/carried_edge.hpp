#pragma once
// Private: the exact strain of an edge under a known motion, the one computation the synthetic
// scenes' and the warped prints' ground truths share, so that both measure it alike.

#include <cmath>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

struct EdgeLengths {
  double before = 0;  // |b - a|
  double after = 0;   // |carry(b) - carry(a)|
};

// The edge from a to b of one frame, and the same edge once `carry` has taken each end to where
// the skin under it is in another frame.
template <class Carry>
EdgeLengths carried_edge(PointMm a, PointMm b, const Carry& carry) {
  const PointMm a_to = carry(a);
  const PointMm b_to = carry(b);
  return {.before = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm),
          .after = std::hypot(b_to.x_mm - a_to.x_mm, b_to.y_mm - a_to.y_mm)};
}

}  // namespace tactile::capture
