#include "tactile/capture/baselines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "camera/cv_image.hpp"

namespace tactile::capture {

namespace {

void check_sizes(const std::vector<GrayImage>& frames, const char* who) {
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (frames[i].width_px != frames[0].width_px || frames[i].height_px != frames[0].height_px) {
      throw std::invalid_argument(fmt::format("{}: frame {} is {}x{} px, frame 0 is {}x{} px", who,
                                              i, frames[i].width_px, frames[i].height_px,
                                              frames[0].width_px, frames[0].height_px));
    }
  }
}

// Live point tracks, each ending when its point is lost; short ones are dropped at the end.
class TrackSet {
 public:
  void start(int frame, cv::Point2f p) {
    Track t;
    t.first_frame = frame;
    t.x_px.push_back(p.x);
    t.y_px.push_back(p.y);
    live_.push_back(tracks_.size());
    tracks_.push_back(std::move(t));
  }
  std::vector<cv::Point2f> live_points() const {
    std::vector<cv::Point2f> pts;
    for (std::size_t i : live_)
      pts.emplace_back(float(tracks_[i].x_px.back()), float(tracks_[i].y_px.back()));
    return pts;
  }
  // keep[i]: whether live point i was followed to next[i].
  void advance(const std::vector<cv::Point2f>& next, const std::vector<char>& keep) {
    std::vector<std::size_t> still;
    for (std::size_t k = 0; k < live_.size(); ++k) {
      if (!keep[k]) continue;
      tracks_[live_[k]].x_px.push_back(next[k].x);
      tracks_[live_[k]].y_px.push_back(next[k].y);
      still.push_back(live_[k]);
    }
    live_ = std::move(still);
  }
  std::vector<Track> finish(int min_frames) {
    std::vector<Track> kept;
    for (auto& t : tracks_) {
      if (static_cast<int>(t.x_px.size()) < min_frames) continue;
      t.id = static_cast<std::int32_t>(kept.size());
      kept.push_back(std::move(t));
    }
    std::stable_sort(kept.begin(), kept.end(),
                     [](const Track& a, const Track& b) { return a.first_frame < b.first_frame; });
    for (std::size_t i = 0; i < kept.size(); ++i) kept[i].id = static_cast<std::int32_t>(i);
    return kept;
  }

 private:
  std::vector<Track> tracks_;
  std::vector<std::size_t> live_;
};

bool inside(const cv::Point2f& p, const cv::Size& size) {
  return p.x >= 0 && p.y >= 0 && p.x <= size.width - 1.0f && p.y <= size.height - 1.0f;
}

// Where no live point lies within `radius_px` (seeding only fills gaps).
cv::Mat free_mask(const cv::Size& size, const std::vector<cv::Point2f>& live, int radius_px) {
  cv::Mat mask(size, CV_8U, cv::Scalar(255));
  for (const auto& p : live) cv::circle(mask, p, radius_px, cv::Scalar(0), -1);
  return mask;
}

// Flow (CV_32FC2) at a sub-pixel position inside the image.
cv::Point2f bilinear(const cv::Mat& flow, cv::Point2f p) {
  const int x0 = std::clamp(static_cast<int>(p.x), 0, flow.cols - 2);
  const int y0 = std::clamp(static_cast<int>(p.y), 0, flow.rows - 2);
  const float fx = std::clamp(p.x - x0, 0.0f, 1.0f);
  const float fy = std::clamp(p.y - y0, 0.0f, 1.0f);
  const auto& a = flow.at<cv::Vec2f>(y0, x0);
  const auto& b = flow.at<cv::Vec2f>(y0, x0 + 1);
  const auto& c = flow.at<cv::Vec2f>(y0 + 1, x0);
  const auto& d = flow.at<cv::Vec2f>(y0 + 1, x0 + 1);
  const cv::Vec2f v = (1 - fy) * ((1 - fx) * a + fx * b) + fy * ((1 - fx) * c + fx * d);
  return {v[0], v[1]};
}

}  // namespace

