#include "tactile/capture/track.hpp"
#include "tactile/capture/causal_smoothing.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

#include "tracking/assignment.hpp"
#include "tracking/track_gradient.hpp"

namespace tactile::capture {

namespace {

struct Active {
  std::size_t track;  // index into `all`
  PointMm last_mm;
  PointMm velocity_mm;  // per frame
  int last_frame;
  double orientation;
  bool has_velocity;
};

struct Candidate {
  double confidence;
  std::size_t active;
  std::size_t feature;
};

// Least-squares quadratic through the positions within +-h frames, evaluated at the centre; it
// keeps constant-acceleration motion unbiased while averaging localisation noise. The value is a
// fixed weighted sum of the positions, whose weights depend only on the window's place in the
// track, so they are computed once per track length and shared by every track of that length.
class QuadraticSmoother {
 public:
  QuadraticSmoother(int h, SmoothingKernel kernel) : h_(h), kernel_(kernel) {
    if (h <= 0) return;
    // Inside the track the window is symmetric; with equal weights these are Savitzky-Golay's.
    inside_ = fit_weights(-h, h);
  }

  std::vector<double> operator()(const std::vector<double>& v) {
    if (h_ <= 0 || v.size() < 3) return v;
    const int n = static_cast<int>(v.size());
    const auto& ends = end_weights(n);
    std::vector<double> out(v.size());
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(0, i - h_), hi = std::min(n - 1, i + h_);
      const bool inside = hi - lo == 2 * h_;
      const double* w = inside ? inside_.data() : ends[static_cast<std::size_t>(i)].data();
      double sum = 0;
      for (int k = lo; k <= hi; ++k) sum += w[k - lo] * v[static_cast<std::size_t>(k)];
      out[static_cast<std::size_t>(i)] = sum;
    }
    return out;
  }

 private:
  // The fit's weight on each frame of a window of frames t = lo..hi from the frame fitted (its
  // value there from each position): row 0 of (A^T K A)^-1 A^T K for A's rows (1, t, t^2) and
  // the kernel's weights K. Fewer than 3 frames: their mean.
  std::vector<double> fit_weights(int lo, int hi) const {
    const int count = hi - lo + 1;
    if (count < 3) return std::vector<double>(static_cast<std::size_t>(count), 1.0 / count);
    Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
    for (int t = lo; t <= hi; ++t) {
      const Eigen::Vector3d a(1, t, double(t) * t);
      ata += weight(t) * a * a.transpose();
    }
    const Eigen::Vector3d row0 = ata.ldlt().solve(Eigen::Vector3d::UnitX());
    std::vector<double> w;
    for (int t = lo; t <= hi; ++t) {
      w.push_back(weight(t) * (row0[0] + row0[1] * t + row0[2] * double(t) * t));
    }
    return w;
  }

  double weight(int t) const {
    if (kernel_ == SmoothingKernel::uniform) return 1.0;
    const double u = t / (h_ + 1.0);
    return 1 - u * u;
  }

  // For a track of n positions, the weights at every position whose window the track cuts.
  const std::vector<std::vector<double>>& end_weights(int n) {
    auto [it, added] = ends_.try_emplace(n);
    if (!added) return it->second;
    it->second.resize(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(0, i - h_), hi = std::min(n - 1, i + h_);
      if (hi - lo == 2 * h_) continue;
      it->second[static_cast<std::size_t>(i)] = fit_weights(lo - i, hi - i);
    }
    return it->second;
  }

