#pragma once
// Deflection limits applied to every mapped movie. The firmware enforces the same two limits on
// the device (its safety rules); applying them here too means the movie file shows what the
// skin will actually get.

#include "tactile/display/emulated_device.hpp"
#include "tactile/display/tactile_movie.hpp"

namespace tactile::mapping {

// What the firmware enforces by default (20 mm/s: a full 100 um swing of a STReSS contactor takes
// 5 ms, 3.5 frames at 700 Hz), so a mapped movie shows what the skin will get.
inline constexpr double kDefaultSlewLimitUmPerS = display::kDefaultMaxSlewUmPerS;

// Clamps every deflection to [layout.deflection_min_um, layout.deflection_max_um], then limits how
// far each contactor may move between consecutive frames to slew_limit_um_per_s / rate_hz. The
// slew limit starts from neutral (0, clamped to the range), where the firmware leaves contactors
// before a movie starts. Throws std::invalid_argument for slew_limit_um_per_s <= 0 or an
// inconsistent movie.
display::TactileMovie apply_limits(display::TactileMovie movie, double slew_limit_um_per_s);

}  // namespace tactile::mapping
