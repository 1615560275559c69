// Causal smoothing of tracks; see causal_smoothing.hpp.

#include "tactile/capture/causal_smoothing.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tactile::capture {

std::vector<double> polynomial_fit_weights(const std::vector<double>& times_frames, int degree,
                                           double read_at_frames) {
  const auto n = static_cast<Eigen::Index>(times_frames.size());
  const Eigen::Index terms = degree + 1;
  if (degree < 0 || n < terms) {
    throw std::invalid_argument(fmt::format(
        "a polynomial fit of degree {} needs at least {} positions, not {}", degree, terms, n));
  }
  Eigen::MatrixXd a(n, terms);
  for (Eigen::Index i = 0; i < n; ++i) {
    double power = 1;
    for (Eigen::Index k = 0; k < terms; ++k, power *= times_frames[static_cast<std::size_t>(i)]) {
      a(i, k) = power;
    }
  }
  Eigen::RowVectorXd read(terms);
  double power = 1;
  for (Eigen::Index k = 0; k < terms; ++k, power *= read_at_frames) read(k) = power;
  // Through QR: the normal equations of a window of 30 frames are ill-conditioned.
  const Eigen::MatrixXd coefficients_of_positions =
      a.colPivHouseholderQr().solve(Eigen::MatrixXd::Identity(n, n));
  const Eigen::RowVectorXd w = read * coefficients_of_positions;
  return std::vector<double>(w.data(), w.data() + w.size());
}

void check_causal_smoothing(const CausalSmoothing& s) {
  if (s.window_frames != CausalSmoothing::kChosenWindow && s.window_frames != 0 &&
      (s.window_frames < 4 || s.window_frames > 30)) {
    throw std::invalid_argument(fmt::format(
        "causal smoothing window: {} frames is out of range: must be 0 (none) or from 4 to 30",
        s.window_frames));
  }
  if (s.degree < 1 || s.degree > 2) {
    throw std::invalid_argument(
        fmt::format("causal smoothing degree: {} is out of range: must be 1 or 2", s.degree));
  }
  if (s.choose_every_frames < 1 || s.choose_every_frames > 10000) {
    throw std::invalid_argument(
        fmt::format("causal smoothing choice: every {} frames is out of range: must be from 1 "
                    "to 10000",
                    s.choose_every_frames));
  }
}

CausalTrackSmoother::CausalTrackSmoother(const CausalSmoothing& smoothing) : smoothing_(smoothing) {
  check_causal_smoothing(smoothing_);
  if (smoothing_.window_frames != CausalSmoothing::kChosenWindow) {
    window_frames_ = smoothing_.window_frames;
  }
}

bool CausalTrackSmoother::choice_due() const {
  return smoothing_.window_frames == CausalSmoothing::kChosenWindow &&
         steps_seen_ >= kCausalChoiceFrames &&
         (steps_seen_ - kCausalChoiceFrames) % smoothing_.choose_every_frames == 0;
}

std::vector<Track> CausalTrackSmoother::tracks_to_choose_by() const {
  std::vector<Track> tracks;
  for (const auto& [id, h] : history_) {
    std::size_t start = h.size() - 1;
    while (start > 0 && h[start - 1].frame + 1 == h[start].frame) --start;
    if (h.size() - start < static_cast<std::size_t>(kCausalChoiceFrames)) continue;
    Track t;
    t.id = id;
    t.first_frame = static_cast<std::int32_t>(h[start].frame);
    for (std::size_t i = start; i < h.size(); ++i) {
      t.x_px.push_back(h[i].x_px);
      t.y_px.push_back(h[i].y_px);
    }
    tracks.push_back(std::move(t));
  }
  return tracks;
}

void CausalTrackSmoother::set_window(int window_frames) {
  CausalSmoothing asked = smoothing_;
  asked.window_frames = window_frames;
  if (window_frames == CausalSmoothing::kChosenWindow) {
    throw std::invalid_argument("causal smoothing: a window to use, not one to choose");
  }
  check_causal_smoothing(asked);
  window_frames_ = window_frames;
}

void CausalTrackSmoother::smooth(std::int64_t frame_from, std::int64_t frame_to,
                                 std::vector<Track>& steps) {
  const bool chosen = smoothing_.window_frames == CausalSmoothing::kChosenWindow;
  const std::size_t kept_frames =
      chosen ? CausalSmoothing::kHistoryFrames : static_cast<std::size_t>(smoothing_.window_frames);
  std::map<std::int32_t, std::vector<Position>> kept;
  for (auto& s : steps) {
    if (s.x_px.size() != 2 || s.y_px.size() != 2) {
      throw std::invalid_argument(fmt::format(
          "causal smoothing: track {} has {} positions, not a step's 2", s.id, s.x_px.size()));
    }
    std::vector<Position> h;
    if (auto it = history_.find(s.id); it != history_.end()) h = std::move(it->second);
    // A track's first step brings its first position; later ones repeat the last.
    if (h.empty() || h.back().frame != frame_from) h = {{frame_from, s.x_px[0], s.y_px[0]}};
    h.push_back({frame_to, s.x_px[1], s.y_px[1]});
    if (h.size() > kept_frames) {
      h.erase(h.begin(), h.end() - static_cast<std::ptrdiff_t>(kept_frames));
    }
    kept[s.id] = std::move(h);
  }
  history_ = std::move(kept);
  ++steps_seen_;

  const int needed = smoothing_.degree + 2;
  if (window_frames_ < needed) return;
  const auto window = static_cast<std::size_t>(window_frames_);
  // A handful of drop patterns at most in a session; bounded all the same.
  if (weights_.size() > 256) weights_.clear();
  for (auto& s : steps) {
    const std::vector<Position>& all = history_.at(s.id);
    if (all.size() < static_cast<std::size_t>(needed)) continue;
    const std::size_t first = all.size() > window ? all.size() - window : 0;
    std::vector<std::int64_t> offsets;
    for (std::size_t i = first; i < all.size(); ++i) offsets.push_back(all[i].frame - frame_to);
    auto it = weights_.find(offsets);
    if (it == weights_.end()) {
      const std::vector<double> times(offsets.begin(), offsets.end());
      it =
          weights_
              .emplace(offsets,
                       std::pair{polynomial_fit_weights(times, smoothing_.degree,
                                                        static_cast<double>(frame_from - frame_to)),
                                 polynomial_fit_weights(times, smoothing_.degree, 0)})
              .first;
    }
    const auto& [at_from, at_to] = it->second;
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      const Position& p = all[first + i];
      x0 += at_from[i] * p.x_px;
      y0 += at_from[i] * p.y_px;
      x1 += at_to[i] * p.x_px;
      y1 += at_to[i] * p.y_px;
    }
    // Measured positions stay in the history; only the step handed out is smoothed.
    s.x_px = {x0, x1};
    s.y_px = {y0, y1};
  }
}

}  // namespace tactile::capture
