#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include <fmt/format.h>

#include "camera/cv_image.hpp"
#include "tactile/capture/track.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/stats.hpp"
#include "tracking/align_rows.hpp"
#include "tracking/track_gradient.hpp"

namespace tactile::capture {
namespace {

// Half-resolution pixels (about two ridge periods at 47 px/mm): what varies more slowly than
// this is shading, not ridges.
constexpr double kShadingSigmaPx = 4.0;

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// The landmark's neighbourhood in its reference frame, ready for inverse-compositional
// alignment (the warp's update is measured on the reference, not on the frame): the window's
// grey levels, weights and gradients (rows of `cols` pixels from `left`, `top`), the sums of the
// steepest-descent images of an affine warp that depend on the reference alone, and the inverse
// of their Hessian. All of it is computed once for every later frame. Single precision and no
// per-pixel offsets or descent images keep a window in the first-level cache: the alignment
// reads it a few times per frame for every track, and the memory traffic was its main cost.
struct Reference {
  int left = 0, top = 0, cols = 0, rows = 0;
  double x_px = 0, y_px = 0;  // the landmark
  std::vector<float> grey, weight, gx, gy;
  // The sums that depend on the reference alone, over the whole window (all_rows) and over
  // each half of its rows (rows 0, 2, 4, ... and rows 1, 3, 5, ...: steps at half the cost).
  struct Sums {
    Vector6 sum_weighted_descent = Vector6::Zero();
    Vector6 sum_weighted_grey_descent = Vector6::Zero();
    Matrix6 hessian_inverse = Matrix6::Zero();
    double total_weight = 0;
    double sum_weighted_grey = 0, sum_weighted_grey_squared = 0;
    bool invertible = false;
  } all_rows, even_rows, odd_rows;
  // Row prefix sums of the quantities a step needs over a window cut by the frame's border
  // (CutSum), made the first time the window is cut: with them a cut window's step costs what
  // a whole window's does instead of a per-pixel pass that builds the Hessian again.
  mutable std::vector<double> cut_prefix;
};

// The per-pixel terms summed over the part of a cut window inside the frame. With oy constant
// along a row, the descent d = (gx ox, gy ox, gx oy, gy oy, gx, gy) needs gx and gy alone and
// times ox, and the Hessian w d d^T needs gx gx, gx gy and gy gy times 1, ox and ox^2.
enum CutSum : std::size_t {
  kW,
  kWG,
  kWGG,
  kWGx,
  kWGy,
  kWGxOx,
  kWGyOx,
  kWGGx,
  kWGGy,
  kWGGxOx,
  kWGGyOx,
  kXX0,
  kXX1,
  kXX2,
  kXY0,
  kXY1,
  kXY2,
  kYY0,
  kYY1,
  kYY2,
  kCutSums
};

// Adds one pixel's terms (weight w, grey level g, gradient (gx, gy), offset ox along its row).
void add_pixel_terms(double w, double g, double gx, double gy, double ox, double* t) {
  const double xx = w * gx * gx, xy = w * gx * gy, yy = w * gy * gy;
  t[kW] += w;
  t[kWG] += w * g;
  t[kWGG] += w * g * g;
  t[kWGx] += w * gx;
  t[kWGy] += w * gy;
  t[kWGxOx] += w * gx * ox;
  t[kWGyOx] += w * gy * ox;
  t[kWGGx] += w * g * gx;
  t[kWGGy] += w * g * gy;
  t[kWGGxOx] += w * g * gx * ox;
  t[kWGGyOx] += w * g * gy * ox;
  t[kXX0] += xx;
  t[kXX1] += xx * ox;
  t[kXX2] += xx * ox * ox;
  t[kXY0] += xy;
  t[kXY1] += xy * ox;
  t[kXY2] += xy * ox * ox;
  t[kYY0] += yy;
  t[kYY1] += yy * ox;
  t[kYY2] += yy * ox * ox;
}

// Sums over pixels of a window: of the weights (sw), x grey (swg), x grey^2 (swgg), of weight x
// descent (swd), x grey (swgd), and the Hessian, sum of weight x descent x descent^T.
struct WindowSums {
  double sw = 0, swg = 0, swgg = 0;
  Vector6 swd = Vector6::Zero(), swgd = Vector6::Zero();
  Matrix6 hessian = Matrix6::Zero();

  // Adds a row's terms (t, summed over its pixels) at offset oy across the rows.
  void add_row(const double* t, double oy) {
    sw += t[kW];
    swg += t[kWG];
    swgg += t[kWGG];
    swd += Vector6(t[kWGxOx], t[kWGyOx], t[kWGx] * oy, t[kWGy] * oy, t[kWGx], t[kWGy]);
    swgd += Vector6(t[kWGGxOx], t[kWGGyOx], t[kWGGx] * oy, t[kWGGy] * oy, t[kWGGx], t[kWGGy]);
    const double oy2 = oy * oy;
    const double h[6][6] = {{t[kXX2], t[kXY2], t[kXX1] * oy, t[kXY1] * oy, t[kXX1], t[kXY1]},
                            {0, t[kYY2], t[kXY1] * oy, t[kYY1] * oy, t[kXY1], t[kYY1]},
                            {0, 0, t[kXX0] * oy2, t[kXY0] * oy2, t[kXX0] * oy, t[kXY0] * oy},
                            {0, 0, 0, t[kYY0] * oy2, t[kXY0] * oy, t[kYY0] * oy},
                            {0, 0, 0, 0, t[kXX0], t[kXY0]},
                            {0, 0, 0, 0, 0, t[kYY0]}};
    for (int i = 0; i < 6; ++i) {
      for (int j = i; j < 6; ++j) hessian(i, j) += h[i][j];
    }
  }

