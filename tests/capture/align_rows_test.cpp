// The alignment's vector row sums against the plain double-precision loop they replace.

#include "tracking/align_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <type_traits>
#include <vector>

namespace tactile::capture {
namespace {

struct TestImage {
  std::vector<float> pixels;
  FloatRows rows;
};

// Random grey levels in rows padded as OpenCV may pad them; the buffer ends where the last row
// does, so that a read past it is one past the allocation.
TestImage random_image(std::mt19937& rng, int cols, int rows, std::size_t stride) {
  std::uniform_real_distribution<float> grey(0.f, 255.f);
  TestImage t;
  t.pixels.resize(stride * static_cast<std::size_t>(rows - 1) + static_cast<std::size_t>(cols));
  for (auto& p : t.pixels) p = grey(rng);
  t.rows = FloatRows{t.pixels.data(), stride, cols, rows};
  return t;
}

struct Reference {
  std::vector<float> weight, grey, gx, gy;
};

// The reference's n pixels seen from (x0, y0) on, (dx, dy) apart.
RowSpan span_of(const Reference& ref, int n, double x0, double y0, double dx, double dy,
                double ox0) {
  return {
      ref.weight.data(), ref.grey.data(), ref.gx.data(), ref.gy.data(), 0, n, x0, y0, dx, dy, ox0};
}

// The reference as a window of rows x cols pixels (see WindowSpan).
WindowSpan window_of(const Reference& ref, int cols, int rows, int row_step, double x0, double y0,
                     double dx, double dy, double rx, double ry, double ox0, double oy0) {
  return {ref.weight.data(),
          ref.grey.data(),
          ref.gx.data(),
          ref.gy.data(),
          cols,
          rows,
          row_step,
          x0,
          y0,
          dx,
          dy,
          rx,
          ry,
          ox0,
          oy0};
}

Reference random_reference(std::mt19937& rng, int n) {
  std::uniform_real_distribution<float> grey(0.f, 255.f), unit(-1.f, 1.f);
  Reference r;
  for (int k = 0; k < n; ++k) {
    r.weight.push_back(0.4f + 0.3f * (unit(rng) + 1.f));
    r.grey.push_back(grey(rng));
    r.gx.push_back(20.f * unit(rng));
    r.gy.push_back(20.f * unit(rng));
  }
  return r;
}

// Single precision loses about 1e-7 of the largest terms, which cancel in these sums: the
// tolerance is a few times that of the sum of the terms' magnitudes bounds (n samples, offsets up
// to 20 px).
bool near(double a, double b, double scale) {
  return std::abs(a - b) <= 5e-7 * scale;
}

template <class Sums>
void expect_same_sums(const Sums& vector, const Sums& plain, int n) {
  const double sample = n * 255.0, gradient = sample * 20, offset = gradient * 20;
  EXPECT_PRED3(near, vector.i, plain.i, sample);
  EXPECT_PRED3(near, vector.ii, plain.ii, sample * 255);
  EXPECT_PRED3(near, vector.it, plain.it, sample * 255);
  EXPECT_PRED3(near, vector.a, plain.a, gradient);
  EXPECT_PRED3(near, vector.a_ox, plain.a_ox, offset);
  EXPECT_PRED3(near, vector.c, plain.c, gradient);
  EXPECT_PRED3(near, vector.c_ox, plain.c_ox, offset);
  if constexpr (std::is_same_v<Sums, WindowSampleSums>) {
    EXPECT_PRED3(near, vector.a_oy, plain.a_oy, offset);
    EXPECT_PRED3(near, vector.c_oy, plain.c_oy, offset);
  }
}

// The same bits in every sum: what two vector versions give for one row or window.
template <class Sums>
void expect_same_bits(const Sums& sums, const Sums& first) {
  EXPECT_EQ(sums.i, first.i);
  EXPECT_EQ(sums.ii, first.ii);
  EXPECT_EQ(sums.it, first.it);
  EXPECT_EQ(sums.a, first.a);
  EXPECT_EQ(sums.a_ox, first.a_ox);
  EXPECT_EQ(sums.c, first.c);
  EXPECT_EQ(sums.c_ox, first.c_ox);
  if constexpr (std::is_same_v<Sums, WindowSampleSums>) {
    EXPECT_EQ(sums.a_oy, first.a_oy);
    EXPECT_EQ(sums.c_oy, first.c_oy);
  }
}

const char* name(RowSumsVersion v) {
  switch (v) {
    case RowSumsVersion::plain:
      return "plain";
    case RowSumsVersion::avx2:
      return "avx2";
    case RowSumsVersion::avx512:
      return "avx512";
  }
  return "?";
}

// Every version here (`add` fills a row's or a window's sums by one) near the plain loop's
// `plain` over `samples` samples, and the vector versions the same to the bit.
template <class Sums, class Add>
void expect_every_version_agrees(const Sums& plain, int samples, const Add& add) {
  std::vector<Sums> by_vector;
  for (const RowSumsVersion version : row_sums_versions_here()) {
    SCOPED_TRACE(name(version));
    Sums sums;
    add(version, sums);
    expect_same_sums(sums, plain, samples);
    if (version == RowSumsVersion::plain) continue;
    by_vector.push_back(sums);
    expect_same_bits(sums, by_vector.front());
  }
}

TEST(AlignRows, EveryVersionHereAgreesWithThePlainLoopAndTheVectorOnesToTheBit) {
  std::mt19937 rng(7);
  const TestImage image = random_image(rng, 80, 60, 83);
  const int n = 37;  // not a multiple of 8: the tail is summed too
  const Reference ref = random_reference(rng, n);
  std::uniform_real_distribution<double> step(-0.25, 0.25), unit(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    // A row turned and stretched by up to a quarter, starting at a fraction of a pixel: a
    // third turned by more than 8 degrees, a third by less (eight samples then span at most
    // two rows), and a third by less ending next to the image's last row and column, where
    // rows of 16 floats from a group's first sample would run past the buffer. A quarter of
    // them turned by under 3.7 degrees, where the AVX-512 version takes sixteen at once.
    const int kind = trial % 3;
    const double dx = 1 + step(rng),
                 dy = (kind == 0 ? step(rng) : 0.5 * step(rng)) * (trial % 4 == 3 ? 0.25 : 1);
    double x0 = 1.3 + 2 * unit(rng), y0 = 20 + 20 * unit(rng);
    if (kind == 2) {
      x0 = image.rows.cols - 1.01 - (n - 1) * dx - unit(rng);
      y0 = image.rows.rows - 1.01 - std::max(0.0, (n - 1) * dy) - 3 * unit(rng);
    }
    const RowSpan row = span_of(ref, n, x0, y0, dx, dy, -18.4);
    RowSums plain;
    add_row_sums(image.rows, row, plain);
    expect_every_version_agrees(plain, n, [&](RowSumsVersion version, RowSums& sums) {
      add_row_sums_by(version, image.rows, row, sums);
    });
  }
  for (const RowSumsVersion version : row_sums_versions_here()) {
    SCOPED_TRACE(name(version));
    // Starting part-way along the row sums only the rest.
    RowSums all, head_then_rest;
    const RowSpan row = span_of(ref, n, 2.5, 30.25, 1.1, 0.1, -18);
    add_row_sums(image.rows, row, all);
    RowSpan head = row, rest = row;
    head.cols = 11;
    rest.first = 11;
    add_row_sums_by(version, image.rows, head, head_then_rest);
    add_row_sums_by(version, image.rows, rest, head_then_rest);
    EXPECT_NEAR(head_then_rest.i, all.i, 5e-7 * n * 255.0);
    EXPECT_NEAR(head_then_rest.c_ox, all.c_ox, 5e-7 * n * 255.0 * 400);
  }
}

TEST(AlignRows, TheDefaultIsTheFastestVersionHere) {
  std::mt19937 rng(11);
  const TestImage image = random_image(rng, 80, 60, 80);
  const int n = 29;
  const Reference ref = random_reference(rng, n);
  const RowSpan row = span_of(ref, n, 3.7, 12.2, 1.03, 0.05, -14);
  RowSums fastest, vector;
  add_row_sums_by(row_sums_versions_here().back(), image.rows, row, fastest);
  add_row_sums_vector(image.rows, row, vector);
  // The same instructions in the same order give the same bits.
  EXPECT_EQ(vector.i, fastest.i);
  EXPECT_EQ(vector.c_ox, fastest.c_ox);
}

TEST(AlignRows, WindowSumsAreTheSumsOfTheirRows) {
  std::mt19937 rng(5);
  const TestImage image = random_image(rng, 90, 70, 93);
  const int cols = 13, rows = 9;
  const Reference ref = random_reference(rng, cols * rows);
  const WindowSpan w = window_of(ref, cols, rows, 2, 20.3, 30.6, 1.02, 0.07, -0.06, 0.98, -6, -4);
  WindowSampleSums sums;
  add_window_sums(image.rows, w, sums);
  // Sample by sample, rows 0, 2, 4, 6 and 8.
  double a_oy = 0, c = 0, ii = 0;
  for (int r = 0; r < rows; r += 2) {
    for (int k = 0; k < cols; ++k) {
      const auto q = static_cast<std::size_t>(r * cols + k);
      double v = 0;
      ASSERT_TRUE(sample(image.rows, w.x0 + k * w.dx + r * w.rx, w.y0 + k * w.dy + r * w.ry, v));
      a_oy += ref.weight[q] * v * ref.gx[q] * (w.oy0 + r);
      c += ref.weight[q] * v * ref.gy[q];
      ii += ref.weight[q] * v * v;
    }
  }
  EXPECT_NEAR(sums.a_oy, a_oy, 1e-9 * std::abs(a_oy) + 1e-6);
  EXPECT_NEAR(sums.c, c, 1e-9 * std::abs(c) + 1e-6);
  EXPECT_NEAR(sums.ii, ii, 1e-9 * ii);
}

// The vector versions differ only in how they fetch a sample's neighbours, so they also agree
// with each other to the bit: tracks do not depend on which of them the machine runs.
TEST(AlignRows, EveryVersionHereSumsWindowsAsThePlainLoopAndTheVectorOnesAgreeToTheBit) {
  std::mt19937 rng(3);
  const TestImage image = random_image(rng, 100, 80, 104);
  std::uniform_real_distribution<double> step(-0.25, 0.25), unit(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    // Windows of 39 x 39 (a whole number of groups and a partial one to a row) and 40 x 21,
    // every row or every other one, turned by more than 8 degrees, by less, and by less next
    // to the image's last row and column.
    const int cols = trial % 2 == 0 ? 39 : 40, rows = trial % 2 == 0 ? 39 : 21;
    const int row_step = trial % 4 < 2 ? 1 : 2;
    const Reference ref = random_reference(rng, cols * rows);
    const int kind = trial % 3;
    // A quarter of them turned by under 3.7 degrees, where the AVX-512 version takes sixteen
    // samples at once.
    const double dx = 1 + step(rng),
                 dy = (kind == 0 ? step(rng) : 0.5 * step(rng)) * (trial % 4 == 3 ? 0.25 : 1);
    const double rx = -dy, ry = dx;  // rows at right angles to the row, as in an alignment
    const double span_x = (cols - 1) * dx + (rows - 1) * rx;
    const double span_y = (cols - 1) * dy + (rows - 1) * ry;
    const double min_x = std::min({0.0, (cols - 1) * dx, (rows - 1) * rx, span_x});
    const double max_x = std::max({0.0, (cols - 1) * dx, (rows - 1) * rx, span_x});
    const double min_y = std::min({0.0, (cols - 1) * dy, (rows - 1) * ry, span_y});
    const double max_y = std::max({0.0, (cols - 1) * dy, (rows - 1) * ry, span_y});
    double x0 = 0.5 - min_x + 2 * unit(rng), y0 = 0.5 - min_y + 2 * unit(rng);
    if (kind == 2) {
      x0 = image.rows.cols - 1.01 - max_x - unit(rng);
      y0 = image.rows.rows - 1.01 - max_y - unit(rng);
    }
    const WindowSpan w = window_of(ref, cols, rows, row_step, x0, y0, dx, dy, rx, ry, -19.2, -18.7);
    WindowSampleSums plain;
    add_window_sums(image.rows, w, plain);
    expect_every_version_agrees(plain, cols * rows,
                                [&](RowSumsVersion version, WindowSampleSums& sums) {
                                  add_window_sums_by(version, image.rows, w, sums);
                                });
  }
}

}  // namespace
}  // namespace tactile::capture
