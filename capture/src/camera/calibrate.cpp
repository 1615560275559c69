#include "tactile/capture/calibrate.hpp"
#include "tactile/common/stats.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>

#include <fmt/format.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "camera/cv_image.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {

namespace {

struct Dot {
  cv::Point2d px;
};

std::vector<Dot> find_dots(const cv::Mat& gray) {
  cv::Mat smooth, mean;
  cv::GaussianBlur(gray, smooth, cv::Size(0, 0), 1.0);
  smooth.convertTo(smooth, CV_32F);
  const int window = std::max(15, std::min(gray.cols, gray.rows) / 12) | 1;
  cv::blur(smooth, mean, cv::Size(window, window));
  cv::Mat dark = (mean - smooth) > 12.0;  // dots are darker than their surroundings
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(dark, labels, stats, centroids, 8, CV_32S);
  std::vector<int> areas;
  for (int i = 1; i < n; ++i) areas.push_back(stats.at<int>(i, cv::CC_STAT_AREA));
  if (areas.empty()) return {};
  const double median_area = median(areas);
  // Grey-level centroids: weight by how much darker than the local mean each pixel is.
  std::vector<cv::Point3d> sums(static_cast<std::size_t>(n), cv::Point3d(0, 0, 0));
  for (int y = 0; y < labels.rows; ++y) {
    const int* lrow = labels.ptr<int>(y);
    const float* srow = smooth.ptr<float>(y);
    const float* mrow = mean.ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (lrow[x] == 0) continue;
      const double w = mrow[x] - srow[x];
      auto& s = sums[static_cast<std::size_t>(lrow[x])];
      s.x += w * x;
      s.y += w * y;
      s.z += w;
    }
  }
  std::vector<Dot> dots;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    const int left = stats.at<int>(i, cv::CC_STAT_LEFT);
    const int top = stats.at<int>(i, cv::CC_STAT_TOP);
    const int w = stats.at<int>(i, cv::CC_STAT_WIDTH);
    const int h = stats.at<int>(i, cv::CC_STAT_HEIGHT);
    if (area < 4 || area < 0.4 * median_area || area > 2.5 * median_area) continue;
    if (left == 0 || top == 0 || left + w >= gray.cols || top + h >= gray.rows) continue;
    const auto& s = sums[static_cast<std::size_t>(i)];
    if (s.z <= 0) continue;
    dots.push_back({{s.x / s.z, s.y / s.z}});
  }
  return dots;
}

}  // namespace