  // The Hessian's lower triangle from its upper one.
  Matrix6 full_hessian() const {
    Matrix6 h = hessian;
    h.triangularView<Eigen::StrictlyLower>() = h.transpose();
    return h;
  }
};

void make_cut_prefix(const Reference& ref) {
  const auto stride = static_cast<std::size_t>(ref.cols + 1) * kCutSums;
  ref.cut_prefix.assign(static_cast<std::size_t>(ref.rows) * stride, 0.0);
  const double ox0 = ref.left - ref.x_px;
  for (int r = 0; r < ref.rows; ++r) {
    double* p = ref.cut_prefix.data() + static_cast<std::size_t>(r) * stride;
    for (int c = 0; c < ref.cols; ++c, p += kCutSums) {
      const std::size_t i = static_cast<std::size_t>(r * ref.cols + c);
      std::copy(p, p + kCutSums, p + kCutSums);
      add_pixel_terms(ref.weight[i], ref.grey[i], ref.gx[i], ref.gy[i], ox0 + c, p + kCutSums);
    }
  }
}

// Columns [first, end) of a row seen at (x0 + c dx, y0 + c dy) whose samples fall inside the
// frame with the same margin as a whole window (see warped_window_inside); the samples of a
// line inside a rectangle are one run of columns.
void inside_columns(double x0, double y0, double dx, double dy, int cols, const FloatRows& image,
                    int& first, int& end) {
  constexpr double margin = 1e-3;
  const double lo_x = margin, hi_x = image.cols - 1 - margin;
  const double lo_y = margin, hi_y = image.rows - 1 - margin;
  double lo = 0, hi = cols - 1;
  // lo <= c <= hi where lo_v <= v0 + c dv < hi_v.
  const auto clip = [&](double v0, double dv, double lo_v, double hi_v) {
    if (dv == 0) {
      if (!(v0 >= lo_v && v0 < hi_v)) hi = -1;
      return;
    }
    const double a = (lo_v - v0) / dv, b = (hi_v - v0) / dv;
    lo = std::max(lo, std::min(a, b));
    hi = std::min(hi, std::max(a, b));
  };
  clip(x0, dx, lo_x, hi_x);
  clip(y0, dy, lo_y, hi_y);
  const auto inside = [&](int c) {
    const double x = x0 + c * dx, y = y0 + c * dy;
    return x >= lo_x && x < hi_x && y >= lo_y && y < hi_y;
  };
  if (!(hi >= lo)) {
    first = end = 0;
    return;
  }
  // The bounds above are exact up to rounding: the ends are checked sample by sample.
  first = std::clamp(static_cast<int>(std::ceil(lo)), 0, cols);
  end = std::clamp(static_cast<int>(std::floor(hi)) + 1, first, cols);
  while (first < end && !inside(first)) ++first;
  while (end > first && !inside(end - 1)) --end;
  while (first > 0 && inside(first - 1)) --first;
  while (end < cols && inside(end)) ++end;
}

Reference::Sums reference_sums(const WindowSums& w) {
  Reference::Sums s;
  s.total_weight = w.sw;
  s.sum_weighted_grey = w.swg;
  s.sum_weighted_grey_squared = w.swgg;
  s.sum_weighted_descent = w.swd;
  s.sum_weighted_grey_descent = w.swgd;
  const Eigen::FullPivLU<Matrix6> lu(w.full_hessian());
  s.invertible = lu.isInvertible();
  if (s.invertible) s.hessian_inverse = lu.inverse();
  return s;
}

// The reference around (x, y) in a smoothed frame; false where too little of the window is
// inside the frame or it holds too little texture to align.
bool make_reference(const cv::Mat& smooth, double x_px, double y_px, int half_side, int room_px,
                    Reference& ref) {
  ref = Reference{};
  // Near the frame's border the window is cut to the part inside it, with room for the
  // landmark to move; a window cut to less than a quarter is no reference.
  const int cx = static_cast<int>(std::lround(x_px)), cy = static_cast<int>(std::lround(y_px));
  const int left = std::max(cx - half_side, room_px),
            right = std::min(cx + half_side, smooth.cols - 1 - room_px);
  const int top = std::max(cy - half_side, room_px),
            bottom = std::min(cy + half_side, smooth.rows - 1 - room_px);
  if (4 * (right - left + 1) * (bottom - top + 1) < (2 * half_side + 1) * (2 * half_side + 1)) {
    return false;
  }
  ref.left = left;
  ref.top = top;
  ref.cols = right - left + 1;
  ref.rows = bottom - top + 1;
  ref.x_px = x_px;
  ref.y_px = y_px;
  const auto n = static_cast<std::size_t>(ref.cols * ref.rows);
  ref.grey.resize(n);
  ref.weight.resize(n);
  ref.gx.resize(n);
  ref.gy.resize(n);
  // Gaussian weights favour the landmark's own surroundings where the skin's strain varies
  // across the window; the Gaussian is the product of one along x and one along y.
  const double sigma = half_side;
  std::vector<double> along_x(static_cast<std::size_t>(ref.cols));
  for (int u = left; u <= right; ++u) {
    const double ox = u - x_px;
    along_x[static_cast<std::size_t>(u - left)] = std::exp(-ox * ox / (2 * sigma * sigma));
  }
  const auto cols = static_cast<std::size_t>(ref.cols);
  WindowSums sums, even, odd;
  for (int v = top; v <= bottom; ++v) {
    const double oy = v - y_px;
    const double along_y = std::exp(-oy * oy / (2 * sigma * sigma));
    const float* row = smooth.ptr<float>(v) + left;
    const float* up = smooth.ptr<float>(v - 1) + left;
    const float* down = smooth.ptr<float>(v + 1) + left;
    const std::size_t row0 = static_cast<std::size_t>(v - top) * cols;
    float* weight = ref.weight.data() + row0;
    float* grey = ref.grey.data() + row0;
    float* gx = ref.gx.data() + row0;
    float* gy = ref.gy.data() + row0;
    for (std::size_t c = 0; c < cols; ++c) {
      weight[c] = static_cast<float>(along_x[c] * along_y);
      grey[c] = row[c];
      gx[c] = 0.5f * (row[c + 1] - row[c - 1]);
      gy[c] = 0.5f * (down[c] - up[c]);
    }
    // The row's values first, in loops the compiler vectorises, then their terms.
    double t[kCutSums] = {};
    for (std::size_t c = 0; c < cols; ++c) {
      add_pixel_terms(weight[c], grey[c], gx[c], gy[c], left + static_cast<double>(c) - x_px, t);
    }
    sums.add_row(t, oy);
    if ((v - top) % 2 == 0) {
      even.add_row(t, oy);
    } else {
      odd.add_row(t, oy);
    }
  }
  ref.all_rows = reference_sums(sums);
  ref.even_rows = reference_sums(even);
  ref.odd_rows = reference_sums(odd);
  const double mean = sums.swg / sums.sw;
  const double spread = std::sqrt(std::max(0.0, sums.swgg / sums.sw - mean * mean));
  if (!ref.all_rows.invertible || spread < 1e-3) return false;
  return true;
}

struct Aligned {
  bool ok = false;
  double x_px = 0, y_px = 0;
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
};

// Whether every sample of the window warped to `position` + `l` x offset falls inside the
// image with room for bilinear interpolation. The warped window is a parallelogram and the
// allowed region convex, so its four corners decide. The margin keeps samples computed step by
// step along a row, or in single precision (about 4e-6 px off at 32 px), on the safe side.
bool warped_window_inside(const Reference& ref, const FloatRows& image,
                          const Eigen::Vector2d& position, const Eigen::Matrix2d& l) {
  constexpr double margin = 1e-3;
  const double ox[2] = {ref.left - ref.x_px, ref.left + ref.cols - 1 - ref.x_px};
  const double oy[2] = {ref.top - ref.y_px, ref.top + ref.rows - 1 - ref.y_px};
  for (const double a : ox) {
    for (const double b : oy) {
      const double x = position.x() + l(0, 0) * a + l(0, 1) * b;
      const double y = position.y() + l(1, 0) * a + l(1, 1) * b;
      if (!(x >= margin && y >= margin && x < image.cols - 1 - margin &&
            y < image.rows - 1 - margin)) {
        return false;
      }
    }
  }
  return true;
}

// Finds where the reference's landmark is in `smooth` (warp x -> position + linear x), from a
// start. Gain and offset of the grey levels are fitted at every step, so a change of exposure
// does not move the result. Where part of the warped window falls outside the frame (a landmark
// near the border), the rest is used if it holds at least half of the weight.
Aligned align(const Reference& ref, const cv::Mat& frame, double x_px, double y_px,
              const Eigen::Matrix2d& linear, const RefineParams& params) {
  Aligned a;
  const FloatRows smooth{frame.ptr<float>(0), frame.step1(), frame.cols, frame.rows};
  Eigen::Vector2d position(x_px, y_px);
  Eigen::Matrix2d l = linear;
  double correlation = 0;
  // The frame's mean grey over the reference's, in the reference's spreads: skin that lifts off
  // the glass turns bright and loses its ridges, and the alignment's gain and offset would
  // follow it there; a track ends instead (no strain across a gap of contact).
  double brightening = 0;
  bool converged = false;
  // The steps alternate between the window's even rows and its odd rows, each at half a whole
  // window's cost. The two halves see the same texture through different samples of the
  // camera's noise, so their fixed points differ by about that noise; once each half's warp is
  // where it was two steps before, the mean of the last two warps stands for the whole window's,
  // with the noise of every row averaged. Here the warps after the last two half steps, and
  // the last one's correlation.
  const bool alternate =
      params.alternate_row_halves && ref.even_rows.invertible && ref.odd_rows.invertible;
  int halves_in_a_row = 0;
  Eigen::Vector2d position_before[2] = {position, position};
  Eigen::Matrix2d linear_before[2] = {l, l};
  double correlation_before = 0;
  for (int it = 0; it < params.max_iterations && !converged; ++it) {
    double sw = 0, swi = 0, swii = 0, swt = 0, swtt = 0, swit = 0;
    // sum of weight x sample x descent: with the reference's own sums it gives the update in
    // this one pass over the window. Its six entries come from four sums per row, since the
    // descent images are the gradients times the offsets.
    Vector6 swid = Vector6::Zero();
    // Over a cut window, the reference's sums over the part inside the frame.
    WindowSums inside;
    const bool whole = warped_window_inside(ref, smooth, position, l);
    if (!whole && ref.cut_prefix.empty()) make_cut_prefix(ref);
    // Half steps where the window is whole. Elsewhere whole-window steps (over the part inside
    // the frame where the window is cut), of which the first, from a start up to a pixel or so
    // off, needs only the even rows.
    const bool half = alternate && whole;
    const bool odd_half = half && halves_in_a_row % 2 == 1;
    const bool coarse = half || (it == 0 && whole && ref.even_rows.invertible);
    const int row_step = coarse ? 2 : 1;
    const int first_row = odd_half ? 1 : 0;
    const double l00 = l(0, 0), l01 = l(0, 1), l10 = l(1, 0), l11 = l(1, 1);
    const double ox0 = ref.left - ref.x_px, oy0 = ref.top - ref.y_px;
    if (whole) {
      // The whole window in one pass, its sums kept in vector registers from row to row.
      const std::size_t skip =
          static_cast<std::size_t>(first_row) * static_cast<std::size_t>(ref.cols);
      const double oyf = oy0 + first_row;
      const WindowSpan window{ref.weight.data() + skip,
                              ref.grey.data() + skip,
                              ref.gx.data() + skip,
                              ref.gy.data() + skip,
                              ref.cols,
                              ref.rows - first_row,
                              row_step,
                              position.x() + l00 * ox0 + l01 * oyf,
                              position.y() + l10 * ox0 + l11 * oyf,
                              l00,
                              l10,
                              l01,
                              l11,
                              ox0,
                              oyf};
      WindowSampleSums ws;
      add_window_sums_vector(smooth, window, ws);
      swi = ws.i;
      swii = ws.ii;
      swit = ws.it;
      swid << ws.a_ox, ws.c_ox, ws.a_oy, ws.c_oy, ws.a, ws.c;
    } else {
      // A cut window row by row over the columns inside the frame, its reference's sums over
      // them from the prefix sums.
      const std::size_t prefix_stride = static_cast<std::size_t>(ref.cols + 1) * kCutSums;
      for (int r = 0; r < ref.rows; ++r) {
        const double oy = oy0 + r;
        const double x = position.x() + l00 * ox0 + l01 * oy;
        const double y = position.y() + l10 * ox0 + l11 * oy;
        const std::size_t row0 = static_cast<std::size_t>(r) * static_cast<std::size_t>(ref.cols);
        int first = 0, end = ref.cols;
        inside_columns(x, y, l00, l10, ref.cols, smooth, first, end);
        if (first == end) continue;
        RowSums rs;
        const RowSpan span{ref.weight.data() + row0,
                           ref.grey.data() + row0,
                           ref.gx.data() + row0,
                           ref.gy.data() + row0,
                           first,
                           end,
                           x,
                           y,
                           l00,
                           l10,
                           ox0};
        add_row_sums_vector(smooth, span, rs);
        swi += rs.i;
        swii += rs.ii;
        swit += rs.it;
        swid(0) += rs.a_ox;
        swid(1) += rs.c_ox;
        swid(2) += rs.a * oy;
        swid(3) += rs.c * oy;
        swid(4) += rs.a;
        swid(5) += rs.c;
        const double* row_prefix =
            ref.cut_prefix.data() + static_cast<std::size_t>(r) * prefix_stride;
        const double* before = row_prefix + static_cast<std::size_t>(first) * kCutSums;
        const double* through = row_prefix + static_cast<std::size_t>(end) * kCutSums;
        double t[kCutSums];
        for (std::size_t q = 0; q < kCutSums; ++q) t[q] = through[q] - before[q];
        inside.add_row(t, oy);
      }
    }
    // The reference's own sums over the whole window are fixed; only a cut window needs them
    // from its inside part.
    const Reference::Sums& fixed =
        coarse ? (odd_half ? ref.odd_rows : ref.even_rows) : ref.all_rows;
    if (whole) {
      sw = fixed.total_weight;
      swt = fixed.sum_weighted_grey;
      swtt = fixed.sum_weighted_grey_squared;
    } else {
      sw = inside.sw;
      swt = inside.swg;
      swtt = inside.swgg;
    }
    if (2 * sw < fixed.total_weight) return a;
    const double mean = swi / sw, ref_mean = swt / sw;
    const double spread = std::sqrt(std::max(0.0, swii / sw - mean * mean));
    const double ref_spread = std::sqrt(std::max(0.0, swtt / sw - ref_mean * ref_mean));
    if (spread < 1e-3 || ref_spread < 1e-3) return a;
    correlation = (swit / sw - mean * ref_mean) / (spread * ref_spread);
    brightening = (mean - ref_mean) / ref_spread;
    // Grey levels of the frame brought to the reference's mean and spread: the error at a
    // sample is ref_mean + gain (warped - mean) - grey, and the update sums weight x error x
    // descent.
    const double gain = ref_spread / spread;
    Vector6 p;
    if (whole) {
      const Vector6 b = gain * swid + (ref_mean - gain * mean) * fixed.sum_weighted_descent -
                        fixed.sum_weighted_grey_descent;
      p = fixed.hessian_inverse * b;
    } else {
      const Vector6 b = gain * swid + (ref_mean - gain * mean) * inside.swd - inside.swgd;
      const Eigen::FullPivLU<Matrix6> lu(inside.full_hessian());
      if (!lu.isInvertible()) return a;
      p = lu.solve(b);
    }
    Eigen::Matrix2d step_linear;
    step_linear << 1 + p(0), p(2), p(1), 1 + p(3);
    if (std::abs(step_linear.determinant()) < 1e-6) return a;
    // Inverse composition: W <- W o dW^-1.
    l = l * step_linear.inverse();
    position -= l * Eigen::Vector2d(p(4), p(5));
    if (half) {
      ++halves_in_a_row;
      const Eigen::Vector2d two_before = position_before[0];
      const Eigen::Matrix2d linear_two_before = linear_before[0];
      position_before[0] = position_before[1];
      linear_before[0] = linear_before[1];
      position_before[1] = position;
      linear_before[1] = l;
      if (halves_in_a_row >= 3 && (position - two_before).norm() < params.stop_step_px &&
          (l - linear_two_before).cwiseAbs().maxCoeff() < params.stop_step_px / 10) {
        converged = true;
        position = 0.5 * (position + position_before[0]);
        l = 0.5 * (l + linear_before[0]);
        correlation = 0.5 * (correlation + correlation_before);
      }
      correlation_before = correlation;
    } else {
      halves_in_a_row = 0;
      converged = !coarse && std::hypot(p(4), p(5)) < params.stop_step_px &&
                  p.head<4>().cwiseAbs().maxCoeff() < params.stop_step_px / 10;
    }
  }
  a.x_px = position.x();
  a.y_px = position.y();
  a.linear = l;
  const double distortion = (l - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff();
  a.ok = converged && correlation >= params.min_correlation && brightening < 0.5 &&
         distortion <= params.max_distortion && std::isfinite(a.x_px) && std::isfinite(a.y_px);
  return a;
}

void check_refine_params(double px_per_mm, const RefineParams& params) {
  if (!(px_per_mm > 0)) throw std::invalid_argument("refine_tracks: px_per_mm must be > 0");
  if (!(params.window_mm > 0)) throw std::invalid_argument("refine_tracks: window_mm must be > 0");
  if (!(params.min_correlation >= 0 && params.min_correlation < 1)) {
    throw std::invalid_argument("refine_tracks: min_correlation must be 0 to 1");
  }
  if (params.min_frames < 2) throw std::invalid_argument("refine_tracks: min_frames must be >= 2");
  if (!(params.presmoothing_px >= 0)) {
    throw std::invalid_argument("refine_tracks: presmoothing_px must be >= 0");
  }
}

// Normalised correlation of `a` and `b` (CV_32F) over the part of the view both see when `b` is
// `a` moved by the whole pixels (dx, dy); -1 where they share less than a quarter of it.
double overlap_correlation(const cv::Mat& a, const cv::Mat& b, int dx, int dy) {
  const int w = a.cols - std::abs(dx), h = a.rows - std::abs(dy);
  if (w <= 0 || h <= 0 || 4 * w * h < a.cols * a.rows) return -1;
  const int ax = std::max(0, -dx), ay = std::max(0, -dy), bx = std::max(0, dx),
            by = std::max(0, dy);
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int y = 0; y < h; ++y) {
    const float* pa = a.ptr<float>(ay + y) + ax;
    const float* pb = b.ptr<float>(by + y) + bx;
    for (int x = 0; x < w; ++x) {
      const double u = pa[x], v = pb[x];
      sa += u;
      sb += v;
      saa += u * u;
      sbb += v * v;
      sab += u * v;
    }
  }
  const double n = static_cast<double>(w) * h;
  const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
  return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : -1;
}

// The motion of the whole view from `before` to `now` (full-resolution pixels), by phase
// correlation of the two frames at half resolution: the motion is only a start for the
// alignments, and a quarter of the pixels keeps it a small part of a frame's time. A print's
// ridges repeat, so the correlation surface has side peaks about one ridge period from the true
// one: the peak is checked against the other motions that are plausible (the view's motion in
// the previous frame and no motion), by the correlation of the frames' shared part, and the best
// of them is kept.
Eigen::Vector2d view_motion(const cv::Mat& before, const cv::Mat& now, cv::Mat& hanning,
                            const Eigen::Vector2d& previous) {
  if (hanning.size() != now.size()) cv::createHanningWindow(hanning, now.size(), CV_32F);
  const cv::Point2d peak = cv::phaseCorrelate(before, now, hanning);
  const std::array<Eigen::Vector2d, 3> candidates{Eigen::Vector2d(peak.x, peak.y), previous / 2,
                                                  Eigen::Vector2d::Zero()};
  Eigen::Vector2d best = candidates[0];
  double best_score = -2;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const Eigen::Vector2d& c = candidates[k];
    // A candidate within a pixel of one already scored is the same motion.
    bool seen = false;
    for (std::size_t e = 0; e < k; ++e) seen = seen || (candidates[e] - c).norm() < 1;
    if (seen || !c.allFinite()) continue;
    const double score = overlap_correlation(before, now, static_cast<int>(std::lround(c.x())),
                                             static_cast<int>(std::lround(c.y())));
    if (score > best_score + 1e-9) {
      best_score = score;
      best = c;
    }
  }
  return 2 * best;
}

// A little smoothing takes noise out of the gradients that the alignment follows.
void smoothed_frame(const GrayImage& frame, double presmoothing_px, cv::Mat& out) {
  as_mat(frame).convertTo(out, CV_32F);
  if (presmoothing_px > 0) cv::GaussianBlur(out, out, {0, 0}, presmoothing_px);
}

}  // namespace

