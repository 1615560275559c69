#pragma once
// When a camera frame was available, by the camera driver's own clock where it can be trusted.

#include <chrono>
#include <optional>

namespace tactile::live {

using Clock = std::chrono::steady_clock;

// A V4L2 buffer's timestamp as OpenCV's V4L2 capture reports it (CAP_PROP_POS_MSEC:
// milliseconds on CLOCK_MONOTONIC, the clock steady_clock reads on Linux) as the moment the frame
// was available, when it is plausible: not after `arrival` and at most a second before it. A
// driver that stamps on another clock (or not at all: 0) is far off, and arrival stands.
std::optional<Clock::time_point> driver_time(double pos_msec, Clock::time_point arrival);

}  // namespace tactile::live
