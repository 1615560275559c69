// Smoothing of each frame's steps across the skin; see neighbour_smoothing.hpp.

#include "tactile/capture/neighbour_smoothing.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

namespace tactile::capture {

namespace {

constexpr double kReachSigmas = 2.5;

void check_steps(const std::vector<Track>& steps) {
  for (const auto& s : steps) {
    if (s.x_px.size() != 2 || s.y_px.size() != 2) {
      throw std::invalid_argument(fmt::format(
          "neighbour smoothing: track {} has {} positions, not a step's two", s.id, s.x_px.size()));
    }
  }
}

Eigen::Vector2d displacement(const Track& s) {
  return {s.x_px[1] - s.x_px[0], s.y_px[1] - s.y_px[0]};
}

// The steps' first positions and displacements side by side, and the steps by square cells of
// a side, so that those within that distance of a point are in its cell and the eight around
// it (a dense grid over the positions' extent, its cells' members held one after another).
class StepGrid {
 public:
  StepGrid(const std::vector<Track>& steps, double cell_px) : cell_px_(cell_px) {
    const std::size_t n = steps.size();
    x_.resize(n);
    y_.resize(n);
    d_.resize(n);
    double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
    for (std::size_t i = 0; i < n; ++i) {
      x_[i] = steps[i].x_px[0];
      y_[i] = steps[i].y_px[0];
      d_[i] = displacement(steps[i]);
      if (!std::isfinite(x_[i]) || !std::isfinite(y_[i])) {
        throw std::invalid_argument(
            fmt::format("neighbour smoothing: track {} is at no finite position", steps[i].id));
      }
      min_x = i == 0 ? x_[i] : std::min(min_x, x_[i]);
      min_y = i == 0 ? y_[i] : std::min(min_y, y_[i]);
      max_x = i == 0 ? x_[i] : std::max(max_x, x_[i]);
      max_y = i == 0 ? y_[i] : std::max(max_y, y_[i]);
    }
    x0_ = min_x;
    y0_ = min_y;
    // A view is at most a few thousand pixels a side and a cell a few pixels: a grid larger
    // than the steps many times over would say the positions are far outside any view (the
    // cells counted in double precision first, as a span of any size can be).
    const double cols = (max_x - min_x) / cell_px + 1, rows = (max_y - min_y) / cell_px + 1;
    if (cols * rows > static_cast<double>(64 * n + 1024)) {
      throw std::invalid_argument(fmt::format(
          "neighbour smoothing: the steps span {:.0f} x {:.0f} px, far beyond a camera's view",
          max_x - min_x, max_y - min_y));
    }
    cols_ = static_cast<long>(cols);
    rows_ = static_cast<long>(rows);
    std::vector<long> cell_of(n);
    first_.assign(static_cast<std::size_t>(cols_ * rows_ + 1), 0);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of[i] = cell(x_[i], y_[i]);
      ++first_[static_cast<std::size_t>(cell_of[i]) + 1];
    }
    for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
    members_.resize(n);
    std::vector<std::size_t> filled(first_.begin(), first_.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      members_[filled[static_cast<std::size_t>(cell_of[i])]++] = i;
  }

  template <typename Visit>
  void near(double x_px, double y_px, Visit&& visit) const {
    const long cx = static_cast<long>(std::floor((x_px - x0_) / cell_px_));
    const long cy = static_cast<long>(std::floor((y_px - y0_) / cell_px_));
    for (long gy = std::max(0L, cy - 1); gy <= std::min(rows_ - 1, cy + 1); ++gy) {
      for (long gx = std::max(0L, cx - 1); gx <= std::min(cols_ - 1, cx + 1); ++gx) {
        const auto c = static_cast<std::size_t>(gy * cols_ + gx);
        for (std::size_t k = first_[c]; k < first_[c + 1]; ++k) visit(members_[k]);
      }
    }
  }

  double x(std::size_t i) const { return x_[i]; }
  double y(std::size_t i) const { return y_[i]; }
  const Eigen::Vector2d& d(std::size_t i) const { return d_[i]; }

 private:
  long cell(double x_px, double y_px) const {
    return static_cast<long>((y_px - y0_) / cell_px_) * cols_ +
           static_cast<long>((x_px - x0_) / cell_px_);
  }