RefineStats refine_tracks(const std::vector<GrayImage>& frames, std::vector<Track>& tracks,
                          double px_per_mm, const RefineParams& params, int threads) {
  check_refine_params(px_per_mm, params);
  const int n = static_cast<int>(frames.size());
  for (const auto& t : tracks) {
    if (t.first_frame < 0 || t.last_frame() >= n) {
      throw std::invalid_argument("refine_tracks: a track reaches beyond the frames");
    }
  }
  const int half_side =
      std::max(2, static_cast<int>(std::lround(params.window_mm * px_per_mm / 2)));
  const double max_offset_px = params.max_offset_mm * px_per_mm;
  const int room_px = 1 + static_cast<int>(std::ceil(max_offset_px));
  std::vector<cv::Mat> smooth(frames.size());
  parallel_for(frames.size(), worker_count(threads), [&](std::size_t f) {
    smoothed_frame(frames[f], params.presmoothing_px, smooth[f]);
  });

  std::vector<long> steps(tracks.size(), 0), anchors(tracks.size(), 0);
  std::vector<char> cut(tracks.size(), 0);
  parallel_for(tracks.size(), worker_count(threads), [&](std::size_t i) {
    const Track detected = tracks[i];
    Track& t = tracks[i];
    const auto frame_at = [&](int f) -> const cv::Mat& {
      return smooth[static_cast<std::size_t>(f)];
    };
    const std::size_t seen = detected.x_px.size();
    const std::size_t reach =
        params.follow_past_detections ? static_cast<std::size_t>(n - detected.first_frame) : seen;
    t.x_px.assign(1, detected.x_px[0]);
    t.y_px.assign(1, detected.y_px[0]);
    // Renewed references would make the warps' linear parts relative to different frames.
    t.gradient.clear();
    Reference ref;
    int ref_frame = detected.first_frame;
    if (!make_reference(frame_at(ref_frame), t.x_px[0], t.y_px[0], half_side, room_px, ref)) {
      t.x_px.clear();
      t.y_px.clear();
    }
    Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
    for (std::size_t k = 1; k < reach && !t.x_px.empty(); ++k) {
      const int f = detected.first_frame + static_cast<int>(k);
      ++steps[i];
      // Started where the detections say the landmark moved; past them, where its own last
      // step would take it.
      const bool has_detection = k < seen;
      // The track's own last step carried on.
      double ox = t.x_px[k - 1], oy = t.y_px[k - 1];
      if (k >= 2) {
        ox += t.x_px[k - 1] - t.x_px[k - 2];
        oy += t.y_px[k - 1] - t.y_px[k - 2];
      }
      double sx = ox, sy = oy;
      if (has_detection) {
        sx = t.x_px[k - 1] + detected.x_px[k] - detected.x_px[k - 1];
        sy = t.y_px[k - 1] + detected.y_px[k] - detected.y_px[k - 1];
      }
      const auto accepted = [&](const Aligned& a) {
        return a.ok && (!has_detection || std::hypot(a.x_px - detected.x_px[k],
                                                     a.y_px - detected.y_px[k]) <= max_offset_px);
      };
      Aligned a = align(ref, frame_at(f), sx, sy, linear, params);
      // Only where the image, not the detection, disagreed: a detection that jumped to another
      // landmark must end the track, not lead a new reference onto that landmark.
      if (!a.ok && params.reanchor && ref_frame != f - 1) {
        // The skin has deformed away from the reference: the last confirmed frame becomes the
        // reference. Each new anchor adds the error of one position (a few hundredths of a
        // pixel) to the track, instead of ending it.
        Reference next;
        if (make_reference(frame_at(f - 1), t.x_px[k - 1], t.y_px[k - 1], half_side, room_px,
                           next)) {
          const Aligned b = align(next, frame_at(f), ox, oy, Eigen::Matrix2d::Identity(), params);
          if (accepted(b)) {
            ref = std::move(next);
            ref_frame = f - 1;
            a = b;
            ++anchors[i];
          }
        }
      }
      if (!accepted(a)) break;
      t.x_px.push_back(a.x_px);
      t.y_px.push_back(a.y_px);
      linear = a.linear;
    }
    cut[i] = t.x_px.size() < seen;
  });
  RefineStats stats;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    stats.steps += steps[i];
    stats.cut += cut[i];
    stats.anchors += anchors[i];
  }
  // A track ends at the first frame the image does not confirm: from there on its positions
  // could only be the detections, whose noise (about 0.5 px on real prints) would dominate the
  // strain of every edge the track is in.
  std::vector<Track> kept;
  for (auto& t : tracks) {
    if (static_cast<int>(t.x_px.size()) < params.min_frames) {
      ++stats.dropped;
      continue;
    }
    kept.push_back(std::move(t));
  }
  // Followed past its detections, a track can run onto the landmark of another track (the same
  // pore detected again after a gap, which the detection tracker started anew). Two tracks on
  // one landmark make a zero-length edge; the one that started later gives way from there.
  std::stable_sort(kept.begin(), kept.end(),
                   [](const Track& a, const Track& b) { return a.first_frame < b.first_frame; });
  const double same_px = params.same_landmark_mm * px_per_mm;
  std::vector<std::vector<std::array<double, 2>>> taken(static_cast<std::size_t>(n));
  std::vector<Track> unique;
  for (auto& t : kept) {
    std::size_t keep = t.x_px.size();
    for (std::size_t k = 0; k < t.x_px.size(); ++k) {
      const auto& here = taken[static_cast<std::size_t>(t.first_frame) + k];
      const bool clash = std::any_of(here.begin(), here.end(), [&](const auto& p) {
        return std::hypot(p[0] - t.x_px[k], p[1] - t.y_px[k]) < same_px;
      });
      if (clash) {
        keep = k;
        break;
      }
    }
    if (static_cast<int>(keep) < params.min_frames) {
      ++stats.dropped;
      continue;
    }
    t.x_px.resize(keep);
    t.y_px.resize(keep);
    for (std::size_t k = 0; k < keep; ++k) {
      taken[static_cast<std::size_t>(t.first_frame) + k].push_back({t.x_px[k], t.y_px[k]});
    }
    unique.push_back(std::move(t));
  }
  kept = std::move(unique);
  for (std::size_t i = 0; i < kept.size(); ++i) kept[i].id = static_cast<std::int32_t>(i);
  tracks = std::move(kept);
  return stats;
}

