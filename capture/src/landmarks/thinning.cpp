#include "landmarks/thinning.hpp"

#include <array>
#include <cstdint>

namespace tactile::capture {

namespace {

// Decision tables indexed by the 8-neighbour bit pattern P2..P9 (bit 0 = P2, clockwise from
// north), precomputed once so each pass is a table lookup per pixel.
struct Tables {
  std::array<std::uint8_t, 256> first{};
  std::array<std::uint8_t, 256> second{};
  Tables() {
    for (int m = 0; m < 256; ++m) {
      int p[8];
      for (int k = 0; k < 8; ++k) p[k] = (m >> k) & 1;  // p[0]=P2 ... p[7]=P9
      int b = 0, a = 0;
      for (int k = 0; k < 8; ++k) {
        b += p[k];
        a += (p[k] == 0 && p[(k + 1) % 8] == 1) ? 1 : 0;
      }
      const bool common = b >= 2 && b <= 6 && a == 1;
      // P2*P4*P6 == 0 and P4*P6*P8 == 0 (first); P2*P4*P8 == 0 and P2*P6*P8 == 0 (second).
      first[static_cast<std::size_t>(m)] =
          common && !(p[0] && p[2] && p[4]) && !(p[2] && p[4] && p[6]);
      second[static_cast<std::size_t>(m)] =
          common && !(p[0] && p[2] && p[6]) && !(p[0] && p[4] && p[6]);
    }
  }
};

}  // namespace

cv::Mat zhang_suen_thinning(const cv::Mat& binary) {
  const Tables tables;  // 512 entries: cheaper to build than to share
  cv::Mat img = cv::Mat::zeros(binary.rows + 2, binary.cols + 2, CV_8U);
  binary.copyTo(img(cv::Rect(1, 1, binary.cols, binary.rows)));
  img.setTo(1, img > 1);
  std::vector<cv::Point> remove;
  bool changed = true;
  while (changed) {
    changed = false;
    for (int pass = 0; pass < 2; ++pass) {
      const auto& table = pass == 0 ? tables.first : tables.second;
      remove.clear();
      for (int y = 1; y < img.rows - 1; ++y) {
        const std::uint8_t* up = img.ptr<std::uint8_t>(y - 1);
        const std::uint8_t* row = img.ptr<std::uint8_t>(y);
        const std::uint8_t* down = img.ptr<std::uint8_t>(y + 1);
        for (int x = 1; x < img.cols - 1; ++x) {
          if (!row[x]) continue;
          const int m = up[x] | (up[x + 1] << 1) | (row[x + 1] << 2) | (down[x + 1] << 3) |
                        (down[x] << 4) | (down[x - 1] << 5) | (row[x - 1] << 6) | (up[x - 1] << 7);
          if (table[static_cast<std::size_t>(m)]) remove.emplace_back(x, y);
        }
      }
      for (const auto& pt : remove) img.at<std::uint8_t>(pt) = 0;
      changed = changed || !remove.empty();
    }
  }
  return img(cv::Rect(1, 1, binary.cols, binary.rows)).clone();
}

int crossing_number(const cv::Mat& skeleton, int x, int y) {
  static constexpr int kRing[8][2] = {{1, 0},  {1, 1},   {0, 1},  {-1, 1},
                                      {-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
  auto on = [&](int k) {
    const int xx = x + kRing[k % 8][0];
    const int yy = y + kRing[k % 8][1];
    return xx >= 0 && yy >= 0 && xx < skeleton.cols && yy < skeleton.rows &&
           skeleton.at<std::uint8_t>(yy, xx) != 0;
  };
  int n = 0;
  for (int k = 0; k < 8; ++k) n += (!on(k) && on(k + 1)) ? 1 : 0;
  return n;
}

}  // namespace tactile::capture