  double cell_px_, x0_ = 0, y0_ = 0;
  long cols_ = 0, rows_ = 0;
  std::vector<double> x_, y_;
  std::vector<Eigen::Vector2d> d_;
  std::vector<std::size_t> first_, members_;
};

// A step near the one fitted: its first position's offset from that one's and its displacement.
struct Near {
  double dx_px, dy_px;
  Eigen::Vector2d displacement;
};

// The steps within reach_px of step i's first position, without i itself and those within
// exclude_px of it where `without_own`; nearest first where `nearest_first`.
void near_steps(const StepGrid& grid, std::size_t i, double reach_px, bool without_own,
                double exclude_px, bool nearest_first, std::vector<Near>& out) {
  out.clear();
  const double x0 = grid.x(i), y0 = grid.y(i);
  grid.near(x0, y0, [&](std::size_t j) {
    if (without_own && j == i) return;
    const double dx = grid.x(j) - x0, dy = grid.y(j) - y0;
    const double r2 = dx * dx + dy * dy;
    if (r2 > reach_px * reach_px || (without_own && r2 < exclude_px * exclude_px)) return;
    out.push_back({dx, dy, grid.d(j)});
  });
  // A fit of a shorter reach then stops at the first beyond it.
  if (nearest_first) {
    std::sort(out.begin(), out.end(), [](const Near& a, const Near& b) {
      return a.dx_px * a.dx_px + a.dy_px * a.dy_px < b.dx_px * b.dx_px + b.dy_px * b.dy_px;
    });
  }
}

// The Gaussian-weighted quadratic of the near steps' displacements, read at the centre; none
// where fewer than min_neighbours are within 2.5 sigma or they lie along a line.
std::optional<Eigen::Vector2d> fit_of(const std::vector<Near>& near, bool nearest_first,
                                      double sigma_px, int min_neighbours) {
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  // The normal equations of the terms 1, u, v, u^2, uv, v^2 hold the weighted moments of u and v
  // up to the fourth order, fifteen in all (m[a][b] = sum of w u^a v^b), and the right-hand
  // side the weighted moments of the displacements up to the second: summed as such, each
  // neighbour costs a few dozen multiply-adds.
  double m[5][5] = {};
  double dx[3][3] = {}, dy[3][3] = {};
  int count = 0;
  for (const Near& n : near) {
    // Offsets in sigmas keep the moments of one size.
    const double u = n.dx_px / sigma_px, v = n.dy_px / sigma_px;
    const double r2 = u * u + v * v;
    if (r2 > kReachSigmas * kReachSigmas) {
      if (nearest_first) break;  // the rest are further
      continue;
    }
    const double w = std::exp(-0.5 * r2);
    double wu[5];
    wu[0] = w;
    for (int a = 1; a < 5; ++a) wu[a] = wu[a - 1] * u;
    for (int a = 0; a < 5; ++a) {
      double term = wu[a];
      for (int b = 0; a + b < 5; ++b, term *= v) m[a][b] += term;
    }
    for (int a = 0; a < 3; ++a) {
      double term = wu[a];
      for (int b = 0; a + b < 3; ++b, term *= v) {
        dx[a][b] += term * n.displacement.x();
        dy[a][b] += term * n.displacement.y();
      }
    }
    ++count;
  }
  if (count < min_neighbours) return std::nullopt;
  // Term k as powers (a, b) of (u, v).
  constexpr int kPowers[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
  Matrix6 normal;
  Eigen::Matrix<double, 6, 2> rhs;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      normal(r, c) = m[kPowers[r][0] + kPowers[c][0]][kPowers[r][1] + kPowers[c][1]];
    }
    rhs(r, 0) = dx[kPowers[r][0]][kPowers[r][1]];
    rhs(r, 1) = dy[kPowers[r][0]][kPowers[r][1]];
  }
  const Eigen::LDLT<Matrix6> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::Matrix<double, 6, 1> d = ldlt.vectorD();
  if (!(d.minCoeff() > 1e-6 * d.maxCoeff())) return std::nullopt;
  const Eigen::Matrix<double, 6, 2> coefficients = ldlt.solve(rhs);
  if (!coefficients.allFinite()) return std::nullopt;
  return Eigen::Vector2d(coefficients.row(0).transpose());
}

}  // namespace

void check_neighbour_smoothing(const NeighbourSmoothing& s) {
  if (s.sigma_mm != NeighbourSmoothing::kChosenSigma && s.sigma_mm != 0 &&
      !(s.sigma_mm >= 0.1 && s.sigma_mm <= 5)) {
    throw std::invalid_argument(
        fmt::format("neighbour smoothing: sigma {} mm is out of range: must be 0 (none) or from "
                    "0.1 to 5 mm",
                    s.sigma_mm));
  }
  if (s.min_neighbours < 6 || s.min_neighbours > 1000) {
    throw std::invalid_argument(
        fmt::format("neighbour smoothing: {} neighbours is out of range: must be from 6 to 1000",
                    s.min_neighbours));
  }
  if (s.choose_every_frames < 1 || s.choose_every_frames > 10000) {
    throw std::invalid_argument(
        fmt::format("neighbour smoothing choice: every {} frames is out of range: must be from 1 "
                    "to 10000",
                    s.choose_every_frames));
  }
}