  int h_;
  SmoothingKernel kernel_;
  std::vector<double> inside_;
  std::map<int, std::vector<std::vector<double>>> ends_;
};

// Cuts a trajectory wherever a position lies more than gate_px from the least-squares line
// through the (up to) 6 positions before it in the same piece.
std::vector<Track> split_at_jumps(const Track& t, double gate_px) {
  constexpr int kWindow = 6;
  constexpr int kMinFit = 3;
  std::vector<Track> pieces;
  const int n = static_cast<int>(t.x_px.size());
  int start = 0;
  auto emit = [&](int from, int to) {
    Track piece;
    piece.type = t.type;
    piece.first_frame = t.first_frame + from;
    piece.x_px.assign(t.x_px.begin() + from, t.x_px.begin() + to);
    piece.y_px.assign(t.y_px.begin() + from, t.y_px.begin() + to);
    pieces.push_back(std::move(piece));
  };
  for (int k = 0; k < n; ++k) {
    const int m = std::min(kWindow, k - start);
    if (m < kMinFit) continue;
    // Line through samples s = 0..m-1, extrapolated to s = m.
    const double s_mean = (m - 1) / 2.0;
    double ss = 0, sx = 0, sy = 0, mx = 0, my = 0;
    for (int i = 0; i < m; ++i) {
      mx += t.x_px[static_cast<std::size_t>(k - m + i)];
      my += t.y_px[static_cast<std::size_t>(k - m + i)];
    }
    mx /= m;
    my /= m;
    for (int i = 0; i < m; ++i) {
      const double ds = i - s_mean;
      ss += ds * ds;
      sx += ds * (t.x_px[static_cast<std::size_t>(k - m + i)] - mx);
      sy += ds * (t.y_px[static_cast<std::size_t>(k - m + i)] - my);
    }
    const double px = mx + sx / ss * (m - s_mean);
    const double py = my + sy / ss * (m - s_mean);
    const auto uk = static_cast<std::size_t>(k);
    if (std::hypot(t.x_px[uk] - px, t.y_px[uk] - py) > gate_px) {
      emit(start, k);
      start = k;
    }
  }
  emit(start, n);
  return pieces;
}

}  // namespace

void smooth_tracks(std::vector<Track>& tracks, int half_window, SmoothingKernel kernel,
                   int threads) {
  // Chunks of tracks on the workers, each with a smoother of its own (it keeps the weights of
  // the lengths it has seen).
  constexpr std::size_t kChunk = 64;
  parallel_for((tracks.size() + kChunk - 1) / kChunk, worker_count(threads), [&](std::size_t c) {
    QuadraticSmoother smooth(half_window, kernel);
    for (std::size_t i = c * kChunk; i < std::min(tracks.size(), (c + 1) * kChunk); ++i) {
      Track& t = tracks[i];
      t.x_px = smooth(t.x_px);
      t.y_px = smooth(t.y_px);
      if (!has_gradients(t)) continue;
      // The deformation gradient carries the same frames' noise as the positions.
      std::vector<double> entry(t.gradient.size());
      for (std::size_t e = 0; e < 4; ++e) {
        for (std::size_t k = 0; k < entry.size(); ++k) entry[k] = t.gradient[k][e];
        entry = smooth(entry);
        for (std::size_t k = 0; k < entry.size(); ++k) t.gradient[k][e] = entry[k];
      }
    }
  });
}

namespace {

// RMS over frames of what smoothing by h removes from a series, for both coordinates.
double smoothing_residual(const std::vector<double>& dx, const std::vector<double>& dy,
                          QuadraticSmoother& smooth) {
  const auto sx = smooth(dx), sy = smooth(dy);
  double sum = 0;
  for (std::size_t k = 0; k < dx.size(); ++k) {
    sum += std::pow(sx[k] - dx[k], 2) + std::pow(sy[k] - dy[k], 2);
  }
  return std::sqrt(sum / static_cast<double>(dx.size()));
}

// The relative position of each track and its nearest neighbour over the frames both cover:
// motion common to both (slide, rotation) cancels and what remains is the strain between them
// plus the trackers' noise, which is what the smoother trades against each other.
struct NeighbourSeries {
  std::vector<double> dx, dy;
};
// Every track but at most `most` of them, evenly spread: a median over a few hundred tracks
// chooses the smoothing as well as one over all of a large frame's.
std::vector<std::size_t> spread_sample(std::size_t count, std::size_t most) {
  const std::size_t step = std::max<std::size_t>(1, (count + most - 1) / most);
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < count; i += step) out.push_back(i);
  return out;
}

