// The alignment's vector row sums against the plain double-precision loop they replace.

#include "tracking/align_rows.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace tactile::capture {
namespace {

TEST(AlignRows, VectorSumsAgreeWithThePlainLoop) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> grey(0.f, 255.f);
  const int cols = 80, rows = 60;
  const std::size_t stride = 83;  // rows padded, as OpenCV may
  std::vector<float> pixels(stride * rows);
  for (auto& p : pixels) p = grey(rng);
  const FloatRows image{pixels.data(), stride, cols, rows};
  const int n = 37;  // not a multiple of 8: the tail is summed too
  std::vector<float> weight(n), ref(n), gx(n), gy(n);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  for (int k = 0; k < n; ++k) {
    weight[k] = 0.4f + 0.3f * (unit(rng) + 1.f);
    ref[k] = grey(rng);
    gx[k] = 20.f * unit(rng);
    gy[k] = 20.f * unit(rng);
  }
  std::uniform_real_distribution<double> step(-0.25, 0.25);
  for (int trial = 0; trial < 50; ++trial) {
    // A row turned and stretched by up to a quarter, starting at a fraction of a pixel.
    const double dx = 1 + step(rng), dy = step(rng);
    const double x0 = 1.3 + 4 * (step(rng) + 0.25), y0 = 20 + 40 * (step(rng) + 0.25);
    const RowSpan row{weight.data(), ref.data(), gx.data(), gy.data(), 0, n, x0, y0, dx, dy, -18.4};
    RowSums plain, vector;
    add_row_sums(image, row, plain);
    add_row_sums_vector(image, row, vector);
    // Single precision loses about 1e-7 of the largest terms, which cancel in these sums: the
    // tolerance is a few times that of the sum of the terms' magnitudes bounds.
    const double sample = n * 255.0, gradient = sample * 20, offset = gradient * 20;
    auto near = [](double a, double b, double scale) { return std::abs(a - b) <= 5e-7 * scale; };
    EXPECT_PRED3(near, vector.i, plain.i, sample);
    EXPECT_PRED3(near, vector.ii, plain.ii, sample * 255);
    EXPECT_PRED3(near, vector.it, plain.it, sample * 255);
    EXPECT_PRED3(near, vector.a, plain.a, gradient);
    EXPECT_PRED3(near, vector.a_ox, plain.a_ox, offset);
    EXPECT_PRED3(near, vector.c, plain.c, gradient);
    EXPECT_PRED3(near, vector.c_ox, plain.c_ox, offset);
  }
  // Starting part-way along the row sums only the rest.
  RowSums all, head_then_rest;
  const RowSpan row{weight.data(), ref.data(), gx.data(), gy.data(), 0,  n,
                    2.5,           30.25,      1.1,       0.1,       -18};
  add_row_sums(image, row, all);
  RowSpan head = row, rest = row;
  head.cols = 11;
  rest.first = 11;
  add_row_sums_vector(image, head, head_then_rest);
  add_row_sums_vector(image, rest, head_then_rest);
  EXPECT_NEAR(head_then_rest.i, all.i, 5e-7 * n * 255.0);
  EXPECT_NEAR(head_then_rest.c_ox, all.c_ox, 5e-7 * n * 255.0 * 400);
}

}  // namespace
}  // namespace tactile::capture