void smooth_steps_across_neighbours(std::vector<Track>& steps, double px_per_mm, double sigma_mm,
                                    int min_neighbours) {
  check_neighbour_smoothing({.sigma_mm = sigma_mm, .min_neighbours = min_neighbours});
  if (!(px_per_mm > 0)) throw std::invalid_argument("neighbour smoothing: px_per_mm must be > 0");
  check_steps(steps);
  if (sigma_mm == 0 || steps.empty()) return;
  const double sigma_px = sigma_mm * px_per_mm;
  const StepGrid grid(steps, kReachSigmas * sigma_px);
  std::vector<Eigen::Vector2d> smoothed(steps.size());
  std::vector<Near> near;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    near_steps(grid, i, kReachSigmas * sigma_px, false, 0, false, near);
    smoothed[i] = fit_of(near, false, sigma_px, min_neighbours).value_or(grid.d(i));
  }
  for (std::size_t i = 0; i < steps.size(); ++i) {
    steps[i].x_px[1] = steps[i].x_px[0] + smoothed[i].x();
    steps[i].y_px[1] = steps[i].y_px[0] + smoothed[i].y();
  }
}

NeighbourStepSmoother::NeighbourStepSmoother(const NeighbourSmoothing& smoothing, double px_per_mm)
    : smoothing_(smoothing), px_per_mm_(px_per_mm) {
  check_neighbour_smoothing(smoothing_);
  if (!(px_per_mm > 0)) throw std::invalid_argument("neighbour smoothing: px_per_mm must be > 0");
  if (smoothing_.sigma_mm != NeighbourSmoothing::kChosenSigma) sigma_mm_ = smoothing_.sigma_mm;
}

void NeighbourStepSmoother::smooth(std::vector<Track>& steps) {
  check_steps(steps);
  if (smoothing_.sigma_mm == NeighbourSmoothing::kChosenSigma && !steps.empty()) {
    // Each sampled track's measured step against every candidate's fit without it, counted only
    // where every candidate has a fit, so that the candidates are scored on the same tracks.
    const double widest_px = kReachSigmas * kNeighbourSigmaCandidatesMm.back() * px_per_mm_;
    const StepGrid grid(steps, widest_px);
    const std::size_t every =
        std::max<std::size_t>(1, steps.size() / NeighbourSmoothing::kChoiceSampleTracks);
    std::vector<Near> near;
    for (std::size_t i = every / 2; i < steps.size(); i += every) {
      near_steps(grid, i, widest_px, true, NeighbourSmoothing::kChoiceExcludeMm * px_per_mm_, true,
                 near);
      std::array<double, kNeighbourSigmaCandidatesMm.size()> squared{};
      bool all = true;
      for (std::size_t c = 0; c < kNeighbourSigmaCandidatesMm.size() && all; ++c) {
        const auto fit = fit_of(near, true, kNeighbourSigmaCandidatesMm[c] * px_per_mm_,
                                smoothing_.min_neighbours);
        all = fit.has_value();
        if (all) squared[c] = (grid.d(i) - *fit).squaredNorm();
      }
      if (!all) continue;
      for (std::size_t c = 0; c < squared.size(); ++c) squared_residuals_[c] += squared[c];
      ++residuals_;
    }
    ++frames_;
    ++frames_since_choice_;
    const bool due = choices_ == 0 ? frames_ >= NeighbourSmoothing::kFirstChoiceFrames
                                   : frames_since_choice_ >= smoothing_.choose_every_frames;
    // A few dozen tracks' residuals at least, or the choice would follow their noise.
    if (due && residuals_ >= 50) {
      const auto best = std::min_element(squared_residuals_.begin(), squared_residuals_.end());
      sigma_mm_ =
          kNeighbourSigmaCandidatesMm[static_cast<std::size_t>(best - squared_residuals_.begin())];
      min_chosen_mm_ = choices_ == 0 ? sigma_mm_ : std::min(min_chosen_mm_, sigma_mm_);
      max_chosen_mm_ = std::max(max_chosen_mm_, sigma_mm_);
      ++choices_;
      frames_since_choice_ = 0;
      squared_residuals_.fill(0);
      residuals_ = 0;
    }
  }
  smooth_steps_across_neighbours(steps, px_per_mm_, sigma_mm_, smoothing_.min_neighbours);
}

}  // namespace tactile::capture
