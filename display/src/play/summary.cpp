// Movie summary statistics; see summary.hpp.
#include "tactile/display/summary.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tactile::display {

std::vector<double> frame_rms_um(const movie::TactileMovie& movie) {
  std::vector<double> rms(static_cast<std::size_t>(std::max(movie.frame_count, 0)));
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    double sum = 0;
    const auto frame = movie.frame(f);
    for (float v : frame) sum += static_cast<double>(v) * v;
    rms[static_cast<std::size_t>(f)] = frame.empty() ? 0 : std::sqrt(sum / frame.size());
  }
  return rms;
}

MovieSummary summarize(const movie::TactileMovie& movie) {
  validate_movie(movie);
  MovieSummary s;
  s.layout_name = movie.layout.name;
  s.rows = movie.layout.rows;
  s.cols = movie.layout.cols;
  s.rate_hz = movie.rate_hz;
  s.frame_count = movie.frame_count;
  s.duration_s = movie.duration_s();
  const double hi = movie.layout.deflection_max_um - 0.05;
  const double lo = movie.layout.deflection_min_um + 0.05;
  double sum = 0;
  std::size_t saturated = 0;
  for (float v : movie.deflection_um) {
    s.peak_deflection_um = std::max(s.peak_deflection_um, std::abs(static_cast<double>(v)));
    sum += static_cast<double>(v) * v;
    if (v >= hi || v <= lo) ++saturated;
  }
  const auto n = movie.deflection_um.size();
  if (n > 0) {
    s.rms_deflection_um = std::sqrt(sum / n);
    s.saturated_fraction = static_cast<double>(saturated) / n;
  }
  const std::vector<double> rms = frame_rms_um(movie);
  for (std::size_t f = 0; f < rms.size(); ++f) {
    if (rms[f] > s.peak_frame_rms_um) {
      s.peak_frame_rms_um = rms[f];
      s.peak_frame_t_s = f / movie.rate_hz;
    }
  }
  // Windows hold whole frames: frame f belongs to window floor(t_f / 0.1 s). The RMS of a
  // window is over all its samples, i.e. the root of the mean of the frames' mean squares.
  const auto windows =
      static_cast<std::size_t>(std::ceil(s.duration_s / s.activity_window_s - 1e-9));
  std::vector<double> sq(windows, 0.0);
  std::vector<int> count(windows, 0);
  for (std::size_t f = 0; f < rms.size(); ++f) {
    const auto w = std::min(
        windows - 1, static_cast<std::size_t>(f / movie.rate_hz / s.activity_window_s + 1e-9));
    sq[w] += rms[f] * rms[f];
    count[w]++;
  }
  s.activity_rms_um.resize(windows);
  for (std::size_t w = 0; w < windows; ++w) {
    s.activity_rms_um[w] = count[w] > 0 ? std::sqrt(sq[w] / count[w]) : 0.0;
  }
  return s;
}

std::string frame_count_text(std::int64_t movie_frames, std::int64_t ramp_frames) {
  if (ramp_frames == 0) return fmt::format("{} movie frames", movie_frames);
  return fmt::format("{} movie frames + {} frames of ramp from and to rest", movie_frames,
                     ramp_frames);
}

std::string format_summary(const MovieSummary& s) {
  std::string out;
  out += fmt::format("layout      {} ({} x {} contactors)\n", s.layout_name, s.rows, s.cols);
  out += fmt::format("length      {} at {} Hz = {:.3f} s\n",
                     frame_count_text(s.frame_count, s.ramp_frames), s.rate_hz, s.duration_s);
  out += fmt::format("deflection  peak {:.2f} um, RMS {:.2f} um\n", s.peak_deflection_um,
                     s.rms_deflection_um);
  out += fmt::format("activity    peak frame RMS {:.2f} um at t = {:.3f} s\n", s.peak_frame_rms_um,
                     s.peak_frame_t_s);
  out += fmt::format("saturated   {:.2f} % of samples at the deflection limits\n",
                     100.0 * s.saturated_fraction);
  // A one-line sparkline of activity per window, scaled to the peak window.
  static const char* const kLevels[] = {" ", ".", ":", "-", "=", "+", "*", "#"};
  double peak = 0;
  for (double a : s.activity_rms_um) peak = std::max(peak, a);
  std::string line;
  for (double a : s.activity_rms_um) {
    const int level = peak > 0 ? static_cast<int>(std::lround(7 * a / peak)) : 0;
    line += kLevels[std::clamp(level, 0, 7)];
  }
  out += fmt::format("activity    per {:.1f} s (peak {:.2f} um RMS): |{}|\n", s.activity_window_s,
                     peak, line);
  return out;
}

}  // namespace tactile::display
