#pragma once
// The innermost loop of the track alignment (refine.cpp): bilinear samples of a frame along
// the rows of a warped reference window, and the sums one Gauss-Newton step needs from them, a
// row at a time (a window cut by the frame's border) or a whole window in one pass. Kept apart
// so that the vector versions can be tested against the plain one.

#include <cstddef>
#include <vector>

namespace tactile::capture {

// A single-channel float image's rows.
struct FloatRows {
  const float* data = nullptr;
  std::size_t stride = 0;  // floats from one row to the next
  int cols = 0, rows = 0;
};

// Bilinear interpolation in double precision (OpenCV's warps round sample positions to 1/32
// pixel, and the alignment is after hundredths of a pixel), for a position known to be inside
// [0, cols - 1) x [0, rows - 1).
inline double sample_inside(const FloatRows& image, double x, double y) {
  // Truncation is the floor for these positions (std::floor is a library call on the baseline
  // x86-64 target, and sampling is most of an alignment's time).
  const int ix = static_cast<int>(x), iy = static_cast<int>(y);
  const double ax = x - ix, ay = y - iy;
  const float* r0 = image.data + static_cast<std::size_t>(iy) * image.stride + ix;
  const float* r1 = r0 + image.stride;
  return (1 - ay) * ((1 - ax) * r0[0] + ax * r0[1]) + ay * ((1 - ax) * r1[0] + ax * r1[1]);
}

// As sample_inside, for any position; false outside the image.
inline bool sample(const FloatRows& image, double x, double y, double& value) {
  if (!(x >= 0 && y >= 0)) return false;
  const int ix = static_cast<int>(x), iy = static_cast<int>(y);
  if (ix + 1 >= image.cols || iy + 1 >= image.rows) return false;
  value = sample_inside(image, x, y);
  return true;
}

// Sums over one row of the window for one alignment step: of weight x sample (i), x sample^2
// (ii), x reference grey (it), and of weight x sample x gradient along x (a) and y (c), alone
// and times the offset along x (a_ox, c_ox).
struct RowSums {
  double i = 0, ii = 0, it = 0, a = 0, a_ox = 0, c = 0, c_ox = 0;

  // One sample v where the reference has weight w, grey level g and gradient (gx, gy), at an
  // offset ox along x.
  void add(double v, double w, double g, double gx, double gy, double ox) {
    const double wv = w * v;
    i += wv;
    ii += wv * v;
    it += wv * g;
    const double ga = wv * gx, gc = wv * gy;
    a += ga;
    a_ox += ga * ox;
    c += gc;
    c_ox += gc * ox;
  }
};

// One row of the reference window (weights, grey levels and gradients, `cols` of each) and
// where its pixels are seen: pixel k at (x0 + k dx, y0 + k dy), every one inside
// [0, cols - 1) x [0, rows - 1) of the frame, with an offset along x of ox0 + k.
struct RowSpan {
  const float *weight, *grey, *gx, *gy;
  int first, cols;  // pixels first..cols-1 are summed
  double x0, y0, dx, dy, ox0;
};

// Adds the row's sums to s, in double precision.
void add_row_sums(const FloatRows& image, const RowSpan& row, RowSums& s);

// A whole window: rows 0, row_step, 2 row_step, ... below `rows` of `cols` pixels each (weights,
// grey levels and gradients row after row, `cols` to a row), pixel k of row r seen at
// (x0 + k dx + r rx, y0 + k dy + r ry), every one inside [0, cols - 1) x [0, rows - 1) of the
// frame, with offsets ox0 + k along x and oy0 + r along y.
struct WindowSpan {
  const float *weight, *grey, *gx, *gy;
  int cols, rows, row_step;
  double x0, y0, dx, dy, rx, ry, ox0, oy0;
};

// RowSums over a window, with the gradients' sums also times the offset along y (a_oy, c_oy).
struct WindowSampleSums {
  double i = 0, ii = 0, it = 0, a = 0, a_ox = 0, a_oy = 0, c = 0, c_ox = 0, c_oy = 0;
};

// Adds the window's sums to s: add_row_sums row by row.
void add_window_sums(const FloatRows& image, const WindowSpan& window, WindowSampleSums& s);

// The ways add_row_sums can run: the plain loop, eight samples at a time with AVX2 and FMA
// (each sample's two neighbours along x gathered as one pair; a row's last two to seven samples
// as one more group of eight with the rest left out), and the same with AVX-512, which takes the
// neighbours of eight samples that lie within 15 columns and two rows of the first (rows
// stretched by at most 1.8 and turned by at most 8 degrees) from contiguous loads of those rows by
// permutes instead of gathers.
enum class RowSumsVersion { plain, avx2, avx512 };

// The versions this machine runs, plain first and fastest last.
std::vector<RowSumsVersion> row_sums_versions_here();

// add_row_sums by one of row_sums_versions_here().
// Positions are taken relative to the row's first whole pixel, so single precision keeps them
// to about 4e-6 px; each row's sums are of at most a few dozen terms before they join the
// double-precision totals, so the vector versions agree with add_row_sums to about 1e-6
// relative.
void add_row_sums_by(RowSumsVersion version, const FloatRows& image, const RowSpan& row,
                     RowSums& s);

// add_window_sums by one of row_sums_versions_here(). The vector versions keep a window's sums
// in single precision for four rows at a time (a few dozen terms, as a row's in
// add_row_sums_by) and add them to double-precision totals after each four, so they agree with
// add_window_sums to about 1e-6 relative too.
void add_window_sums_by(RowSumsVersion version, const FloatRows& image, const WindowSpan& window,
                        WindowSampleSums& s);

// add_window_sums by the fastest version here.
void add_window_sums_vector(const FloatRows& image, const WindowSpan& window, WindowSampleSums& s);

// add_row_sums by the fastest version here.
void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s);

}  // namespace tactile::capture
