#pragma once
// Device-independent limits of a tactile movie, shared by what makes movies (mapping) and what
// plays them (display's emulated device), so a mapped movie shows what the skin will get.

namespace tactile::movie {

// The default slew limit of the display firmware, and so the one mappings apply. Assumption:
// 20 mm/s lets a contactor cross the whole +-50 um STReSS range in 5 ms (3.5 frames at 700 Hz),
// fast enough for any strain-derived movie yet a real limit on step inputs.
inline constexpr double kDefaultSlewLimitUmPerS = 20000.0;

}  // namespace tactile::movie
