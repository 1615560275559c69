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
namespace avx512 {
#define TACTILE_ROWS_BY_PERMUTE 1
#include "tracking/align_rows_simd.inc"
#undef TACTILE_ROWS_BY_PERMUTE
}  // namespace avx512
#pragma GCC pop_options

}  // namespace

std::vector<RowSumsVersion> row_sums_versions_here() {
  std::vector<RowSumsVersion> here{RowSumsVersion::plain};
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) {
    here.push_back(RowSumsVersion::avx2);
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) {
      here.push_back(RowSumsVersion::avx512);
    }
  }
  return here;
}

void add_row_sums_by(RowSumsVersion version, const FloatRows& image, const RowSpan& row,
                     RowSums& s) {
  switch (version) {
    case RowSumsVersion::avx512:
      avx512::add_row_sums_simd(image, row, s);
      return;
    case RowSumsVersion::avx2:
      avx2::add_row_sums_simd(image, row, s);
      return;
    case RowSumsVersion::plain:
      break;
  }
  add_row_sums(image, row, s);
}

void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s) {
  if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma")) {
    add_row_sums(image, row, s);
  } else if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) {
    avx512::add_row_sums_simd(image, row, s);
  } else {
    avx2::add_row_sums_simd(image, row, s);
  }
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

#endif

}  // namespace tactile::capture
