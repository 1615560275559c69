#include <algorithm>
#include <cmath>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "camera/cv_image.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {

RefineStats refine_tracks(const std::vector<GrayImage>& frames, std::vector<Track>& tracks,
                          double px_per_mm, const RefineParams& params) {
  if (!(px_per_mm > 0)) throw std::invalid_argument("refine_tracks: px_per_mm must be > 0");
  if (!(params.window_mm > 0)) throw std::invalid_argument("refine_tracks: window_mm must be > 0");
  if (!(params.anchor_weight >= 0 && params.anchor_weight <= 1)) {
    throw std::invalid_argument("refine_tracks: anchor_weight must be 0 to 1");
  }
  RefineStats stats;
  const int n = static_cast<int>(frames.size());
  for (const auto& t : tracks) {
    if (t.first_frame < 0 || t.last_frame() >= n) {
      throw std::invalid_argument("refine_tracks: a track reaches beyond the frames");
    }
  }
  const int side =
      std::max(5, 2 * static_cast<int>(std::lround(params.window_mm * px_per_mm / 2)) + 1);
  const cv::Size window(side, side);
  const cv::TermCriteria stop(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 30, 0.003);

  // The detected positions stay the anchors; `refined` is filled frame by frame.
  std::vector<Track> refined = tracks;
  std::vector<cv::Point2f> from, to, back;
  std::vector<std::size_t> which;
  std::vector<unsigned char> ok_fwd, ok_back;
  std::vector<float> err;
  for (int f = 0; f + 1 < n; ++f) {
    from.clear();
    to.clear();
    which.clear();
    for (std::size_t i = 0; i < tracks.size(); ++i) {
      const Track& d = tracks[i];
      if (d.first_frame > f || d.last_frame() < f + 1) continue;
      const auto k = static_cast<std::size_t>(f - d.first_frame);
      const Track& r = refined[i];
      from.emplace_back(static_cast<float>(r.x_px[k]), static_cast<float>(r.y_px[k]));
      // Started from the detected step: within a pixel or two of the true one.
      to.emplace_back(static_cast<float>(r.x_px[k] + d.x_px[k + 1] - d.x_px[k]),
                      static_cast<float>(r.y_px[k] + d.y_px[k + 1] - d.y_px[k]));
      which.push_back(i);
    }
    if (from.empty()) continue;
    const cv::Mat a = as_mat(frames[static_cast<std::size_t>(f)]);
    const cv::Mat b = as_mat(frames[static_cast<std::size_t>(f + 1)]);
    cv::calcOpticalFlowPyrLK(a, b, from, to, ok_fwd, err, window, 1, stop,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    back = from;
    cv::calcOpticalFlowPyrLK(b, a, to, back, ok_back, err, window, 1, stop,
                             cv::OPTFLOW_USE_INITIAL_FLOW);
    for (std::size_t j = 0; j < which.size(); ++j) {
      const Track& d = tracks[which[j]];
      Track& r = refined[which[j]];
      const auto k = static_cast<std::size_t>(f - d.first_frame);
      double x = r.x_px[k] + d.x_px[k + 1] - d.x_px[k];
      double y = r.y_px[k] + d.y_px[k + 1] - d.y_px[k];
      ++stats.steps;
      const bool confirmed =
          ok_fwd[j] && ok_back[j] &&
          std::hypot(back[j].x - from[j].x, back[j].y - from[j].y) <= params.max_back_error_px &&
          std::hypot(to[j].x - x, to[j].y - y) <= 0.5 * side;
      if (confirmed) {
        x = to[j].x;
        y = to[j].y;
      } else {
        ++stats.rejected;
      }
      r.x_px[k + 1] = x + params.anchor_weight * (d.x_px[k + 1] - x);
      r.y_px[k + 1] = y + params.anchor_weight * (d.y_px[k + 1] - y);
    }
  }
  tracks = std::move(refined);
  return stats;
}

}  // namespace tactile::capture