struct AlignmentTracker::State {
  struct Live {
    Track track;
    Reference reference;
    Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
    bool ended = false;
  };
  double px_per_mm = 0;
  RefineParams params;
  int threads = 0;
  int half_side = 0;
  double max_offset_px = 0;
  int room_px = 0;
  int frames = 0;
  std::int32_t next_id = 0;
  int width_px = 0, height_px = 0;
  double min_spacing_px = 0;  // set_min_spacing_px
  // Each live track on the heap: a frame where tracks end moves pointers, not kilobytes.
  std::vector<std::unique_ptr<Live>> live;
  std::vector<Track> ended;
  RefineStats stats;
  cv::Mat smooth, half, half_before, hanning;
  // The whole view's motion into each frame from the one before (pixels; frame 0: none).
  std::vector<Eigen::Vector2d> view_motion;
  // last_step()'s curvature fits by track id, kept while the track lives.
  struct StepFit;
  std::unordered_map<std::int32_t, std::unique_ptr<StepFit>> step_fits;
};

AlignmentTracker::AlignmentTracker(double px_per_mm, const RefineParams& params, int threads)
    : state_(std::make_unique<State>()) {
  check_refine_params(px_per_mm, params);
  State& s = *state_;
  s.px_per_mm = px_per_mm;
  s.params = params;
  s.threads = threads;
  s.half_side = std::max(2, static_cast<int>(std::lround(params.window_mm * px_per_mm / 2)));
  s.max_offset_px = params.max_offset_mm * px_per_mm;
  s.room_px = 1 + static_cast<int>(std::ceil(s.max_offset_px));
}

AlignmentTracker::~AlignmentTracker() = default;

int AlignmentTracker::frames() const {
  return state_->frames;
}

int AlignmentTracker::live_tracks() const {
  return static_cast<int>(state_->live.size());
}

void AlignmentTracker::set_min_spacing_px(double px) {
  if (!(px >= 0) || !std::isfinite(px)) {
    throw std::invalid_argument(
        fmt::format("AlignmentTracker: a spacing of {} px is not a distance (0 or more)", px));
  }
  state_->min_spacing_px = px;
}

namespace {

// Points kept at least a spacing apart, taken one at a time: cells of the spacing's side over
// the frame (positions off it in the border cells), so that a kept point that is too close lies
// in the cell of the one asked about or in the eight around it.
class SpacedPoints {
 public:
  SpacedPoints(int width_px, int height_px, double spacing_px)
      : spacing_px_(spacing_px),
        cols_(std::max(1, static_cast<int>(width_px / spacing_px) + 1)),
        rows_(std::max(1, static_cast<int>(height_px / spacing_px) + 1)),
        cells_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_)) {}

  // Keeps p where no kept point is closer than the spacing; says whether it did.
  bool add(const Eigen::Vector2d& p) {
    const int cx = cell(p.x(), cols_), cy = cell(p.y(), rows_);
    for (int gy = std::max(0, cy - 1); gy <= std::min(rows_ - 1, cy + 1); ++gy) {
      for (int gx = std::max(0, cx - 1); gx <= std::min(cols_ - 1, cx + 1); ++gx) {
        for (const auto& q : cells_[static_cast<std::size_t>(gy * cols_ + gx)]) {
          if ((q - p).squaredNorm() < spacing_px_ * spacing_px_) return false;
        }
      }
    }
    cells_[static_cast<std::size_t>(cy * cols_ + cx)].push_back(p);
    return true;
  }

 private:
  int cell(double v, int count) const {
    if (!(v > 0)) return 0;            // NaN too
    const double c = v / spacing_px_;  // compared before the cast: no overflow far off the frame
    return c >= count - 1 ? count - 1 : static_cast<int>(c);
  }

  double spacing_px_;
  int cols_, rows_;
  std::vector<std::vector<Eigen::Vector2d>> cells_;
};

}  // namespace

bool AlignmentTracker::sliding() const {
  const State& s = *state_;
  return !s.view_motion.empty() && s.view_motion.back().norm() > s.max_offset_px;
}

namespace {

// Tracks binned by position in square cells, for finding those near a point without a pass
// over all of them (or over all in a strip across the image).
class NearIndex {
 public:
  // The tracks j with included[j] and a finite at[j], in cells of about cell_px.
  NearIndex(const std::vector<Eigen::Vector2d>& at, const std::vector<char>& included,
            double cell_px) {
    double x_max = 0, y_max = 0;
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (!included[j] || !at[j].allFinite()) continue;
      if (count_ == 0) {
        x0_ = x_max = at[j].x();
        y0_ = y_max = at[j].y();
      }
      x0_ = std::min(x0_, at[j].x());
      y0_ = std::min(y0_, at[j].y());
      x_max = std::max(x_max, at[j].x());
      y_max = std::max(y_max, at[j].y());
      ++count_;
    }
    if (count_ == 0) return;
    // At most kMaxCells a side, however far apart the tracks lie.
    constexpr double kMaxCells = 1024;
    cell_px_ = std::max({cell_px, (x_max - x0_) / kMaxCells, (y_max - y0_) / kMaxCells, 1e-9});
    cols_ = cell_of(x_max, x0_) + 1;
    rows_ = cell_of(y_max, y0_) + 1;
    // Counting sort into the cells: within a cell, tracks in their own order.
    first_.assign(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_) + 1, 0);
    std::vector<std::size_t> cell(at.size(), 0);
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (!included[j] || !at[j].allFinite()) continue;
      cell[j] =
          static_cast<std::size_t>(cell_of(at[j].y(), y0_)) * static_cast<std::size_t>(cols_) +
          static_cast<std::size_t>(cell_of(at[j].x(), x0_));
      ++first_[cell[j] + 1];
    }
    for (std::size_t c = 1; c < first_.size(); ++c) first_[c] += first_[c - 1];
    tracks_.resize(count_);
    std::vector<std::size_t> fill(first_.begin(), first_.end() - 1);
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (included[j] && at[j].allFinite()) tracks_[fill[cell[j]]++] = j;
    }
  }

  bool empty() const { return count_ == 0; }

  // Calls visit(j) for every track within reach_px of p along both axes (and for some beyond).
  template <class Visit>
  void for_each_near(const Eigen::Vector2d& p, double reach_px, Visit&& visit) const {
    if (count_ == 0 || !p.allFinite()) return;
    // A hair wider, so that rounding cannot leave out a track a distance test would keep.
    const double reach = reach_px * (1 + 1e-9) + 1e-9;
    const auto range = [&](double v, double origin, int cells, int& lo, int& hi) {
      const double a = std::floor((v - reach - origin) / cell_px_);
      const double b = std::floor((v + reach - origin) / cell_px_);
      if (b < 0 || a > cells - 1) return false;
      lo = static_cast<int>(std::max(a, 0.0));
      hi = static_cast<int>(std::min(b, cells - 1.0));
      return true;
    };
    int x_lo = 0, x_hi = 0, y_lo = 0, y_hi = 0;
    if (!range(p.x(), x0_, cols_, x_lo, x_hi) || !range(p.y(), y0_, rows_, y_lo, y_hi)) return;
    for (int cy = y_lo; cy <= y_hi; ++cy) {
      const std::size_t row = static_cast<std::size_t>(cy) * static_cast<std::size_t>(cols_);
      for (std::size_t k = first_[row + static_cast<std::size_t>(x_lo)];
           k < first_[row + static_cast<std::size_t>(x_hi) + 1]; ++k) {
        visit(tracks_[k]);
      }
    }
  }

 private:
  int cell_of(double v, double origin) const {
    return static_cast<int>(std::floor((v - origin) / cell_px_));
  }

  std::size_t count_ = 0;
  double x0_ = 0, y0_ = 0, cell_px_ = 1;
  int cols_ = 0, rows_ = 0;
  std::vector<std::size_t> first_;   // cell c holds tracks_[first_[c] .. first_[c + 1])
  std::vector<std::size_t> tracks_;  // by cell, row by row
};

