#pragma once
// Deflection limits applied to every mapped movie. The firmware enforces the same two limits on
// the device (its safety rules); applying them here too means the movie file shows what the
// skin will actually get.

#include "tactile/movie/limits.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// Clamps every deflection to [layout.deflection_min_um, layout.deflection_max_um], then limits how
// far each contactor may move between consecutive frames to slew_limit_um_per_s / rate_hz. The
// slew limit starts from neutral (0, clamped to the range), where the firmware leaves contactors
// before a movie starts. Throws std::invalid_argument for slew_limit_um_per_s <= 0 or an
// inconsistent movie.
movie::TactileMovie apply_limits(movie::TactileMovie movie, double slew_limit_um_per_s);

}  // namespace tactile::mapping
