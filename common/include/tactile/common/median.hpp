#pragma once
// The median of a sample, as the benchmarks and evaluations report it.

#include <algorithm>
#include <cstddef>
#include <vector>

namespace tactile {

// The upper median (element n/2 in sorted order) of `v`; 0 for an empty sample.
inline double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace tactile
