// Smoothing of each frame's steps across the skin; see neighbour_smoothing.hpp.

#include "tactile/capture/neighbour_smoothing.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <unordered_map>

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

// The steps by square cells of a side, so that those within that distance of a point are in
// its cell and the eight around it.
class StepGrid {
 public:
  StepGrid(const std::vector<Track>& steps, double cell_px) : steps_(steps), cell_px_(cell_px) {
    for (std::size_t i = 0; i < steps.size(); ++i) {
      cells_[key(cell(steps[i].x_px[0]), cell(steps[i].y_px[0]))].push_back(i);
    }
  }

  template <typename Visit>
  void near(double x_px, double y_px, Visit&& visit) const {
    const long long cx = cell(x_px), cy = cell(y_px);
    for (long long gx = cx - 1; gx <= cx + 1; ++gx) {
      for (long long gy = cy - 1; gy <= cy + 1; ++gy) {
        const auto found = cells_.find(key(gx, gy));
        if (found == cells_.end()) continue;
        for (const std::size_t j : found->second) visit(j);
      }
    }
  }

 private:
  long long cell(double v) const { return static_cast<long long>(std::floor(v / cell_px_)); }
  static long long key(long long cx, long long cy) { return (cx << 32) ^ (cy & 0xffffffffLL); }

  const std::vector<Track>& steps_;
  double cell_px_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

Eigen::Vector2d displacement(const Track& s) {
  return {s.x_px[1] - s.x_px[0], s.y_px[1] - s.y_px[0]};
}

// The quadratic of the displacements of the steps near step i, read at i's first position;
// none where too few or along a line. `without_own`: without i itself and the steps within
// exclude_px of it.
std::optional<Eigen::Vector2d> fit_at(const std::vector<Track>& steps, const StepGrid& grid,
                                      std::size_t i, double sigma_px, int min_neighbours,
                                      bool without_own, double exclude_px = 0) {
  using Vector6 = Eigen::Matrix<double, 6, 1>;
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  const double x0 = steps[i].x_px[0], y0 = steps[i].y_px[0];
  Matrix6 normal = Matrix6::Zero();
  Eigen::Matrix<double, 6, 2> rhs = Eigen::Matrix<double, 6, 2>::Zero();
  int count = 0;
  grid.near(x0, y0, [&](std::size_t j) {
    if (without_own && j == i) return;
    // Offsets in sigmas keep the normal equations' entries of one size.
    const double u = (steps[j].x_px[0] - x0) / sigma_px, v = (steps[j].y_px[0] - y0) / sigma_px;
    const double r2 = u * u + v * v;
    if (without_own && r2 * sigma_px * sigma_px < exclude_px * exclude_px) return;
    if (r2 > kReachSigmas * kReachSigmas) return;
    const double w = std::exp(-0.5 * r2);
    Vector6 row;
    row << 1, u, v, u * u, u * v, v * v;
    normal.noalias() += w * row * row.transpose();
    rhs.noalias() += w * row * displacement(steps[j]).transpose();
    ++count;
  });
  if (count < min_neighbours) return std::nullopt;
  const Eigen::LDLT<Matrix6> ldlt(normal);
  if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return std::nullopt;
  const Eigen::VectorXd d = ldlt.vectorD();
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
  for (std::size_t i = 0; i < steps.size(); ++i) {
    smoothed[i] =
        fit_at(steps, grid, i, sigma_px, min_neighbours, false).value_or(displacement(steps[i]));
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
    const double widest_px = kNeighbourSigmaCandidatesMm.back() * px_per_mm_;
    const StepGrid grid(steps, kReachSigmas * widest_px);
    const std::size_t every =
        std::max<std::size_t>(1, steps.size() / NeighbourSmoothing::kChoiceSampleTracks);
    for (std::size_t i = 0; i < steps.size(); i += every) {
      std::array<double, kNeighbourSigmaCandidatesMm.size()> squared{};
      bool all = true;
      for (std::size_t c = 0; c < kNeighbourSigmaCandidatesMm.size() && all; ++c) {
        const auto fit = fit_at(steps, grid, i, kNeighbourSigmaCandidatesMm[c] * px_per_mm_,
                                smoothing_.min_neighbours, true,
                                NeighbourSmoothing::kChoiceExcludeMm * px_per_mm_);
        all = fit.has_value();
        if (all) squared[c] = (displacement(steps[i]) - *fit).squaredNorm();
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