std::vector<NeighbourSeries> neighbour_series(const std::vector<Track>& tracks,
                                              std::size_t min_frames, std::size_t most,
                                              int threads) {
  auto at = [](const Track& t, std::int32_t f, const std::vector<double>& v) {
    return v[static_cast<std::size_t>(f - t.first_frame)];
  };
  const std::vector<std::size_t> sample = spread_sample(tracks.size(), most);
  // Each sampled track's pair on the workers; those without one are left out afterwards.
  std::vector<NeighbourSeries> found(sample.size());
  parallel_for(sample.size(), worker_count(threads), [&](std::size_t r) {
    const std::size_t i = sample[r];
    const Track& a = tracks[i];
    if (a.x_px.size() < min_frames) return;
    double best = std::numeric_limits<double>::infinity();
    std::size_t best_j = i;
    for (std::size_t j = 0; j < tracks.size(); ++j) {
      const Track& b = tracks[j];
      const std::int32_t lo = std::max(a.first_frame, b.first_frame);
      const std::int32_t hi = std::min(a.last_frame(), b.last_frame());
      if (j == i || hi - lo + 1 < static_cast<std::int32_t>(min_frames)) continue;
      const double d = std::pow(at(a, lo, a.x_px) - at(b, lo, b.x_px), 2) +
                       std::pow(at(a, lo, a.y_px) - at(b, lo, b.y_px), 2);
      if (d < best) {
        best = d;
        best_j = j;
      }
    }
    if (best_j == i) return;
    const Track& b = tracks[best_j];
    NeighbourSeries& s = found[r];
    for (std::int32_t f = std::max(a.first_frame, b.first_frame);
         f <= std::min(a.last_frame(), b.last_frame()); ++f) {
      s.dx.push_back(at(a, f, a.x_px) - at(b, f, b.x_px));
      s.dy.push_back(at(a, f, a.y_px) - at(b, f, b.y_px));
    }
  });
  std::vector<NeighbourSeries> out;
  for (auto& s : found) {
    if (!s.dx.empty()) out.push_back(std::move(s));
  }
  return out;
}

// For the smoother on n samples (S) and the frame-to-frame difference (D), the squared Frobenius
// norms of I - S, of D (I - S) and of D S: how much white noise of unit variance the smoother
// removes, and what of it the frame-to-frame changes of the removed and of the kept part hold.
struct SmootherNoise {
  double removed = 0, removed_change = 0, kept_change = 0;
};
SmootherNoise smoother_noise(QuadraticSmoother& smooth, int n) {
  SmootherNoise out;
  std::vector<double> unit(static_cast<std::size_t>(n), 0.0);
  for (int j = 0; j < n; ++j) {
    unit[static_cast<std::size_t>(j)] = 1;
    const auto column = smooth(unit);
    for (int i = 0; i < n; ++i) {
      const double removed = (i == j ? 1.0 : 0.0) - column[static_cast<std::size_t>(i)];
      out.removed += removed * removed;
      if (i == 0) continue;
      const double kept_change =
          column[static_cast<std::size_t>(i)] - column[static_cast<std::size_t>(i - 1)];
      const double change = (i == j ? 1.0 : 0.0) - (i - 1 == j ? 1.0 : 0.0);
      out.kept_change += kept_change * kept_change;
      out.removed_change += (change - kept_change) * (change - kept_change);
    }
    unit[static_cast<std::size_t>(j)] = 0;
  }
  return out;
}

double trimmed_mean(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t cut = v.size() / 10;
  double sum = 0;
  for (std::size_t k = cut; k < v.size() - cut; ++k) sum += v[k];
  return sum / static_cast<double>(v.size() - 2 * cut);
}

// Sum over both coordinates of the squared removed part and of its frame-to-frame changes.
struct Removed {
  double sum_sq = 0, change_sq = 0;
};
Removed removed_by(const NeighbourSeries& s, QuadraticSmoother& smooth) {
  Removed r;
  for (const auto* v : {&s.dx, &s.dy}) {
    const auto kept = smooth(*v);
    double previous = 0;
    for (std::size_t k = 0; k < v->size(); ++k) {
      const double removed = (*v)[k] - kept[k];
      r.sum_sq += removed * removed;
      if (k > 0) r.change_sq += (removed - previous) * (removed - previous);
      previous = removed;
    }
  }
  return r;
}

