#pragma once
// Device-independent limits of a tactile movie, shared by what makes movies (mapping) and what
// plays them (display's player and emulated device), so a mapped movie shows what the skin will
// get and a movie that cannot be played is refused when it is made, not when it is played.

#include <string_view>

namespace tactile::movie {

// Devices play whole rates: the wire protocol carries the rate as an unsigned 16-bit number of
// hertz, so 500.5 Hz could only be played as 500 or 501 Hz, a different movie.
inline constexpr double kMaxPlayableRateHz = 65535;
inline constexpr std::string_view kPlayableRateRule = "a whole number of hertz from 1 to 65535";

// True for a rate a device can play (see kPlayableRateRule).
bool is_playable_rate(double rate_hz);

// Throws std::invalid_argument "<what> <rate> Hz is not playable: devices play <rule>" unless
// is_playable_rate(rate_hz).
void require_playable_rate(double rate_hz, std::string_view what);

// The default slew limit of the display firmware, and so the one mappings apply. Assumption:
// 20 mm/s lets a contactor cross the whole +-50 um STReSS range in 5 ms (3.5 frames at 700 Hz),
// fast enough for any strain-derived movie yet a real limit on step inputs.
inline constexpr double kDefaultSlewLimitUmPerS = 20000.0;

}  // namespace tactile::movie
