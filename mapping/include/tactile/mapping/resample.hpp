#pragma once
// Time resampling from the camera's frame times to the display's rate.

#include <cstdint>
#include <vector>

namespace tactile::mapping {

// Frames of equally many values sampled at increasing times (values frame-major).
struct TimedFrames {
  std::vector<double> t_s;
  std::int32_t values_per_frame = 0;
  std::vector<double> values;
};

// Display frames at t_s[0] + i / rate_hz for i = 0 .. floor((t_s.back() - t_s[0]) * rate_hz),
// each value interpolated linearly between the two camera frames around it (the movie spans the
// camera samples exactly; nothing is extrapolated). Linear interpolation keeps every output
// between its neighbouring camera values, so it never overshoots the deflection range. Throws
// std::invalid_argument for no frames, non-increasing times, inconsistent sizes or rate <= 0.
TimedFrames resample_linear(const TimedFrames& camera, double rate_hz);

}  // namespace tactile::mapping
