#pragma once
// Summary statistics of a sample, defined once for every module, benchmark and evaluation, so
// that two figures with the same name are computed the same way.
//
// Order statistics pick an element of the sample, never interpolate between two:
//   median(v)      = the upper median, element n/2 (0-based) of v sorted ascending;
//   quantile(v, q) = element floor(q * (n - 1)) of v sorted ascending, q in [0, 1]
//                    (numpy's method "lower"); quantile(v, 0.99) is the "p99" printed everywhere.
// The two agree for an odd n; for an even n the median is the upper and quantile(v, 0.5) the
// lower of the two middle elements. Both are 0 for an empty sample.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace tactile {

template <typename T>
double median(std::vector<T> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return static_cast<double>(*mid);
}

// Throws std::invalid_argument for q outside [0, 1] (or NaN).
template <typename T>
double quantile(std::vector<T> v, double q) {
  if (!(q >= 0 && q <= 1)) {
    throw std::invalid_argument("quantile: fraction " + std::to_string(q) + " is outside 0 to 1");
  }
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::ptrdiff_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + k, v.end());
  return static_cast<double>(v[static_cast<std::size_t>(k)]);
}

// Median absolute deviation from the median (unscaled: multiply by 1.4826 for the standard
// deviation of a normal sample), computed in T so a float sample gives the float result.
template <typename T>
double mad(std::vector<T> v) {
  if (v.empty()) return 0.0;
  const T m = static_cast<T>(median(v));
  for (T& a : v) a = static_cast<T>(std::abs(a - m));
  return median(std::move(v));
}

// Pearson's correlation of the pairs (a[i], b[i]), computed about the means (two passes). 0 when
// there are fewer than two pairs or either population variance is not above `min_variance`
// (a constant has no correlation). Throws std::invalid_argument if the sizes differ.
inline double pearson(const std::vector<double>& a, const std::vector<double>& b,
                      double min_variance = 0) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("pearson: " + std::to_string(a.size()) + " values against " +
                                std::to_string(b.size()));
  }
  if (a.size() < 2) return 0.0;
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i], mb += b[i];
  ma /= n;
  mb /= n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  if (!(saa / n > min_variance) || !(sbb / n > min_variance)) return 0.0;
  return sab / std::sqrt(saa * sbb);
}

}  // namespace tactile
