#pragma once
// Pore detections scored against hand-marked pores the way published PolyU HRF figures are:
// detections and marks paired one-to-one as mutual nearest neighbours closer than a bound.

#include <array>
#include <vector>

#include "tactile/capture/features.hpp"
#include "tactile/capture/pore_training.hpp"
#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

// The bound of the PolyU HRF convention (7 px at 1200 dpi).
constexpr double kPoreMatchRadiusMm = 0.15;

struct PoreScore {
  int marked = 0;
  int detected = 0;
  int matched = 0;

  // Fraction of marked pores found (TDR) and of detections that are no marked pore (FDR).
  double true_detection_rate() const { return marked > 0 ? double(matched) / marked : 0.0; }
  double false_detection_rate() const {
    return detected > 0 ? 1.0 - double(matched) / detected : 0.0;
  }
  PoreScore& operator+=(const PoreScore& other) {
    marked += other.marked;
    detected += other.detected;
    matched += other.matched;
    return *this;
  }
};

// `found` against `marked_px` (x, y), pairs closer than `bound_px`.
PoreScore score_pores(const std::vector<Feature>& found,
                      const std::vector<std::array<double, 2>>& marked_px, double bound_px);

// The ridge-blob detector with `params` on the whole print (no border margin, no minutiae: the
// marks cover the whole image), scored within kPoreMatchRadiusMm.
PoreScore score_ridge_blob_pores(const PoreTrainingPrint& print, double px_per_mm,
                                 const RidgeBlobParams& params);

}  // namespace tactile::capture
