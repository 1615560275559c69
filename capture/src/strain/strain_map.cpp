#include "tactile/capture/strain_map.hpp"
#include "tactile/common/stats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tactile/common/image_write.hpp"

namespace tactile::capture {

namespace {

// Dark blue background: black, grey and white edges all stand out against it.
const cv::Scalar kBackground(70, 40, 20);
const cv::Scalar kText(230, 230, 230);

// rel_change -> grey level: -full_scale black, 0 mid grey, +full_scale white.
int grey_of(double rel_change, double full_scale) {
  const double t = std::clamp(0.5 + 0.5 * rel_change / full_scale, 0.0, 1.0);
  return static_cast<int>(std::lround(255.0 * t));
}

void draw_scale(cv::Mat& image, double full_scale) {
  const int x0 = 10, y0 = image.rows - 28, width = 160, height = 12;
  for (int i = 0; i < width; ++i) {
    const double rel = full_scale * (2.0 * i / (width - 1) - 1.0);
    const int g = grey_of(rel, full_scale);
    cv::line(image, {x0 + i, y0}, {x0 + i, y0 + height}, cv::Scalar(g, g, g));
  }
  cv::rectangle(image, {x0 - 1, y0 - 1}, {x0 + width, y0 + height + 1}, kText);
  const auto label = fmt::format("{:+.1f} %  compressed .. stretched  {:+.1f} %", -100 * full_scale,
                                 100 * full_scale);
  cv::putText(image, label, {x0 + width + 8, y0 + height}, cv::FONT_HERSHEY_SIMPLEX, 0.4, kText, 1,
              cv::LINE_AA);
}

}  // namespace

double strain_map_full_scale(const StrainMovie& movie) {
  std::vector<double> magnitudes;
  for (const auto& f : movie.frames) {
    for (const auto& e : f.edges) {
      if (std::isfinite(e.rel_change)) magnitudes.push_back(std::abs(e.rel_change));
    }
  }
  return quantile(std::move(magnitudes), 0.99);
}

void write_strain_map_png(const std::filesystem::path& path, const StrainFrame& frame,
                          const Calibration& calibration, const StrainMapOptions& options) {
  if (!(options.full_scale > 0) || !std::isfinite(options.full_scale)) {
    throw std::invalid_argument(fmt::format(
        "strain map: full scale must be a positive number, got {}", options.full_scale));
  }
  if (calibration.image_width_px <= 0 || calibration.image_height_px <= 0) {
    throw std::invalid_argument("strain map: the calibration gives no image size");
  }
  std::unordered_map<std::int32_t, const TrackedPoint*> by_track;
  for (const auto& p : frame.points_to) by_track[p.track_id] = &p;

  cv::Mat image(calibration.image_height_px, calibration.image_width_px, CV_8UC3, kBackground);
  for (const auto& e : frame.edges) {
    const auto a = by_track.find(e.track_a);
    const auto b = by_track.find(e.track_b);
    if (a == by_track.end() || b == by_track.end()) {
      throw std::invalid_argument(fmt::format(
          "strain map: edge {}-{} of frames {}->{} names a track that is not a point of the frame",
          e.track_a, e.track_b, frame.frame_from, frame.frame_to));
    }
    const int g = grey_of(e.rel_change, options.full_scale);
    cv::line(image, cv::Point2d(a->second->x_px, a->second->y_px),
             cv::Point2d(b->second->x_px, b->second->y_px), cv::Scalar(g, g, g),
             options.line_width_px, cv::LINE_AA);
  }
  cv::putText(image, fmt::format("strain, frames {} -> {}", frame.frame_from, frame.frame_to),
              {10, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.5, kText, 1, cv::LINE_AA);
  draw_scale(image, options.full_scale);
  write_image_atomically(path, image);
}

}  // namespace tactile::capture