// Where the neighbours' motion in this frame takes the landmark last seen at `from`: a
// Gaussian-weighted fit of an affine motion field to the steps (from `last` to `now`) of the
// nearest confirmed tracks within radius_px other than `self` (at least three; the fit's
// gradient is pulled towards none where they line up). The motion of skin changes smoothly
// across a few landmarks, so where a track's own history predicts badly, its neighbours'
// present motion predicts well.
bool neighbours_motion(const std::vector<Eigen::Vector2d>& last,
                       const std::vector<Eigen::Vector2d>& now, const NearIndex& known,
                       std::size_t self, const Eigen::Vector2d& from, double radius_px,
                       Eigen::Vector2d& out) {
  constexpr std::size_t kNearest = 8;
  std::array<std::pair<double, std::size_t>, kNearest> near;
  std::size_t count = 0;
  const double r2 = radius_px * radius_px;
  known.for_each_near(from, radius_px, [&](std::size_t j) {
    const double d2 = (last[j] - from).squaredNorm();
    if (j == self || !(d2 <= r2)) return;
    // The nearest kNearest by distance, then by track: the same whatever order they come in.
    const std::pair<double, std::size_t> c(d2, j);
    if (count == kNearest && !(c < near[kNearest - 1])) return;
    std::size_t k = count < kNearest ? count++ : kNearest - 1;
    for (; k > 0 && c < near[k - 1]; --k) near[k] = near[k - 1];
    near[k] = c;
  });
  if (count < 3) return false;
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, 2> b = Eigen::Matrix<double, 3, 2>::Zero();
  const double scale = radius_px / 2;
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t j = near[k].second;
    const Eigen::Vector2d o = (last[j] - from) / scale;
    const double w = std::exp(-0.5 * o.squaredNorm());
    const Eigen::Vector3d row(1, o.x(), o.y());
    a += w * row * row.transpose();
    b += w * row * (now[j] - last[j]).transpose();
  }
  // A little weight against a gradient: with the neighbours along a line, or all on one side,
  // the fit falls back towards their weighted mean step.
  a(1, 1) += 1e-3 * a(0, 0);
  a(2, 2) += 1e-3 * a(0, 0);
  const Eigen::Matrix<double, 3, 2> c = a.ldlt().solve(b);
  out = from + c.row(0).transpose();
  return std::isfinite(out.x()) && std::isfinite(out.y());
}

// Workers for a step of `count` jobs: one where the jobs are too few to pay for starting a
// thread (a parallel_for of two trivial jobs on two threads took 11 us here, start and join),
// which a step of a few retries or a few cheap checks costs more than it takes over. The jobs are
// independent, so the result does not depend on it.
int workers_for(std::size_t count, std::size_t min_for_two, int threads) {
  return count < min_for_two ? 1 : worker_count(threads);
}

// Jobs below which a step stays on one thread: an alignment takes at most about 10 us (the 640 x
// 484 fast scene's 29 aligned frames, 32,538 alignments and all else, took 354-402 ms of CPU with
// whole-window steps; the alternating row halves need about a quarter less window work); a
// neighbours' motion is a weighted fit over the tracks within the radius (a median of 84 on the
// fast scene), far less.
constexpr std::size_t kAlignmentsForTwo = 8;
constexpr std::size_t kMotionsForTwo = 64;

}  // namespace

void AlignmentTracker::add_frame(const GrayImage& image, const std::vector<Feature>& seeds) {
  add_frame(image, seeds, state_->frames);
}

