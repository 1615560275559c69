#pragma once
// One mapping as the authoring window shows it: the movie a MapRequest makes of a strain movie,
// its fidelity figures (whole and over time) and where it saturates or is slew-limited, with
// the time the mapping took. The rules are the mapping library's own (map_request.hpp,
// fidelity.hpp); this adds nothing to them but the slicing in time.

#include <memory>
#include <string>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/mapping/fidelity.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/mapping/map_request.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::author {

// Fidelity over a stretch of the strain movie's time.
struct FidelityPoint {
  double t0_s = 0, t1_s = 0;  // the strain frames' times the stretch covers
  double strain_correlation = 0;
  double strain_rms_error = 0;
  double saturated_fraction = 0;     // of the contactor-frames between t0_s and t1_s
  double slew_limited_fraction = 0;  // of the frame steps between t0_s and t1_s
};

struct MappingOutcome {
  mapping::MapRequest request;  // as asked
  // Set when the request was refused or the mapping failed: the message (in the command line's
  // spelling), and nothing else below is set.
  std::string error;
  movie::Layout layout;
  mapping::MappingParams params;  // resolved (rate_hz set)
  movie::TactileMovie movie;
  mapping::FidelityMetrics metrics;
  std::vector<FidelityPoint> over_time;
  // Per contactor, the share of its frames at a limit of the deflection range and of its frame
  // steps at the slew limit (mapping::at_deflection_limit, at_slew_limit).
  std::vector<float> saturated_share;
  std::vector<float> slew_limited_share;
  double map_ms = 0;      // the mapping alone
  double figures_ms = 0;  // fidelity, over time and per contactor
};

// How many stretches of time `over_time` has at most.
inline constexpr int kFidelityStretches = 24;

// Maps `strain` as `request` asks (the strain file and the request's strain path are not read:
// the strain is given), the program version stamped as `map` does. A refused request or a
// failed mapping is an outcome with `error` set, never an exception: the window shows it.
MappingOutcome map_for_authoring(const capture::StrainMovie& strain,
                                 const mapping::MapRequest& request);

// The figures of two outcomes side by side, a line each, as the window's A/B table and the
// command's log show them: "correlation", "RMS error", "saturated %", "slew-limited %", "map ms".
struct FigureRow {
  std::string name;
  double a = 0, b = 0;
};
std::vector<FigureRow> compare_figures(const MappingOutcome& a, const MappingOutcome& b);

// What changed from `a` to `b`, in the command line's words ("--method integrated ->
// proportional, --gain 1000 -> 2000"); "same mapping" when nothing did.
std::string describe_change(const mapping::MapRequest& a, const mapping::MapRequest& b);

}  // namespace tactile::author