// The noise variance of each neighbour pair's relative position (per coordinate and frame),
// taken noise_scale times over: what the half-window 2 smoother, which bends only the fastest
// motions, removes from the pair, against what it removes from white noise of unit variance.
constexpr int kNoiseWindow = 2;
constexpr std::size_t kMinSeries = 20, kMaxSeries = 400;  // pairs needed, pairs used at most
std::vector<double> pair_noise_variance(const std::vector<NeighbourSeries>& series,
                                        SmoothingKernel kernel, double noise_scale) {
  QuadraticSmoother noise_smoother(kNoiseWindow, kernel);
  std::map<int, SmootherNoise> noise_norms;
  std::vector<double> noise_variance;
  for (const auto& s : series) {
    const int n = static_cast<int>(s.dx.size());
    auto it = noise_norms.find(n);
    if (it == noise_norms.end())
      it = noise_norms.emplace(n, smoother_noise(noise_smoother, n)).first;
    noise_variance.push_back(noise_scale * removed_by(s, noise_smoother).sum_sq /
                             (2 * it->second.removed));
  }
  return noise_variance;
}

}  // namespace

int smoothing_that_fits(const std::vector<Track>& tracks, int half_window, double max_residual_px,
                        SmoothingKernel kernel, int threads, double noise_scale) {
  if (!(noise_scale > 0)) throw std::invalid_argument("noise_scale must be > 0");
  if (half_window <= 0) return half_window;
  std::vector<int> candidates;
  for (int h : {half_window, 14, 12, 10, 8, 7, 6, 5, 4, 3}) {
    if (h <= half_window && (candidates.empty() || h < candidates.back())) candidates.push_back(h);
  }
  // Between a track and its nearest neighbour the common motion cancels, and what is left is
  // the strain between them plus the trackers' noise. For each window the expected squared
  // error of the smoothed frame-to-frame changes (what the strain is made of) is estimated
  // without the truth (Stein's unbiased risk estimate): the changes of what the window removes,
  // less the noise's share of them, plus the noise that the kept changes still carry. The noise
  // is measured by the half-window 2 smoother, which bends only the fastest motions. The window
  // with the least estimated error is taken, 0 (no smoothing) included. The estimate is of the
  // mean error over all pairs, so pairs are averaged (a tenth at each end left out, for the few
  // whose tracks slipped), not their median taken: each pair's estimate is skewed.
  constexpr std::size_t kMaxFrames = 256;  // enough frames of each series to choose by
  auto series = neighbour_series(tracks, static_cast<std::size_t>(2 * (kNoiseWindow + 1) + 1),
                                 kMaxSeries, threads);
  if (series.size() < kMinSeries) return 0;
  for (auto& s : series) {
    if (s.dx.size() > kMaxFrames) {
      s.dx.resize(kMaxFrames);
      s.dy.resize(kMaxFrames);
    }
  }
  const std::vector<double> noise_variance = pair_noise_variance(series, kernel, noise_scale);
  // No smoothing: every change carries the noise of two frames.
  std::vector<double> error;
  for (std::size_t k = 0; k < series.size(); ++k) {
    error.push_back(noise_variance[k] * 2 * 2);  // per change
  }
  int best = 0;
  double best_error = trimmed_mean(error);
  // Each window's estimate on the workers (NaN: the window moves the tracks too far), then the
  // least of them in the order of the windows.
  const std::vector<std::size_t> sample = spread_sample(tracks.size(), kMaxSeries);
  std::vector<double> estimate(candidates.size(), std::numeric_limits<double>::quiet_NaN());
  parallel_for(candidates.size(), worker_count(threads), [&](std::size_t c) {
    const int h = candidates[c];
    QuadraticSmoother smoother(h, kernel);
    // A window may not move a whole track by more than max_residual_px (RMS, median track).
    std::vector<double> residuals;
    for (const std::size_t i : sample) {
      const Track& t = tracks[i];
      if (static_cast<int>(t.x_px.size()) < 2 * h + 1) continue;
      residuals.push_back(smoothing_residual(t.x_px, t.y_px, smoother));
    }
    if (residuals.empty() || median(residuals) > max_residual_px) return;
    std::map<int, SmootherNoise> norms;
    std::vector<double> window_error(series.size());
    for (std::size_t k = 0; k < series.size(); ++k) {
      const int n = static_cast<int>(series[k].dx.size());
      auto it = norms.find(n);
      if (it == norms.end()) it = norms.emplace(n, smoother_noise(smoother, n)).first;
      const Removed r = removed_by(series[k], smoother);
      window_error[k] = (r.change_sq + 2 * noise_variance[k] *
                                           (it->second.kept_change - it->second.removed_change)) /
                        static_cast<double>(n - 1);
    }
    estimate[c] = trimmed_mean(std::move(window_error));
  });
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    if (estimate[c] < best_error) {
      best_error = estimate[c];
      best = candidates[c];
    }
  }
  return best;
}