Calibration calibrate_dot_grid(const GrayImage& image, double spacing_mm) {
  if (!(spacing_mm > 0)) throw std::invalid_argument("dot grid spacing must be > 0 mm");
  if (image.width_px < 16 || image.height_px < 16) {
    throw FormatError(fmt::format(
        "no dot grid found: the image is {}x{} px, too small to hold one (need at least 16x16 px)",
        image.width_px, image.height_px));
  }
  const std::vector<Dot> dots = find_dots(as_mat(image));
  auto no_grid = [&](const std::string& why) {
    return FormatError(fmt::format("no dot grid found in the {}x{} px image: {}", image.width_px,
                                   image.height_px, why));
  };
  if (dots.size() < 16) {
    throw no_grid(fmt::format("only {} dot-like blobs (need at least 16)", dots.size()));
  }

  // Grid pitch in pixels: the median nearest-neighbour distance.
  std::vector<double> nearest(dots.size(), 1e30);
  std::vector<std::size_t> nearest_index(dots.size(), 0);
  for (std::size_t i = 0; i < dots.size(); ++i) {
    for (std::size_t j = 0; j < dots.size(); ++j) {
      if (i == j) continue;
      const double d = cv::norm(dots[i].px - dots[j].px);
      if (d < nearest[i]) {
        nearest[i] = d;
        nearest_index[i] = j;
      }
    }
  }
  const double pitch = median(nearest);

  // Seed at the dot closest to the image centre; lattice vectors from its neighbours.
  const cv::Point2d centre(image.width_px / 2.0, image.height_px / 2.0);
  std::size_t seed = 0;
  for (std::size_t i = 1; i < dots.size(); ++i) {
    if (cv::norm(dots[i].px - centre) < cv::norm(dots[seed].px - centre)) seed = i;
  }
  // Lattice vectors: the nearest neighbours within 30 degrees of the image axes (the pitch may
  // differ between x and y when pixels are not square).
  cv::Point2d ax(0, 0), ay(0, 0);
  double best_x = 1e30, best_y = 1e30;
  for (const auto& d : dots) {
    const cv::Point2d v = d.px - dots[seed].px;
    const double len = cv::norm(v);
    if (len < 0.5 * pitch || len > 2.5 * pitch) continue;
    if (v.x / len > 0.866 && len < best_x) {
      best_x = len;
      ax = v;
    }
    if (v.y / len > 0.866 && len < best_y) {
      best_y = len;
      ay = v;
    }
  }
  if (best_x > 1e29 || best_y > 1e29) throw no_grid("the central dot has no grid neighbours");

  // Breadth-first indexing; each step predicts from the local neighbour, which follows
  // perspective and lens distortion better than one global lattice.
  std::map<std::pair<int, int>, std::size_t> index_of;
  std::vector<std::pair<int, int>> grid_of(dots.size(), {0, 0});
  std::vector<bool> assigned(dots.size(), false);
  std::queue<std::size_t> todo;
  index_of[{0, 0}] = seed;
  assigned[seed] = true;
  todo.push(seed);
  const int steps[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!todo.empty()) {
    const std::size_t k = todo.front();
    todo.pop();
    const auto [gi, gj] = grid_of[k];
    for (const auto& s : steps) {
      const std::pair<int, int> target{gi + s[0], gj + s[1]};
      if (index_of.count(target)) continue;
      cv::Point2d step = s[0] != 0 ? ax * s[0] : ay * s[1];
      // Local step: reuse the step from the opposite neighbour when it is known.
      const auto back = index_of.find({gi - s[0], gj - s[1]});
      if (back != index_of.end()) step = dots[k].px - dots[back->second].px;
      const cv::Point2d predicted = dots[k].px + step;
      std::size_t best = dots.size();
      double best_d = 0.3 * cv::norm(step);
      for (std::size_t m = 0; m < dots.size(); ++m) {
        if (assigned[m]) continue;
        const double d = cv::norm(dots[m].px - predicted);
        if (d < best_d) {
          best_d = d;
          best = m;
        }
      }
      if (best == dots.size()) continue;
      assigned[best] = true;
      grid_of[best] = target;
      index_of[target] = best;
      todo.push(best);
    }
  }
  int min_i = 0, max_i = 0, min_j = 0, max_j = 0;
  std::vector<cv::Point2f> px, mm;
  for (const auto& [g, k] : index_of) {
    min_i = std::min(min_i, g.first);
    max_i = std::max(max_i, g.first);
    min_j = std::min(min_j, g.second);
    max_j = std::max(max_j, g.second);
    px.emplace_back(static_cast<float>(dots[k].px.x), static_cast<float>(dots[k].px.y));
    mm.emplace_back(static_cast<float>(g.first * spacing_mm),
                    static_cast<float>(g.second * spacing_mm));
  }
  if (max_i - min_i < 3 || max_j - min_j < 3) {
    throw no_grid(fmt::format("the indexed grid spans only {} x {} dots (need 4 x 4)",
                              max_i - min_i + 1, max_j - min_j + 1));
  }
  cv::Mat h = cv::findHomography(px, mm, cv::RANSAC, 0.02 * spacing_mm / 0.5);
  if (h.empty()) throw no_grid("the dot positions do not fit a homography");

  // Move the mm origin to pixel (0, 0).
  const double w0 = h.at<double>(2, 2);
  const double x0 = h.at<double>(0, 2) / w0;
  const double y0 = h.at<double>(1, 2) / w0;
  cv::Mat shift = (cv::Mat_<double>(3, 3) << 1, 0, -x0, 0, 1, -y0, 0, 0, 1);
  h = shift * h;
  h /= h.at<double>(2, 2);

  Calibration c;
  for (int r = 0; r < 3; ++r) {
    for (int col = 0; col < 3; ++col) {
      c.px_to_mm[static_cast<std::size_t>(r * 3 + col)] = h.at<double>(r, col);
    }
  }
  c.image_width_px = image.width_px;
  c.image_height_px = image.height_px;
  // Mean scale: square root of the local area magnification at the image centre.
  const double e = 1.0;
  const PointMm p0 = to_mm(c, centre.x, centre.y);
  const PointMm px1 = to_mm(c, centre.x + e, centre.y);
  const PointMm py1 = to_mm(c, centre.x, centre.y + e);
  const double det =
      (px1.x_mm - p0.x_mm) * (py1.y_mm - p0.y_mm) - (px1.y_mm - p0.y_mm) * (py1.x_mm - p0.x_mm);
  c.mm_per_px = std::sqrt(std::abs(det)) / e;
  c.method = fmt::format("dot-grid {} mm, {} dots", spacing_mm, px.size());
  return c;
}

}  // namespace tactile::capture
