#include "tracking/align_rows.hpp"

#include <algorithm>
#include <cmath>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define TACTILE_VECTOR_ROWS 1
#endif

namespace tactile::capture {

void add_row_sums(const FloatRows& image, const RowSpan& row, RowSums& s) {
  double x = row.x0 + row.first * row.dx, y = row.y0 + row.first * row.dy;
  for (int k = row.first; k < row.cols; ++k, x += row.dx, y += row.dy) {
    s.add(sample_inside(image, x, y), row.weight[k], row.grey[k], row.gx[k], row.gy[k],
          row.ox0 + k);
  }
}

void add_window_sums(const FloatRows& image, const WindowSpan& window, WindowSampleSums& s) {
  const auto cols = static_cast<std::size_t>(window.cols);
  for (int r = 0; r < window.rows; r += window.row_step) {
    const std::size_t row0 = static_cast<std::size_t>(r) * cols;
    const RowSpan row{window.weight + row0,
                      window.grey + row0,
                      window.gx + row0,
                      window.gy + row0,
                      0,
                      window.cols,
                      window.x0 + r * window.rx,
                      window.y0 + r * window.ry,
                      window.dx,
                      window.dy,
                      window.ox0};
    RowSums rs;
    add_row_sums(image, row, rs);
    const double oy = window.oy0 + r;
    s.i += rs.i;
    s.ii += rs.ii;
    s.it += rs.it;
    s.a += rs.a;
    s.a_ox += rs.a_ox;
    s.a_oy += rs.a * oy;
    s.c += rs.c;
    s.c_ox += rs.c_ox;
    s.c_oy += rs.c * oy;
  }
}

#ifdef TACTILE_VECTOR_ROWS

namespace {

#pragma GCC push_options
#pragma GCC target("avx2,fma")
namespace avx2 {
#define TACTILE_ROWS_BY_PERMUTE 0
#include "tracking/align_rows_simd.inc"
#undef TACTILE_ROWS_BY_PERMUTE
}  // namespace avx2
#pragma GCC pop_options

#pragma GCC push_options
#pragma GCC target("avx2,fma,avx512f,avx512vl")
// GCC 12 warns falsely (-Wmaybe-uninitialized) inside avx512fintrin.h, where its extractions and
// conversions start from an _mm512_undefined_* value; the warning is attributed to the
// header's lines, so it is silenced for this version only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
namespace avx512 {
#define TACTILE_ROWS_BY_PERMUTE 1
#include "tracking/align_rows_simd.inc"
#undef TACTILE_ROWS_BY_PERMUTE
}  // namespace avx512
#pragma GCC diagnostic pop
#pragma GCC pop_options

}  // namespace

namespace {

// Asked at every alignment step: a couple of loads of the processor's feature bits.
RowSumsVersion fastest_here() {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    return RowSumsVersion::plain;
  }
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) {
    return RowSumsVersion::avx512;
  }
  return RowSumsVersion::avx2;
}

}  // namespace

std::vector<RowSumsVersion> row_sums_versions_here() {
  std::vector<RowSumsVersion> here{RowSumsVersion::plain};
  if (fastest_here() != RowSumsVersion::plain) here.push_back(RowSumsVersion::avx2);
  if (fastest_here() == RowSumsVersion::avx512) here.push_back(RowSumsVersion::avx512);
  return here;
}

namespace {

// A computation built three times: with AVX-512, with AVX2 and FMA, and plain.
template <typename Span, typename Sums>
using SumsBuild = void (*)(const FloatRows&, const Span&, Sums&);

template <typename Span, typename Sums>
void add_sums_by(RowSumsVersion version, SumsBuild<Span, Sums> avx512_build,
                 SumsBuild<Span, Sums> avx2_build, SumsBuild<Span, Sums> plain_build,
                 const FloatRows& image, const Span& span, Sums& s) {
  switch (version) {
    case RowSumsVersion::avx512:
      avx512_build(image, span, s);
      return;
    case RowSumsVersion::avx2:
      avx2_build(image, span, s);
      return;
    case RowSumsVersion::plain:
      break;
  }
  plain_build(image, span, s);
}

}  // namespace

void add_row_sums_by(RowSumsVersion version, const FloatRows& image, const RowSpan& row,
                     RowSums& s) {
  add_sums_by(version, avx512::add_row_sums_simd, avx2::add_row_sums_simd, add_row_sums, image, row,
              s);
}

void add_window_sums_by(RowSumsVersion version, const FloatRows& image, const WindowSpan& window,
                        WindowSampleSums& s) {
  add_sums_by(version, avx512::add_window_sums_simd, avx2::add_window_sums_simd, add_window_sums,
              image, window, s);
}

void add_window_sums_vector(const FloatRows& image, const WindowSpan& window, WindowSampleSums& s) {
  add_window_sums_by(fastest_here(), image, window, s);
}

void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s) {
  add_row_sums_by(fastest_here(), image, row, s);
}

#else

std::vector<RowSumsVersion> row_sums_versions_here() {
  return {RowSumsVersion::plain};
}

void add_row_sums_by(RowSumsVersion, const FloatRows& image, const RowSpan& row, RowSums& s) {
  add_row_sums(image, row, s);
}

void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s) {
  add_row_sums(image, row, s);
}

void add_window_sums_by(RowSumsVersion, const FloatRows& image, const WindowSpan& window,
                        WindowSampleSums& s) {
  add_window_sums(image, window, s);
}

void add_window_sums_vector(const FloatRows& image, const WindowSpan& window, WindowSampleSums& s) {
  add_window_sums(image, window, s);
}

#endif

}  // namespace tactile::capture
