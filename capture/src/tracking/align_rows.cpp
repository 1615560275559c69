#include "tracking/align_rows.hpp"

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

__attribute__((target("avx2,fma"))) double horizontal_sum(__m256 v) {
  const __m128 h = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 q = _mm_add_ps(h, _mm_movehl_ps(h, h));
  return static_cast<double>(_mm_cvtss_f32(_mm_add_ss(q, _mm_shuffle_ps(q, q, 1))));
}

// The two neighbours along x of eight samples, (image[at], image[at + 1]) for each lane, as two
// vectors: one gather of pairs (8 bytes each) per four lanes instead of one per value. Lanes
// off in `mask` (all bits set = on) read nothing and give zero.
__attribute__((target("avx2,fma"))) void gather_pairs(const float* base, __m256i at, __m256i mask,
                                                      __m256& left, __m256& right) {
  const __m256i lo_mask = _mm256_cvtepi32_epi64(_mm256_castsi256_si128(mask));
  const __m256i hi_mask = _mm256_cvtepi32_epi64(_mm256_extracti128_si256(mask, 1));
  const auto* pairs = reinterpret_cast<const long long*>(base);
  const __m256 lo = _mm256_castsi256_ps(_mm256_mask_i32gather_epi64(
      _mm256_setzero_si256(), pairs, _mm256_castsi256_si128(at), lo_mask, 4));
  const __m256 hi = _mm256_castsi256_ps(_mm256_mask_i32gather_epi64(
      _mm256_setzero_si256(), pairs, _mm256_extracti128_si256(at, 1), hi_mask, 4));
  // (l0 r0 l1 r1 | l2 r2 l3 r3) and the same for lanes 4..7: evens and odds, then the 64-bit
  // halves back in lane order.
  const __m256 even = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0));
  const __m256 odd = _mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(3, 1, 3, 1));
  left = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(even), _MM_SHUFFLE(3, 1, 2, 0)));
  right = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(odd), _MM_SHUFFLE(3, 1, 2, 0)));
}

__attribute__((target("avx2,fma"))) void add_row_sums_avx2(const FloatRows& image,
                                                           const RowSpan& row, RowSums& s) {
  const double bx = std::floor(row.x0), by = std::floor(row.y0);
  const __m256 fx0 = _mm256_set1_ps(static_cast<float>(row.x0 - bx));
  const __m256 fy0 = _mm256_set1_ps(static_cast<float>(row.y0 - by));
  const __m256 dx = _mm256_set1_ps(static_cast<float>(row.dx));
  const __m256 dy = _mm256_set1_ps(static_cast<float>(row.dy));
  const __m256 ox0 = _mm256_set1_ps(static_cast<float>(row.ox0));
  const __m256i base_x = _mm256_set1_epi32(static_cast<int>(bx));
  const __m256i base_y = _mm256_set1_epi32(static_cast<int>(by));
  const __m256i stride = _mm256_set1_epi32(static_cast<int>(image.stride));
  const __m256 lane = _mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256i lane_index = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  __m256 si = _mm256_setzero_ps(), sii = si, sit = si, sa = si, sa_ox = si, sc = si, sc_ox = si;
  const float* below = image.data + image.stride;
  // Eight samples from k on; lanes at or past `end` are left out (a row's last, partial group:
  // one more vector step is cheaper than two or more samples one at a time).
  const auto add_eight = [&](int k, __m256i on) __attribute__((target("avx2,fma"))) {
    const __m256 kk = _mm256_add_ps(_mm256_set1_ps(static_cast<float>(k)), lane);
    const __m256 x = _mm256_fmadd_ps(kk, dx, fx0), y = _mm256_fmadd_ps(kk, dy, fy0);
    const __m256 flx = _mm256_floor_ps(x), fly = _mm256_floor_ps(y);
    const __m256 ax = _mm256_sub_ps(x, flx), ay = _mm256_sub_ps(y, fly);
    const __m256i ix = _mm256_add_epi32(_mm256_cvttps_epi32(flx), base_x);
    const __m256i iy = _mm256_add_epi32(_mm256_cvttps_epi32(fly), base_y);
    const __m256i at = _mm256_add_epi32(_mm256_mullo_epi32(iy, stride), ix);
    __m256 p00, p01, p10, p11;
    gather_pairs(image.data, at, on, p00, p01);
    gather_pairs(below, at, on, p10, p11);
    const __m256 upper = _mm256_fmadd_ps(ax, _mm256_sub_ps(p01, p00), p00);
    const __m256 lower = _mm256_fmadd_ps(ax, _mm256_sub_ps(p11, p10), p10);
    const __m256 v = _mm256_fmadd_ps(ay, _mm256_sub_ps(lower, upper), upper);
    const __m256 wv = _mm256_mul_ps(_mm256_maskload_ps(row.weight + k, on), v);
    si = _mm256_add_ps(si, wv);
    sii = _mm256_fmadd_ps(wv, v, sii);
    sit = _mm256_fmadd_ps(wv, _mm256_maskload_ps(row.grey + k, on), sit);
    const __m256 ox = _mm256_add_ps(ox0, kk);
    const __m256 ga = _mm256_mul_ps(wv, _mm256_maskload_ps(row.gx + k, on));
    const __m256 gc = _mm256_mul_ps(wv, _mm256_maskload_ps(row.gy + k, on));
    sa = _mm256_add_ps(sa, ga);
    sa_ox = _mm256_fmadd_ps(ga, ox, sa_ox);
    sc = _mm256_add_ps(sc, gc);
    sc_ox = _mm256_fmadd_ps(gc, ox, sc_ox);
  };
  const __m256i all = _mm256_set1_epi32(-1);
  int k = row.first;
  for (; k + 8 <= row.cols; k += 8) add_eight(k, all);
  if (row.cols - k >= 2) {
    add_eight(k, _mm256_cmpgt_epi32(_mm256_set1_epi32(row.cols - k), lane_index));
    k = row.cols;
  }
  s.i += horizontal_sum(si);
  s.ii += horizontal_sum(sii);
  s.it += horizontal_sum(sit);
  s.a += horizontal_sum(sa);
  s.a_ox += horizontal_sum(sa_ox);
  s.c += horizontal_sum(sc);
  s.c_ox += horizontal_sum(sc_ox);
  RowSpan rest = row;
  rest.first = k;
  add_row_sums(image, rest, s);
}

}  // namespace

bool has_vector_row_sums() {
  return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
}

void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s) {
  if (has_vector_row_sums()) {
    add_row_sums_avx2(image, row, s);
  } else {
    add_row_sums(image, row, s);
  }
}

#else

bool has_vector_row_sums() {
  return false;
}

void add_row_sums_vector(const FloatRows& image, const RowSpan& row, RowSums& s) {
  add_row_sums(image, row, s);
}

#endif

}  // namespace tactile::capture
