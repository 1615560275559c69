#pragma once
// Private: the first paper's syntactic repair of a valley skeleton (spurs, short valleys,
// bridges, broken valleys), applied before minutiae are read off it.

#include <opencv2/core.hpp>

namespace tactile::capture {

// Lengths in millimetres, against a ridge period of about 0.45 mm (valley to valley).
struct SkeletonRepairParams {
  // A branch from a fork to an ending shorter than about half a ridge period is a notch in the
  // valley's edge left by thinning or noise, not a valley: anatomy forks into full valleys.
  double spur_max_mm = 0.2;
  // An isolated valley piece (ending to ending) shorter than about two thirds of a period is a
  // fragment, not a valley. Such a piece is dropped, not turned into a pore: every bright blob
  // already went through the pore rules (area, extent, fill) before the valleys were thinned,
  // and the ones that passed were masked out, so what reaches the skeleton failed them.
  double short_valley_max_mm = 0.3;
  // A fork-to-fork segment running across the valleys joins two neighbouring valleys over a
  // ridge, typically through a large pore or a ridge gap. Neighbouring valley centre lines are
  // one period (about 0.45 mm) apart, so such a bridge is about 0.45 mm long, more on a slant:
  // the bound is 0.6 mm, not the 0.3 mm of the other rules, which would never see one.
  double bridge_max_mm = 0.6;
  // "Across": more than halfway (45 degrees) from the valley direction at its two forks.
  double bridge_min_angle_rad = 0.7853981633974483;
  // Two endings this close that point at each other are one valley broken by noise or a pore
  // on a thin ridge: shorter than the period, so they cannot be two neighbouring valleys.
  double gap_max_mm = 0.3;
  double gap_max_angle_rad = 0.5235987755982988;  // 30 degrees
  // Ending direction and valley direction are read this far along the branch: enough pixels
  // to average out the thinning's staircase, less than a spur.
  double direction_mm = 0.15;
};

struct SkeletonRepairCounts {
  int spurs = 0;
  int short_valleys = 0;
  int bridges = 0;
  int gaps_joined = 0;
};

// Repairs a CV_8U 0/1 one-pixel skeleton in place: joins broken valleys first (so a valley
// broken twice is not shortened by losing its middle piece), then removes spurs, bridges and
// short valleys until none is left (removing one can reveal another).
SkeletonRepairCounts repair_skeleton(cv::Mat& skeleton, double px_per_mm,
                                     const SkeletonRepairParams& params = {});

}  // namespace tactile::capture