void AlignmentTracker::add_frame(const GrayImage& image, const std::vector<Feature>& found,
                                 int seeds_frame) {
  State& s = *state_;
  if (seeds_frame < 0 || seeds_frame > s.frames) {
    throw std::invalid_argument(fmt::format(
        "AlignmentTracker: seeds found on frame {}, not one of frames 0 to {} (this one)",
        seeds_frame, s.frames));
  }
  if (s.frames == 0) {
    s.width_px = image.width_px;
    s.height_px = image.height_px;
  } else if (image.width_px != s.width_px || image.height_px != s.height_px) {
    throw std::invalid_argument(
        fmt::format("AlignmentTracker: frame {} is {}x{} px, frame 0 is {}x{} px", s.frames,
                    image.width_px, image.height_px, s.width_px, s.height_px));
  }
  smoothed_frame(image, s.params.presmoothing_px, s.smooth);
  std::swap(s.half_before, s.half);
  cv::resize(s.smooth, s.half, {}, 0.5, 0.5, cv::INTER_AREA);
  // Only the ridges: the print's shading varies slowly across the view and, left in, correlates
  // better with no motion at all than the ridges do with the true one.
  cv::Mat shading;
  cv::GaussianBlur(s.half, shading, {0, 0}, kShadingSigmaPx);
  s.half -= shading;
  const int frame = s.frames++;
  const std::size_t n = s.live.size();
  // The whole view's motion first: where the skin slides through the view, a new track's first
  // step is many pixels, far beyond what an alignment from where it stood can find.
  Eigen::Vector2d motion = Eigen::Vector2d::Zero();
  if (frame > 0) {
    motion = view_motion(s.half_before, s.half, s.hanning, s.view_motion.back());
  }
  s.view_motion.push_back(motion);
  // The view slides where it moves further than an alignment may move from its start
  // (max_offset_mm): a new track standing still could not follow it. Below that a new track
  // starts standing still, as it always has.
  const bool sliding = motion.norm() > s.max_offset_px;
  // Each track's start: its own last step carried on; on its second frame, the view's motion
  // where the view slides, and standing still otherwise.
  std::vector<Eigen::Vector2d> start(n);
  std::vector<Aligned> result(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Track& t = s.live[i]->track;
    const std::size_t k = t.x_px.size();
    const Eigen::Vector2d first_step = sliding ? motion : Eigen::Vector2d::Zero();
    const double step_x = k >= 2 ? t.x_px[k - 1] - t.x_px[k - 2] : first_step.x();
    const double step_y = k >= 2 ? t.y_px[k - 1] - t.y_px[k - 2] : first_step.y();
    start[i] = {t.x_px[k - 1] + step_x, t.y_px[k - 1] + step_y};
  }
  // An alignment that ends within max_offset_px of where it started.
  // A retry starts close to the answer or not at all: it is not given the full iterations.
  RefineParams retry_params = s.params;
  retry_params.max_iterations = std::min(s.params.max_iterations, 10);
  const auto try_align = [&](std::size_t i, Aligned& out, bool retry) {
    const State::Live& l = *s.live[i];
    out = align(l.reference, s.smooth, start[i].x(), start[i].y(), l.linear,
                retry ? retry_params : s.params);
    return out.ok &&
           std::hypot(out.x_px - start[i].x(), out.y_px - start[i].y()) <= s.max_offset_px;
  };
  // A track whose own prediction was good lands near it. One that landed far from it may have
  // locked onto the wrong stretch of ridge (a start pixels off, or a shift along the ridge that
  // the window barely constrains): it waits for its neighbours' verdict below.
  const bool by_neighbours = s.params.neighbour_rounds > 0;
  const double sure_px = by_neighbours ? 0.5 * s.max_offset_px : s.max_offset_px;
  enum : char { kNone, kConfirmed, kTentative };
  std::vector<char> state(n, kNone);
  parallel_for(n, worker_count(s.threads), [&](std::size_t i) {
    if (!try_align(i, result[i], false)) return;
    const double d = std::hypot(result[i].x_px - start[i].x(), result[i].y_px - start[i].y());
    state[i] = d <= sure_px ? kConfirmed : kTentative;
  });
  s.stats.steps += static_cast<long>(n);
  // Where the skin moves several pixels a frame and its motion changes from frame to frame (a
  // fast wave, a slow camera), a track's own last step is a poor start and the alignment fails
  // where the landmark is still plainly in view. Its neighbours that did confirm this frame say
  // where it went: the retry starts at their motion, fitted around it, and rounds repeat while
  // new tracks confirm, so the motion spreads from where it was small. A result must then agree
  // with the neighbours' motion. Each round reads only the rounds before it, so the result does
  // not depend on the workers.
  const double radius_px = s.params.neighbour_radius_mm * s.px_per_mm;
  const double agree_px = s.params.neighbour_check_px;
  std::vector<Eigen::Vector2d> last(n), now(n);
  for (std::size_t i = 0; i < n; ++i) {
    last[i] = {s.live[i]->track.x_px.back(), s.live[i]->track.y_px.back()};
  }
  for (int round = 0; round < s.params.neighbour_rounds; ++round) {
    std::vector<std::size_t> open;
    std::vector<char> sure(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (state[i] == kConfirmed) {
        sure[i] = 1;
        now[i] = {result[i].x_px, result[i].y_px};
      } else {
        open.push_back(i);
      }
    }
    const NearIndex known(last, sure, radius_px);
    if (known.empty() || open.empty()) break;
    std::vector<char> next(state);
    std::vector<Aligned> retried(open.size());
    std::vector<char> changed(open.size(), 0);
    const int open_workers = workers_for(open.size(), kAlignmentsForTwo, s.threads);
    parallel_for(open.size(), open_workers, [&](std::size_t r) {
      const std::size_t i = open[r];
      Eigen::Vector2d p;
      if (!neighbours_motion(last, now, known, n, last[i], radius_px, p)) return;
      const auto near = [&](const Aligned& a) {
        return std::hypot(a.x_px - p.x(), a.y_px - p.y()) <= agree_px;
      };
      if (state[i] == kTentative && near(result[i])) {
        next[i] = kConfirmed;
        changed[r] = 1;
        return;
      }
      // A start within a fraction of a pixel of the one tried gives the same answer.
      if ((p - start[i]).norm() < s.params.neighbour_retry_px) {
        next[i] = kNone;
        return;
      }
      start[i] = p;
      changed[r] = 1;
      next[i] = try_align(i, retried[r], true) && near(retried[r]) ? kConfirmed : kNone;
      if (next[i] == kConfirmed) result[i] = retried[r];
    });
    state = std::move(next);
    const auto tried = std::count(changed.begin(), changed.end(), 1);
    if (tried == 0) break;
    s.stats.steps += static_cast<long>(tried);
  }
  // Without confirmed neighbours there is no one to ask: as without them.
  std::vector<char> confirmed(n, 0);
  for (std::size_t i = 0; i < n; ++i) confirmed[i] = state[i] != kNone;
  // A track confirmed by its own prediction far from where its neighbours' motion takes it is
  // tried once more from theirs, and ended unless it then agrees with them.
  if (by_neighbours && agree_px > 0) {
    for (std::size_t i = 0; i < n; ++i) {
      if (confirmed[i]) now[i] = {result[i].x_px, result[i].y_px};
    }
    const NearIndex known(last, confirmed, radius_px);
    std::vector<char> odd(n, 0);
    // Only a track that moved away from its start can have been drawn onto another minimum.
    std::vector<std::size_t> moved;
    for (std::size_t i = 0; i < n; ++i) {
      if (confirmed[i] && (now[i] - start[i]).norm() > s.params.neighbour_retry_px) {
        moved.push_back(i);
      }
    }
    const int moved_workers = workers_for(moved.size(), kMotionsForTwo, s.threads);
    parallel_for(moved.size(), moved_workers, [&](std::size_t r) {
      const std::size_t i = moved[r];
      Eigen::Vector2d p;
      odd[i] = neighbours_motion(last, now, known, i, last[i], radius_px, p) &&
               (now[i] - p).norm() > agree_px;
    });
    std::vector<std::size_t> suspect;
    std::vector<char> agreeing(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      if (odd[i]) suspect.push_back(i);
      agreeing[i] = confirmed[i] && !odd[i];
    }
    const NearIndex others(last, agreeing, radius_px);
    const int suspect_workers = workers_for(suspect.size(), kAlignmentsForTwo, s.threads);
    parallel_for(suspect.size(), suspect_workers, [&](std::size_t r) {
      const std::size_t i = suspect[r];
      confirmed[i] = 0;
      Eigen::Vector2d p;
      if (!neighbours_motion(last, now, others, i, last[i], radius_px, p)) return;
      start[i] = p;
      confirmed[i] = try_align(i, result[i], true) &&
                     std::hypot(result[i].x_px - p.x(), result[i].y_px - p.y()) <= agree_px;
    });
    s.stats.steps += static_cast<long>(suspect.size());
  }
  for (std::size_t i = 0; i < n; ++i) {
    State::Live& l = *s.live[i];
    if (!confirmed[i]) {
      l.ended = true;
      continue;
    }
    l.track.x_px.push_back(result[i].x_px);
    l.track.y_px.push_back(result[i].y_px);
    l.linear = result[i].linear;
    l.track.gradient.push_back({l.linear(0, 0), l.linear(0, 1), l.linear(1, 0), l.linear(1, 1)});
  }
  // Ended tracks leave in place, the others keep their order: a frame where none ended moves
  // nothing. With a spacing, the tracks that crowd older ones end too (the live tracks are in the
  // order they started); the points kept are kept for the seeds below.
  std::optional<SpacedPoints> spaced;
  if (s.min_spacing_px > 0) spaced.emplace(s.width_px, s.height_px, s.min_spacing_px);
  std::size_t still = 0;
  for (std::size_t i = 0; i < s.live.size(); ++i) {
    const Track& t = s.live[i]->track;
    const bool crowding =
        !s.live[i]->ended && spaced && !spaced->add({t.x_px.back(), t.y_px.back()});
    if (s.live[i]->ended || crowding) {
      ++(crowding ? s.stats.thinned : s.stats.cut);
      s.ended.push_back(std::move(s.live[i]->track));
      continue;
    }
    if (still != i) s.live[still] = std::move(s.live[i]);
    ++still;
  }
  s.live.resize(still);
  // Seeds found on an earlier frame (a detector slower than the camera) where the skin is now:
  // each moved by the motion of the live tracks around it since that frame (neighbours_motion),
  // or by the whole view's where too few tracks are near. A seed on a landmark already tracked
  // then lands on that track, within the separation below, where the view's median motion alone
  // left it pixels off on a strain wave and started a second track on the same skin.
  // Copied only when they move: most frames bring none, or bring this frame's own.
  std::vector<Feature> carried;
  if (seeds_frame != frame && !found.empty()) {
    carried = found;
    const std::size_t live = s.live.size();
    std::vector<Eigen::Vector2d> then(live), at(live);
    std::vector<char> known(live, 0);
    for (std::size_t i = 0; i < live; ++i) {
      const Track& t = s.live[i]->track;
      const int k = seeds_frame - t.first_frame;
      if (k < 0) continue;
      then[i] = {t.x_px[static_cast<std::size_t>(k)], t.y_px[static_cast<std::size_t>(k)]};
      at[i] = {t.x_px.back(), t.y_px.back()};
      known[i] = 1;
    }
    Eigen::Vector2d view = Eigen::Vector2d::Zero();
    for (int f = seeds_frame + 1; f <= frame; ++f) {
      view += s.view_motion[static_cast<std::size_t>(f)];
    }
    const NearIndex index(then, known, radius_px);
    for (auto& seed : carried) {
      const Eigen::Vector2d from(seed.x_px, seed.y_px);
      Eigen::Vector2d to;
      if (!neighbours_motion(then, at, index, live, from, radius_px, to)) to = from + view;
      seed.x_px = to.x();
      seed.y_px = to.y();
    }
  }
  const std::vector<Feature>& given = carried.empty() ? found : carried;
  // With a spacing: the seeds clear of the live tracks and of the seeds kept before them.
  std::vector<Feature> clear_of_others;
  if (spaced) {
    for (const Feature& f : given) {
      if (spaced->add({f.x_px, f.y_px})) clear_of_others.push_back(f);
    }
  }
  const std::vector<Feature>& seeds = spaced ? clear_of_others : given;
  // New tracks only where no live track is: one landmark, one track.
  const double min_separation_px = 0.5 * s.max_offset_px;
  const std::size_t tracked = s.live.size();
  // None for a frame without seeds.
  std::vector<Eigen::Vector2d> live_at(seeds.empty() ? 0 : tracked);
  for (std::size_t i = 0; i < live_at.size(); ++i) {
    live_at[i] = {s.live[i]->track.x_px.back(), s.live[i]->track.y_px.back()};
  }
  // Cells of a few tracks each: the separation itself is a couple of pixels.
  constexpr double kSeedCellPx = 16;
  const NearIndex live_near(live_at, std::vector<char>(live_at.size(), 1),
                            std::max(min_separation_px, kSeedCellPx));
  std::vector<std::unique_ptr<State::Live>> started(seeds.size());
  std::vector<char> ok(seeds.size(), 0);
  const int seed_workers = workers_for(seeds.size(), kAlignmentsForTwo, s.threads);
  parallel_for(seeds.size(), seed_workers, [&](std::size_t j) {
    const Feature& f = seeds[j];
    bool taken = false;
    live_near.for_each_near({f.x_px, f.y_px}, min_separation_px, [&](std::size_t k) {
      const Eigen::Vector2d& p = live_at[k];
      taken = taken || std::hypot(p.x() - f.x_px, p.y() - f.y_px) < min_separation_px;
    });
    if (taken) return;
    started[j] = std::make_unique<State::Live>();
    State::Live& l = *started[j];
    if (!make_reference(s.smooth, f.x_px, f.y_px, s.half_side, s.room_px, l.reference)) return;
    l.track.type = f.type;
    l.track.first_frame = frame;
    l.track.x_px = {f.x_px};
    l.track.y_px = {f.y_px};
    l.track.gradient = {{1.0, 0.0, 0.0, 1.0}};
    ok[j] = 1;
  });
  for (std::size_t j = 0; j < seeds.size(); ++j) {
    if (!ok[j]) continue;
    started[j]->track.id = s.next_id++;
    s.live.push_back(std::move(started[j]));
  }
}