namespace {

// The weights that give the step into the last of `window` equally spaced positions, f(0) -
// f(-1) (or with `step` false the last position, f(0)), of the least-squares polynomial of
// `degree` through them (oldest first).
std::vector<double> causal_weights(int window, int degree, bool step) {
  std::vector<double> times;
  for (int i = 0; i < window; ++i) times.push_back(i - (window - 1));
  std::vector<double> w = polynomial_fit_weights(times, degree, 0);
  if (step) {
    const std::vector<double> before = polynomial_fit_weights(times, degree, -1);
    for (std::size_t i = 0; i < w.size(); ++i) w[i] -= before[i];
  }
  return w;
}

}  // namespace

int causal_smoothing_that_fits(const std::vector<Track>& tracks, int degree, double max_residual_px,
                               int threads, double noise_scale) {
  if (degree < 1 || degree > 2) throw std::invalid_argument("degree must be 1 or 2");
  if (!(noise_scale > 0)) throw std::invalid_argument("noise_scale must be > 0");
  // As smoothing_that_fits: pairs of neighbouring tracks, the noise of each pair's relative
  // position measured by the centred half-window 2 smoother. For a causal window with step
  // weights w (w0 on the last position, w1 on the one before), Stein's estimate of the squared
  // error of a smoothed change, per coordinate, is the mean square of what the smoothing changes
  // in the raw change plus 2 sigma^2 (w0 - w1 - 1); the raw change's is 2 sigma^2.
  const auto series = neighbour_series(tracks, kCausalChoiceFrames, kMaxSeries, threads);
  if (series.size() < kMinSeries) return 0;
  const std::vector<double> noise_variance =
      pair_noise_variance(series, RefineParams{}.smoothing_kernel, noise_scale);
  std::vector<double> raw;
  for (const double v : noise_variance) raw.push_back(2 * 2 * v);  // both coordinates
  int best = 0;
  double best_error = trimmed_mean(raw);
  const std::vector<std::size_t> sample = spread_sample(tracks.size(), kMaxSeries);
  for (const int window : kCausalWindows) {
    const std::vector<double> w = causal_weights(window, degree, true);
    const double w0 = w.back(), w1 = w[w.size() - 2];
    const auto n_w = static_cast<std::size_t>(window);
    const std::vector<double> last = causal_weights(window, degree, false);
    std::vector<double> residuals;
    for (const std::size_t i : sample) {
      const Track& t = tracks[i];
      if (t.x_px.size() < n_w) continue;
      double sum = 0;
      for (const auto* v : {&t.x_px, &t.y_px}) {
        for (std::size_t e = n_w - 1; e < v->size(); ++e) {
          double fitted = 0;
          for (std::size_t j = 0; j < n_w; ++j) fitted += last[j] * (*v)[e + 1 - n_w + j];
          sum += (fitted - (*v)[e]) * (fitted - (*v)[e]);
        }
      }
      residuals.push_back(std::sqrt(sum / static_cast<double>(t.x_px.size() + 1 - n_w)));
    }
    if (residuals.empty() || median(residuals) > max_residual_px) continue;
    std::vector<double> error;
    for (std::size_t k = 0; k < series.size(); ++k) {
      double sum = 0;
      std::size_t count = 0;
      for (const auto* v : {&series[k].dx, &series[k].dy}) {
        for (std::size_t t = n_w - 1; t < v->size(); ++t) {
          double smoothed = 0;
          for (std::size_t i = 0; i < n_w; ++i) smoothed += w[i] * (*v)[t + 1 - n_w + i];
          const double change = (*v)[t] - (*v)[t - 1];
          sum += (smoothed - change) * (smoothed - change);
          ++count;
        }
      }
      // count covers both coordinates: per change, twice the mean of one.
      error.push_back(2 * sum / static_cast<double>(count) +
                      2 * 2 * noise_variance[k] * (w0 - w1 - 1));
    }
    const double estimate = trimmed_mean(std::move(error));
    if (estimate < best_error) {
      best_error = estimate;
      best = window;
    }
  }
  return best;
}

