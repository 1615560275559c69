// Tactile movies as perception signals (see movie_signals.hpp).

#include "tactile/perception/movie_signals.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace tactile::perception {

using perception::kElectrodeClusterCount;
using perception::kElectrodeCount;

std::vector<int> contactor_clusters(const movie::Layout& layout) {
  if (layout.cols < kElectrodeClusterCount)
    throw std::invalid_argument(
        fmt::format("movie signals: layout '{}' has {} columns, fewer than the {} clusters",
                    layout.name, layout.cols, kElectrodeClusterCount));
  std::vector<int> clusters;
  clusters.reserve(static_cast<std::size_t>(layout.contactor_count()));
  for (std::int32_t r = 0; r < layout.rows; ++r)
    for (std::int32_t c = 0; c < layout.cols; ++c)
      clusters.push_back(
          static_cast<int>(std::floor(kElectrodeClusterCount * (c + 0.5) / layout.cols)));
  return clusters;
}

perception::SensorRecording movie_signals(const movie::TactileMovie& movie,
                                          const std::string& source) {
  movie::validate_movie(movie);
  const auto clusters = contactor_clusters(movie.layout);
  perception::SensorRecording r;
  r.source = source;
  const double frames_per_row = movie.rate_hz / r.rate_hz;
  const auto rows = static_cast<std::size_t>(std::floor(movie.frame_count / frames_per_row));
  if (rows == 0)
    throw std::invalid_argument(
        fmt::format("movie signals: {}: {} frames at {:g} Hz are shorter than one {:g} Hz row",
                    source, movie.frame_count, movie.rate_hz, r.rate_hz));

  // Per display frame: overall activity and the cluster means.
  const auto n = static_cast<std::size_t>(movie.layout.contactor_count());
  std::array<int, kElectrodeClusterCount> members{};
  for (int c : clusters) ++members[static_cast<std::size_t>(c)];
  const auto frames = static_cast<std::size_t>(movie.frame_count);
  std::vector<double> activity(frames);
  std::vector<std::array<double, kElectrodeClusterCount>> cluster(frames);
  for (std::size_t f = 0; f < frames; ++f) {
    const auto d = movie.frame(static_cast<std::int32_t>(f));
    double sum = 0;
    std::array<double, kElectrodeClusterCount> c{};
    for (std::size_t j = 0; j < n; ++j) {
      sum += std::abs(d[j]);
      c[static_cast<std::size_t>(clusters[j])] += d[j];
    }
    activity[f] = sum / static_cast<double>(n);
    for (std::size_t k = 0; k < c.size(); ++k) cluster[f][k] = c[k] / members[k];
  }

  // 100 Hz rows: the mean of the display frames starting within each row's 10 ms. A movie
  // slower than 100 Hz has rows in which no frame starts: they hold the frame on show then.
  for (std::size_t i = 0; i < rows; ++i) {
    auto f0 = static_cast<std::size_t>(std::ceil(static_cast<double>(i) * frames_per_row));
    auto f1 = std::min(
        frames, static_cast<std::size_t>(std::ceil(static_cast<double>(i + 1) * frames_per_row)));
    if (f1 <= f0) {
      f0 = std::min(frames - 1,
                    static_cast<std::size_t>(std::floor(static_cast<double>(i) * frames_per_row)));
      f1 = f0 + 1;
    }
    double a = 0;
    std::array<double, kElectrodeClusterCount> c{};
    for (std::size_t f = f0; f < f1; ++f) {
      a += activity[f];
      for (std::size_t k = 0; k < c.size(); ++k) c[k] += cluster[f][k];
    }
    const double count = static_cast<double>(std::max<std::size_t>(f1 - f0, 1));
    r.t_s.push_back(static_cast<double>(i) / r.rate_hz);
    r.temperature_dc.push_back(0);
    r.temperature_ac.push_back(0);
    r.pressure.push_back(a / count);
    for (int e = 0; e < kElectrodeCount; ++e)
      r.electrodes[static_cast<std::size_t>(e)].push_back(
          c[static_cast<std::size_t>(perception::kElectrodeCluster[static_cast<std::size_t>(e)])] /
          count);
  }

  // Vibration: the change of the activity from each display frame to the next, linearly
  // interpolated at the 2200 Hz sample times.
  std::vector<double> change(frames, 0.0);
  for (std::size_t f = 1; f < frames; ++f) change[f] = activity[f] - activity[f - 1];
  const std::size_t samples = rows * perception::kVibrationPerRow;
  r.vibration.reserve(samples);
  for (std::size_t k = 0; k < samples; ++k) {
    const double at = static_cast<double>(k) / r.vibration_rate_hz * movie.rate_hz;
    const auto f0 = std::min(static_cast<std::size_t>(at), frames - 1);
    const std::size_t f1 = std::min(f0 + 1, frames - 1);
    const double w = at - static_cast<double>(f0);
    r.vibration.push_back((1 - w) * change[f0] + w * change[f1]);
  }
  return r;
}

ContactOptions movie_contact_options() {
  ContactOptions o;
  o.min_threshold = 0.01;
  return o;
}

}  // namespace tactile::perception