namespace {

// The second moment along one axis of a reference window's weights (px^2): Gaussian of sigma
// half_side over offsets -half_side..half_side.
double window_moment_px2(int half_side) {
  double sw = 0, swu2 = 0;
  for (int u = -half_side; u <= half_side; ++u) {
    const double w = std::exp(-0.5 * u * u / (double(half_side) * half_side));
    sw += w;
    swu2 += w * u * u;
  }
  return swu2 / sw;
}

// An affine window aligned to skin whose motion is curved across it finds the weighted mean of
// that motion, not the motion at its centre: position + (M / 2) (laplacian of the map from the
// reference), with M the weights' second moment. On a strain wave this shrinks the measured
// strain in proportion to the true one (about 7 % for a 3 mm wave and a 0.7 mm window). The
// laplacian at each track and frame comes from a weighted quadratic fit of the positions of the
// tracks around it (those alive in its reference frame and in this one) against their
// positions in the reference frame; each correction is limited to max_px. The window's
// deformation gradient (Track::gradient) is the weighted mean of the gradient over the window in
// the same way: the same fit of the neighbours' gradients (from the track's reference frame on)
// corrects it, each entry limited to max_px over the weights' radius of gyration. On the 8 %
// wave (tuning prints 01 / 07, 0.7 mm windows) that took the strain error, with the gradients'
// share blended in, from 0.00050 / 0.00052 to 0.00045 / 0.00048, and at 25 mm/s from 0.00163 /
// 0.00180 to 0.00150 / 0.00169.
// A track's position in frame f, where it has one.
bool position_in_frame(const Track& t, int f, Eigen::Vector2d& p) {
  const int k = f - t.first_frame;
  if (k < 0 || k >= static_cast<int>(t.x_px.size())) return false;
  p = {t.x_px[static_cast<std::size_t>(k)], t.y_px[static_cast<std::size_t>(k)]};
  return true;
}

// One track's fit of its neighbours' motion from its reference frame: the neighbours (at most
// kNearest within the radius, nearest first), their rows of the weighted quadratic fit and
// their weights, and the laplacian's weights on their positions, made again only when the set
// of neighbours alive changes.
class CurvatureFit {
 public:
  // 16 / 24 / 32 nearest on tuning print 02: fast scene 0.00146 / 0.00142 / 0.00142, 4 % bump
  // correlation 0.981 / 0.983 / 0.983 (0.984 uncorrected).
  static constexpr std::size_t kNearest = 32;
  static constexpr std::size_t kFewest = 8;
  using Near = std::tuple<double, std::size_t, Eigen::Vector2d>;  // distance^2, index, position

  CurvatureFit() = default;
  // `near`: the tracks within radius_px of `centre` in the reference frame, in any order.
  CurvatureFit(const Eigen::Vector2d& centre, std::vector<Near> near, double radius_px)
      : scale_(radius_px / 2) {
    const auto by_distance = [](const auto& a, const auto& b) {
      return std::tie(std::get<0>(a), std::get<1>(a)) < std::tie(std::get<0>(b), std::get<1>(b));
    };
    std::sort(near.begin(), near.end(), by_distance);
    if (near.size() > kNearest) near.resize(kNearest);
    for (const auto& n : near) {
      neighbours_.push_back(std::get<1>(n));
      const Eigen::Vector2d o = (std::get<2>(n) - centre) / scale_;
      weights_.push_back(std::exp(-0.5 * o.squaredNorm()));
      Vector6 row;
      row << 1, o.x(), o.y(), o.x() * o.x(), o.x() * o.y(), o.y() * o.y();
      rows_.push_back(row);
    }
    alpha_.assign(near.size(), 0.0);
  }

  // The neighbours' indices as given, nearest first.
  const std::vector<std::size_t>& neighbours() const { return neighbours_; }
  bool usable() const { return neighbours_.size() >= kFewest; }

  // The laplacian's weights for the neighbours `alive` in a frame (the fit is linear in the
  // positions: the laplacian is sum_j alpha_j x position_j); false where too few are alive or
  // the fit fails.
  bool weigh(const std::vector<char>& alive) {
    std::size_t used = 0;
    for (const char a : alive) used += a ? 1 : 0;
    if (used < kFewest) return false;
    if (alive != alive_before_) {
      alive_before_ = alive;
      Matrix6 a = Matrix6::Zero();
      for (std::size_t n = 0; n < rows_.size(); ++n) {
        if (alive[n]) a += weights_[n] * rows_[n] * rows_[n].transpose();
      }
      Vector6 laplacian_of_coefficients = Vector6::Zero();
      laplacian_of_coefficients(3) = laplacian_of_coefficients(5) = 2 / (scale_ * scale_);
      const Eigen::LDLT<Matrix6> ldlt(a);
      const Vector6 g = ldlt.solve(laplacian_of_coefficients);
      fits_ = ldlt.info() == Eigen::Success && g.allFinite();
      for (std::size_t n = 0; n < rows_.size(); ++n) {
        alpha_[n] = alive[n] ? weights_[n] * g.dot(rows_[n]) : 0.0;
      }
    }
    return fits_;
  }
  const std::vector<double>& alpha() const { return alpha_; }

 private:
  double scale_ = 1;
  std::vector<std::size_t> neighbours_;
  std::vector<Vector6> rows_;
  std::vector<double> weights_;
  std::vector<char> alive_before_;
  std::vector<double> alpha_;
  bool fits_ = false;
};

// The correction of a position, -(M / 2) (laplacian of the neighbours' positions `to` by the
// fit's weights), limited to max_px; zero where it is not finite.
Eigen::Vector2d position_correction(const CurvatureFit& fit, const std::vector<char>& alive,
                                    const std::vector<Eigen::Vector2d>& to, double moment_px2,
                                    double max_px, bool& finite) {
  Eigen::Vector2d laplacian = Eigen::Vector2d::Zero();
  for (std::size_t n = 0; n < to.size(); ++n) {
    if (alive[n]) laplacian += fit.alpha()[n] * to[n];
  }
  Eigen::Vector2d dc = -0.5 * moment_px2 * laplacian;
  finite = dc.allFinite();
  if (!finite) return Eigen::Vector2d::Zero();
  if (dc.norm() > max_px) dc *= max_px / dc.norm();
  return dc;
}

// The same for the window's gradient: the neighbours' gradients (`gradient(n)`, from the
// reference frame on through `from_reference`), each entry limited to max_px over the weights'
// radius of gyration.
template <class GradientOf>
std::optional<Eigen::Matrix2d> gradient_correction_of(
    const CurvatureFit& fit, const std::vector<char>& alive,
    const std::vector<Eigen::Matrix2d>& from_reference, GradientOf&& gradient, double moment_px2,
    double max_px) {
  Eigen::Matrix2d lg = Eigen::Matrix2d::Zero();
  for (std::size_t n = 0; n < from_reference.size(); ++n) {
    if (alive[n]) lg += fit.alpha()[n] * gradient(n) * from_reference[n];
  }
  Eigen::Matrix2d dg = -0.5 * moment_px2 * lg;
  const double most = max_px / std::sqrt(moment_px2);
  if (!dg.allFinite()) return std::nullopt;
  if (dg.cwiseAbs().maxCoeff() > most) dg *= most / dg.cwiseAbs().maxCoeff();
  return dg;
}

void correct_window_curvature(std::vector<Track>& tracks, double moment_px2, double radius_px,
                              double max_px, int threads) {
  const auto at = position_in_frame;
  // The tracks alive in each frame a track starts in, binned by where they are there: a
  // track's neighbours come from the cells around it, not a pass over every track.
  struct AliveIn {
    std::vector<Eigen::Vector2d> at;
    NearIndex near;
  };
  std::map<int, AliveIn> alive_in;
  for (const Track& t : tracks) {
    const int frame = t.first_frame;
    if (alive_in.count(frame)) continue;
    std::vector<Eigen::Vector2d> positions(tracks.size());
    std::vector<char> alive(tracks.size(), 0);
    for (std::size_t j = 0; j < tracks.size(); ++j) alive[j] = at(tracks[j], frame, positions[j]);
    NearIndex near(positions, alive, radius_px);
    alive_in.emplace(frame, AliveIn{std::move(positions), std::move(near)});
  }
  std::vector<std::vector<Eigen::Vector2d>> correction(tracks.size());
  std::vector<std::vector<Eigen::Matrix2d>> gradient_correction(tracks.size());
  parallel_for(tracks.size(), worker_count(threads), [&](std::size_t i) {
    const Track& t = tracks[i];
    const int first = t.first_frame;
    const Eigen::Vector2d centre(t.x_px[0], t.y_px[0]);
    std::vector<CurvatureFit::Near> near;
    const AliveIn& in_first = alive_in.at(first);
    in_first.near.for_each_near(centre, radius_px, [&](std::size_t j) {
      const Eigen::Vector2d& p = in_first.at[j];
      const double d2 = (p - centre).squaredNorm();
      if (d2 <= radius_px * radius_px) near.emplace_back(d2, j, p);
    });
    CurvatureFit fit(centre, std::move(near), radius_px);
    const std::vector<std::size_t>& neighbours = fit.neighbours();
    auto& out = correction[i];
    out.assign(t.x_px.size(), Eigen::Vector2d::Zero());
    if (!fit.usable()) return;
    // Each neighbour's gradients from the track's reference frame on, where all carry them.
    bool gradients = has_gradients(t);
    std::vector<Eigen::Matrix2d> from_reference(neighbours.size());
    for (std::size_t n = 0; n < neighbours.size() && gradients; ++n) {
      const Track& b = tracks[neighbours[n]];
      gradients = has_gradients(b) && std::abs(gradient_at(b, first).determinant()) > 1e-6;
      if (gradients) from_reference[n] = gradient_at(b, first).inverse();
    }
    auto& gout = gradient_correction[i];
    if (gradients) gout.assign(t.x_px.size(), Eigen::Matrix2d::Zero());
    std::vector<char> alive(neighbours.size(), 0);
    std::vector<Eigen::Vector2d> to(neighbours.size());
    for (std::size_t k = 1; k < t.x_px.size(); ++k) {
      const int f = first + static_cast<int>(k);
      for (std::size_t n = 0; n < neighbours.size(); ++n) {
        alive[n] = at(tracks[neighbours[n]], f, to[n]);
      }
      if (!fit.weigh(alive)) continue;
      bool finite = false;
      const Eigen::Vector2d dc = position_correction(fit, alive, to, moment_px2, max_px, finite);
      if (!finite) continue;
      out[k] = dc;
      if (!gradients) continue;
      const auto dg = gradient_correction_of(
          fit, alive, from_reference,
          [&](std::size_t n) { return gradient_at(tracks[neighbours[n]], f); }, moment_px2, max_px);
      if (dg) gout[k] = *dg;
    }
  });
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    if (gradient_correction[i].empty()) continue;
    for (std::size_t k = 0; k < tracks[i].gradient.size(); ++k) {
      const Eigen::Matrix2d& d = gradient_correction[i][k];
      auto& g = tracks[i].gradient[k];
      g = {g[0] + d(0, 0), g[1] + d(0, 1), g[2] + d(1, 0), g[3] + d(1, 1)};
    }
  }
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    for (std::size_t k = 0; k < tracks[i].x_px.size(); ++k) {
      tracks[i].x_px[k] += correction[i][k].x();
      tracks[i].y_px[k] += correction[i][k].y();
    }
  }
}

}  // namespace