std::vector<Track> track_features(const std::vector<std::vector<Feature>>& features_per_frame,
                                  const Calibration& calibration, const TrackParams& params) {
  if (!(params.match_radius_mm > 0)) throw std::invalid_argument("match_radius_mm must be > 0");
  if (params.min_track_frames < 2) throw std::invalid_argument("min_track_frames must be >= 2");
  if (params.max_gap_frames < 0) throw std::invalid_argument("max_gap_frames must be >= 0");
  if (!(params.max_jump_mm > 0)) throw std::invalid_argument("max_jump_mm must be > 0");
  if (!(calibration.mm_per_px > 0))
    throw std::invalid_argument("calibration mm_per_px must be > 0");

  std::vector<Track> all;
  std::vector<Active> active;
  PointMm global_velocity{0, 0};  // median motion of the last matched frame: seeds new tracks
  const double radius = params.match_radius_mm;

  auto start_track = [&](const Feature& f, int frame) {
    Track t;
    t.type = f.type;
    t.first_frame = frame;
    t.x_px.push_back(f.x_px);
    t.y_px.push_back(f.y_px);
    all.push_back(std::move(t));
    active.push_back({all.size() - 1,
                      to_mm(calibration, f.x_px, f.y_px),
                      {0, 0},
                      frame,
                      f.orientation_rad,
                      false});
  };

  for (int frame = 0; frame < static_cast<int>(features_per_frame.size()); ++frame) {
    const auto& feats = features_per_frame[static_cast<std::size_t>(frame)];
    std::vector<PointMm> feat_mm;
    feat_mm.reserve(feats.size());
    for (const auto& f : feats) feat_mm.push_back(to_mm(calibration, f.x_px, f.y_px));

    // Features bucketed on a grid of radius-sized cells: a prediction's candidates lie in the
    // 3 x 3 cells around it.
    double min_x = 0, min_y = 0;
    int grid_w = 0, grid_h = 0;
    if (!feats.empty()) {
      min_x = feat_mm[0].x_mm;
      min_y = feat_mm[0].y_mm;
      double max_x = min_x, max_y = min_y;
      for (const auto& p : feat_mm) {
        min_x = std::min(min_x, p.x_mm);
        min_y = std::min(min_y, p.y_mm);
        max_x = std::max(max_x, p.x_mm);
        max_y = std::max(max_y, p.y_mm);
      }
      grid_w = static_cast<int>((max_x - min_x) / radius) + 1;
      grid_h = static_cast<int>((max_y - min_y) / radius) + 1;
    }
    std::vector<int> cell_head(static_cast<std::size_t>(grid_w) * grid_h, -1);
    std::vector<int> next_in_cell(feats.size(), -1);
    for (std::size_t k = 0; k < feats.size(); ++k) {
      const int cx = static_cast<int>((feat_mm[k].x_mm - min_x) / radius);
      const int cy = static_cast<int>((feat_mm[k].y_mm - min_y) / radius);
      auto& head = cell_head[static_cast<std::size_t>(cy) * grid_w + cx];
      next_in_cell[k] = head;
      head = static_cast<int>(k);
    }

    std::vector<Candidate> candidates;
    for (std::size_t a = 0; a < active.size() && !feats.empty(); ++a) {
      const Active& act = active[a];
      const Track& t = all[act.track];
      const int steps = frame - act.last_frame;
      const PointMm v = act.has_velocity ? act.velocity_mm : global_velocity;
      const PointMm pred{act.last_mm.x_mm + v.x_mm * steps, act.last_mm.y_mm + v.y_mm * steps};
      const double gx = std::floor((pred.x_mm - min_x) / radius);
      const double gy = std::floor((pred.y_mm - min_y) / radius);
      if (gx < -1 || gy < -1 || gx > grid_w || gy > grid_h) continue;
      for (int cy = std::max(0, static_cast<int>(gy) - 1);
           cy <= std::min(grid_h - 1, static_cast<int>(gy) + 1); ++cy) {
        for (int cx = std::max(0, static_cast<int>(gx) - 1);
             cx <= std::min(grid_w - 1, static_cast<int>(gx) + 1); ++cx) {
          for (int k = cell_head[static_cast<std::size_t>(cy) * grid_w + cx]; k >= 0;
               k = next_in_cell[static_cast<std::size_t>(k)]) {
            const auto uk = static_cast<std::size_t>(k);
            if (feats[uk].type != t.type) continue;
            const double d = std::hypot(feat_mm[uk].x_mm - pred.x_mm, feat_mm[uk].y_mm - pred.y_mm);
            if (d >= radius) continue;
            double confidence = 1 - d / radius;
            if (t.type == FeatureType::ending) {
              confidence *= 0.5 * (1 + std::cos(feats[uk].orientation_rad - act.orientation));
            }
            if (confidence > 0) candidates.push_back({confidence, a, uk});
          }
        }
      }
    }
    std::vector<ScoredPair> scored;
    scored.reserve(candidates.size());
    for (const auto& c : candidates) scored.push_back({c.confidence, c.active, c.feature});
    const std::vector<ScoredPair> chosen = params.assignment == Assignment::optimal
                                               ? assign_optimal(scored)
                                               : assign_greedy(std::move(scored));
    std::vector<char> feature_used(feats.size(), 0);
    std::vector<double> vx, vy;
    for (const auto& pick : chosen) {
      const Candidate c{pick.score, pick.left, pick.right};
      feature_used[c.feature] = 1;
      Active& act = active[c.active];
      Track& t = all[act.track];
      const int steps = frame - act.last_frame;
      const Feature& f = feats[c.feature];
      // Missed frames in between: linear interpolation.
      const double x0 = t.x_px.back();
      const double y0 = t.y_px.back();
      for (int s = 1; s < steps; ++s) {
        t.x_px.push_back(x0 + (f.x_px - x0) * s / steps);
        t.y_px.push_back(y0 + (f.y_px - y0) * s / steps);
      }
      t.x_px.push_back(f.x_px);
      t.y_px.push_back(f.y_px);
      const PointMm now = feat_mm[c.feature];
      act.velocity_mm = {(now.x_mm - act.last_mm.x_mm) / steps,
                         (now.y_mm - act.last_mm.y_mm) / steps};
      act.has_velocity = true;
      act.last_mm = now;
      act.last_frame = frame;
      act.orientation = f.orientation_rad;
      vx.push_back(act.velocity_mm.x_mm);
      vy.push_back(act.velocity_mm.y_mm);
    }
    if (!vx.empty()) {
      global_velocity = {median(vx), median(vy)};
    }
    // Retire tracks missed for too long, then start tracks for unmatched features.
    std::vector<Active> kept;
    for (std::size_t a = 0; a < active.size(); ++a) {
      if (frame - active[a].last_frame <= params.max_gap_frames) kept.push_back(active[a]);
    }
    active = std::move(kept);
    for (std::size_t k = 0; k < feats.size(); ++k) {
      if (!feature_used[k]) start_track(feats[k], frame);
    }
  }

  std::vector<Track> result;
  const double gate_px = params.max_jump_mm / calibration.mm_per_px;
  for (const auto& whole : all) {
    if (static_cast<int>(whole.x_px.size()) < params.min_track_frames) continue;
    for (auto& t : split_at_jumps(whole, gate_px)) {
      if (static_cast<int>(t.x_px.size()) < params.min_track_frames) continue;
      result.push_back(std::move(t));
    }
  }
  smooth_tracks(result, params.smoothing_half_window);
  std::stable_sort(result.begin(), result.end(),
                   [](const Track& a, const Track& b) { return a.first_frame < b.first_frame; });
  for (std::size_t i = 0; i < result.size(); ++i) result[i].id = static_cast<std::int32_t>(i);
  return result;
}

}  // namespace tactile::capture
