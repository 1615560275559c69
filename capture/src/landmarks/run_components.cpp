#include "landmarks/run_components.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace tactile::capture {

namespace {
std::int32_t find_root(std::vector<std::int32_t>& parent, std::int32_t i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    auto& p = parent[static_cast<std::size_t>(i)];
    p = parent[static_cast<std::size_t>(p)];  // path halving
    i = p;
  }
  return i;
}
std::uint64_t load_word(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

bool has_zero_byte(std::uint64_t v) {
  constexpr std::uint64_t kOnes = 0x0101010101010101ULL;
  constexpr std::uint64_t kHighs = 0x8080808080808080ULL;
  return ((v - kOnes) & ~v & kHighs) != 0;
}
}  // namespace

RunLabels label_runs_4(const cv::Mat& binary) {
  if (binary.type() != CV_8UC1) throw std::invalid_argument("label_runs_4: image must be CV_8U");
  RunLabels out;
  auto& runs = out.runs;
  std::vector<std::int32_t> parent;
  std::size_t prev_begin = 0, prev_end = 0;
  for (int y = 0; y < binary.rows; ++y) {
    const std::uint8_t* row = binary.ptr<std::uint8_t>(y);
    const std::size_t row_begin = runs.size();
    const int cols = binary.cols;
    for (int x = 0; x < cols;) {
      // Eight pixels at a time through the long stretches of zeros and of set pixels.
      while (x + 8 <= cols && load_word(row + x) == 0) x += 8;
      while (x < cols && !row[x]) ++x;
      if (x >= cols) break;
      const int start = x;
      while (x + 8 <= cols && !has_zero_byte(load_word(row + x))) x += 8;
      while (x < cols && row[x]) ++x;
      const auto id = static_cast<std::int32_t>(runs.size());
      runs.push_back({y, start, x, id});
      parent.push_back(id);
    }
    const std::size_t row_end = runs.size();
    // Runs of this row and the row above that share a column are 4-connected.
    std::size_t i = prev_begin, j = row_begin;
    while (i < prev_end && j < row_end) {
      const PixelRun& a = runs[i];
      const PixelRun& b = runs[j];
      if (a.x_begin < b.x_end && b.x_begin < a.x_end) {
        const std::int32_t ra = find_root(parent, a.component);
        const std::int32_t rb = find_root(parent, b.component);
        // The smaller id (earlier first pixel) stays the root.
        if (ra < rb) {
          parent[static_cast<std::size_t>(rb)] = ra;
        } else if (rb < ra) {
          parent[static_cast<std::size_t>(ra)] = rb;
        }
      }
      if (a.x_end < b.x_end) {
        ++i;
      } else {
        ++j;
      }
    }
    prev_begin = row_begin;
    prev_end = row_end;
  }
  // Roots in increasing id order are the components in raster order of their first pixel.
  std::vector<std::int32_t> index(runs.size(), -1);
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const std::int32_t root = find_root(parent, static_cast<std::int32_t>(k));
    auto& slot = index[static_cast<std::size_t>(root)];
    const PixelRun& r = runs[k];
    if (slot < 0) {
      slot = static_cast<std::int32_t>(out.components.size());
      out.components.push_back({0, r.x_begin, r.y, r.x_end - 1, r.y});
    }
    RunComponent& c = out.components[static_cast<std::size_t>(slot)];
    c.area += r.x_end - r.x_begin;
    c.x_min = std::min(c.x_min, r.x_begin);
    c.x_max = std::max(c.x_max, r.x_end - 1);
    c.y_max = r.y;
    runs[k].component = slot;
  }
  return out;
}

}  // namespace tactile::capture