namespace {

// The shortest track kept. Skin that slides through the view stays in it for the view's extent
// along the motion over the speed: a track cannot be longer, and one that must cover most of
// that time is kept only where it entered at the very edge. Half of it, at least 3 frames (two
// steps, so that a track's own motion is checked once), and never more than the still contact's.
int shortest_track_for(const std::vector<Eigen::Vector2d>& view_motion, double sliding_px,
                       int width_px, int height_px, int still_min_frames, RefineStats& stats) {
  std::vector<double> speeds;
  for (std::size_t f = 1; f < view_motion.size(); ++f) speeds.push_back(view_motion[f].norm());
  stats.view_motion_px = speeds.empty() ? 0.0 : median(speeds);
  stats.min_frames = still_min_frames;
  stats.frames_in_view = 0;
  if (!(stats.view_motion_px > sliding_px)) return stats.min_frames;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t f = 1; f < view_motion.size(); ++f) mean += view_motion[f];
  mean /= static_cast<double>(view_motion.size() - 1);
  // The view's extent along the mean motion's direction.
  const Eigen::Vector2d dir =
      mean.norm() > 0 ? Eigen::Vector2d(mean / mean.norm()) : Eigen::Vector2d::UnitX();
  const double extent = std::abs(dir.x()) * width_px + std::abs(dir.y()) * height_px;
  stats.frames_in_view = extent / stats.view_motion_px;
  stats.min_frames = std::min(still_min_frames,
                              std::max(3, static_cast<int>(std::floor(stats.frames_in_view / 2))));
  return stats.min_frames;
}

}  // namespace

// A live track's curvature fit for last_step(), made on the first step it is seen in (that
// step's first frame its reference): the neighbours by id, and their gradients there inverted.
struct AlignmentTracker::State::StepFit {
  CurvatureFit fit;
  std::vector<std::int32_t> ids;
  std::vector<Eigen::Matrix2d> from_reference;  // empty: no gradient correction
};

std::vector<Track> AlignmentTracker::last_step() {
  State& s = *state_;
  const int before = s.frames - 2, last = s.frames - 1;
  std::vector<Track> steps;
  steps.reserve(s.live.size());
  for (const auto& l : s.live) {
    const Track& t = l->track;
    const std::size_t k = t.x_px.size();
    if (k < 2 || t.last_frame() != last) continue;
    Track step;
    step.id = t.id;
    step.type = t.type;
    step.first_frame = before;
    step.x_px = {t.x_px[k - 2], t.x_px[k - 1]};
    step.y_px = {t.y_px[k - 2], t.y_px[k - 1]};
    if (has_gradients(t)) step.gradient = {t.gradient[k - 2], t.gradient[k - 1]};
    steps.push_back(std::move(step));
  }
  if (!s.params.curvature_correction) return steps;

  // As correct_window_curvature corrects whole tracks, each from its reference frame, with one
  // fit per track kept from frame to frame (a fit is most of the work, and a frame's budget at
  // 240 Hz is 4 ms).
  const double radius_px = s.params.neighbour_radius_mm * s.px_per_mm;
  const double moment_px2 = window_moment_px2(s.half_side);
  constexpr double kMaxPx = 0.5;
  const auto at = position_in_frame;
  std::unordered_map<std::int32_t, const Track*> by_id;
  for (const auto& l : s.live) by_id.emplace(l->track.id, &l->track);
  // Fits of the tracks seen for the first time, from the live tracks in this step's first frame.
  std::vector<std::size_t> unfitted;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    if (!s.step_fits.count(steps[i].id)) unfitted.push_back(i);
  }
  if (!unfitted.empty()) {
    std::vector<Eigen::Vector2d> positions(s.live.size());
    std::vector<char> alive(s.live.size(), 0);
    for (std::size_t j = 0; j < s.live.size(); ++j) {
      alive[j] = at(s.live[j]->track, before, positions[j]);
    }
    const NearIndex index(positions, alive, radius_px);
    std::vector<std::unique_ptr<State::StepFit>> made(unfitted.size());
    // Each fit reads the live tracks only: in parallel, stored in order after.
    parallel_for(unfitted.size(), workers_for(unfitted.size(), kMotionsForTwo, s.threads),
                 [&](std::size_t u) {
                   const Track& t = steps[unfitted[u]];
                   const Eigen::Vector2d centre(t.x_px[0], t.y_px[0]);
                   std::vector<CurvatureFit::Near> near;
                   index.for_each_near(centre, radius_px, [&](std::size_t j) {
                     const double d2 = (positions[j] - centre).squaredNorm();
                     if (d2 <= radius_px * radius_px) near.emplace_back(d2, j, positions[j]);
                   });
                   auto fit = std::make_unique<State::StepFit>();
                   fit->fit = CurvatureFit(centre, std::move(near), radius_px);
                   bool gradients = has_gradients(t);
                   for (const std::size_t j : fit->fit.neighbours()) {
                     const Track& b = s.live[j]->track;
                     fit->ids.push_back(b.id);
                     gradients = gradients && has_gradients(b) &&
                                 std::abs(gradient_at(b, before).determinant()) > 1e-6;
                     if (gradients) fit->from_reference.push_back(gradient_at(b, before).inverse());
                   }
                   if (!gradients) fit->from_reference.clear();
                   made[u] = std::move(fit);
                 });
    for (std::size_t u = 0; u < unfitted.size(); ++u) {
      s.step_fits.emplace(steps[unfitted[u]].id, std::move(made[u]));
    }
  }
  std::vector<State::StepFit*> fits(steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) fits[i] = s.step_fits.at(steps[i].id).get();
  // Each step's correction changes its own step and fit alone.
  parallel_for(
      steps.size(), workers_for(steps.size(), kMotionsForTwo, s.threads), [&](std::size_t i) {
        Track& step = steps[i];
        State::StepFit* fit = fits[i];
        const std::size_t n_near = fit->ids.size();
        std::vector<char> alive(n_near, 0);
        std::vector<const Track*> near(n_near, nullptr);
        std::array<std::vector<Eigen::Vector2d>, 2> to{std::vector<Eigen::Vector2d>(n_near),
                                                       std::vector<Eigen::Vector2d>(n_near)};
        for (std::size_t n = 0; n < n_near; ++n) {
          const auto it = by_id.find(fit->ids[n]);
          if (it == by_id.end()) continue;
          near[n] = it->second;
          alive[n] = at(*near[n], before, to[0][n]) && at(*near[n], last, to[1][n]);
        }
        if (fit->fit.usable() && fit->fit.weigh(alive)) {
          for (std::size_t k = 0; k < 2; ++k) {
            const int f = k == 0 ? before : last;
            bool finite = false;
            const Eigen::Vector2d dc =
                position_correction(fit->fit, alive, to[k], moment_px2, kMaxPx, finite);
            if (!finite) continue;
            step.x_px[k] += dc.x();
            step.y_px[k] += dc.y();
            if (fit->from_reference.empty() || step.gradient.size() != 2) continue;
            const auto dg = gradient_correction_of(
                fit->fit, alive, fit->from_reference,
                [&](std::size_t n) { return gradient_at(*near[n], f); }, moment_px2, kMaxPx);
            if (!dg) continue;
            auto& g = step.gradient[k];
            g = {g[0] + (*dg)(0, 0), g[1] + (*dg)(0, 1), g[2] + (*dg)(1, 0), g[3] + (*dg)(1, 1)};
          }
        }
      });
  std::unordered_map<std::int32_t, std::unique_ptr<State::StepFit>> kept;
  for (const auto& step : steps) kept.emplace(step.id, std::move(s.step_fits.at(step.id)));
  // Tracks that ended take their fits with them.
  s.step_fits = std::move(kept);
  return steps;
}

std::vector<Track> AlignmentTracker::finish(RefineStats* stats) {
  State& s = *state_;
  std::vector<Track> all = std::move(s.ended);
  for (auto& l : s.live) all.push_back(std::move(l->track));
  s.live.clear();
  s.ended.clear();
  // Ended tracks were set aside as they ended: back in the order they started (their ids).
  std::sort(all.begin(), all.end(), [](const Track& a, const Track& b) { return a.id < b.id; });
  const int min_frames = shortest_track_for(s.view_motion, s.max_offset_px, s.width_px, s.height_px,
                                            s.params.min_frames, s.stats);
  s.view_motion.clear();
  std::vector<Track> kept;
  for (auto& t : all) {
    if (static_cast<int>(t.x_px.size()) < min_frames) {
      ++s.stats.dropped;
      continue;
    }
    t.id = static_cast<std::int32_t>(kept.size());
    kept.push_back(std::move(t));
  }
  if (s.params.curvature_correction) {
    correct_window_curvature(kept, window_moment_px2(s.half_side),
                             s.params.neighbour_radius_mm * s.px_per_mm, 0.5, s.threads);
  }
  if (stats) *stats = s.stats;
  s.stats = {};
  return kept;
}

}  // namespace tactile::capture