std::vector<Track> track_lucas_kanade(const std::vector<GrayImage>& frames,
                                      const Calibration& calibration, const LucasKanadeParams& p) {
  check_sizes(frames, "track_lucas_kanade");
  if (frames.empty() || frames[0].width_px < 8 || frames[0].height_px < 8) return {};
  const double px_per_mm = 1.0 / calibration.mm_per_px;
  const int min_dist = std::max(1, static_cast<int>(std::lround(p.min_distance_mm * px_per_mm)));
  const cv::Size size(frames[0].width_px, frames[0].height_px);
  TrackSet set;
  auto seed = [&](int frame) {
    const auto live = set.live_points();
    std::vector<cv::Point2f> corners;
    cv::goodFeaturesToTrack(as_mat(frames[static_cast<std::size_t>(frame)]), corners,
                            std::max(1, p.max_corners - static_cast<int>(live.size())),
                            p.corner_quality, min_dist, free_mask(size, live, min_dist));
    for (const auto& c : corners) set.start(frame, c);
  };
  seed(0);
  const cv::Size window(p.window_px, p.window_px);
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const auto prev = set.live_points();
    std::vector<char> keep(prev.size(), 0);
    std::vector<cv::Point2f> next, back;
    if (!prev.empty()) {
      std::vector<unsigned char> ok, ok_back;
      std::vector<float> err;
      cv::calcOpticalFlowPyrLK(as_mat(frames[f - 1]), as_mat(frames[f]), prev, next, ok, err,
                               window, p.pyramid_levels);
      cv::calcOpticalFlowPyrLK(as_mat(frames[f]), as_mat(frames[f - 1]), next, back, ok_back, err,
                               window, p.pyramid_levels);
      for (std::size_t i = 0; i < prev.size(); ++i) {
        keep[i] = ok[i] && ok_back[i] && inside(next[i], size) &&
                  cv::norm(back[i] - prev[i]) <= p.max_forward_backward_px;
      }
    }
    set.advance(next, keep);
    if (p.reseed_every_frames > 0 && f % static_cast<std::size_t>(p.reseed_every_frames) == 0) {
      seed(static_cast<int>(f));
    }
  }
  return set.finish(p.min_track_frames);
}

std::vector<Track> track_dis_flow(const std::vector<GrayImage>& frames,
                                  const Calibration& calibration, const DisFlowParams& p) {
  check_sizes(frames, "track_dis_flow");
  if (frames.empty() || frames[0].width_px < 8 || frames[0].height_px < 8) return {};
  const double px_per_mm = 1.0 / calibration.mm_per_px;
  const double step = std::max(1.0, p.grid_spacing_mm * px_per_mm);
  const cv::Size size(frames[0].width_px, frames[0].height_px);
  const int window = std::max(3, static_cast<int>(std::lround(0.3 * px_per_mm)) | 1);
  TrackSet set;
  auto seed = [&](int frame) {
    cv::Mat g;
    as_mat(frames[static_cast<std::size_t>(frame)]).convertTo(g, CV_32F);
    cv::Mat mean, mean_sq;
    cv::blur(g, mean, cv::Size(window, window));
    cv::blur(g.mul(g), mean_sq, cv::Size(window, window));
    const cv::Mat textured = (mean_sq - mean.mul(mean)) > p.min_texture_std * p.min_texture_std;
    const cv::Mat free = free_mask(size, set.live_points(), static_cast<int>(step / 2));
    for (double y = step / 2; y < size.height; y += step) {
      for (double x = step / 2; x < size.width; x += step) {
        const cv::Point2f pt{static_cast<float>(x), static_cast<float>(y)};
        const cv::Point at(static_cast<int>(x), static_cast<int>(y));
        if (textured.at<std::uint8_t>(at) && free.at<std::uint8_t>(at)) set.start(frame, pt);
      }
    }
  };
  seed(0);
  auto dis = cv::DISOpticalFlow::create(std::clamp(p.preset, 0, 2));
  cv::Mat flow;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    dis->calc(as_mat(frames[f - 1]), as_mat(frames[f]), flow);
    const auto prev = set.live_points();
    std::vector<cv::Point2f> next(prev.size());
    std::vector<char> keep(prev.size(), 0);
    for (std::size_t i = 0; i < prev.size(); ++i) {
      next[i] = prev[i] + bilinear(flow, prev[i]);
      keep[i] = inside(next[i], size);
    }
    set.advance(next, keep);
    if (p.reseed_every_frames > 0 && f % static_cast<std::size_t>(p.reseed_every_frames) == 0) {
      seed(static_cast<int>(f));
    }
  }
  return set.finish(p.min_track_frames);
}

}  // namespace tactile::capture
