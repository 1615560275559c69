// Experiment plots: bar and line charts drawn with OpenCV's primitives.

#include "plots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace tactile::experiments::plots {
namespace {

const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrey(180, 180, 180);
const cv::Scalar kWhite(255, 255, 255);
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

// A colour-blind-safe palette (Okabe-Ito), BGR.
cv::Scalar colour(int i) {
  static const cv::Scalar palette[] = {{178, 114, 0},  {0, 159, 230},   {115, 158, 0},
                                       {66, 228, 240}, {167, 121, 204}, {0, 94, 213},
                                       {233, 180, 86}, {0, 0, 0}};
  return palette[static_cast<std::size_t>(std::max(i, 0)) % std::size(palette)];
}

void text(cv::Mat& img, const std::string& s, int x, int y, double scale = 0.45,
          const cv::Scalar& c = kBlack) {
  cv::putText(img, s, {x, y}, kFont, scale, c, 1, cv::LINE_AA);
}

void save(const std::filesystem::path& path, const cv::Mat& img) {
  std::filesystem::create_directories(path.parent_path());
  if (!cv::imwrite(path.string(), img)) {
    throw std::runtime_error(fmt::format("cannot write plot {}", path.string()));
  }
}

}  // namespace

void bar_chart(const std::filesystem::path& path, const std::string& title,
               const std::string& value_name, const std::vector<std::string>& labels,
               const std::vector<double>& values, const std::vector<int>& colour_index,
               const std::vector<std::string>& legend, double value_min, double value_max,
               const std::string& footer) {
  const int label_w = 420, plot_w = 480, bar_h = 18, gap = 4, top = 60;
  const int n = static_cast<int>(values.size());
  const int height = top + n * (bar_h + gap) + 90;
  cv::Mat img(height, label_w + plot_w + 40, CV_8UC3, kWhite);
  text(img, title, 10, 25, 0.6);
  const double span = value_max > value_min ? value_max - value_min : 1.0;
  const auto x_of = [&](double v) {
    return label_w + static_cast<int>(std::lround(
                         (std::clamp(v, value_min, value_max) - value_min) / span * plot_w));
  };
  for (int t = 0; t <= 4; ++t) {
    const double v = value_min + span * t / 4;
    const int x = x_of(v);
    cv::line(img, {x, top - 5}, {x, top + n * (bar_h + gap)}, kGrey, 1);
    text(img, fmt::format("{:.2g}", v), x - 12, top - 10, 0.4);
  }
  for (int i = 0; i < n; ++i) {
    const int y = top + i * (bar_h + gap);
    text(img, labels[static_cast<std::size_t>(i)], 10, y + bar_h - 4, 0.4);
    const double v = values[static_cast<std::size_t>(i)];
    const int x0 = x_of(std::clamp(0.0, value_min, value_max));
    const int x1 = x_of(v);
    cv::rectangle(img, {std::min(x0, x1), y}, {std::max(x0, x1) + 1, y + bar_h},
                  colour(colour_index[static_cast<std::size_t>(i)]), cv::FILLED);
    text(img, std::isfinite(v) ? fmt::format("{:.3f}", v) : "n/a", std::max(x0, x1) + 4,
         y + bar_h - 4, 0.4);
  }
  const int bottom = top + n * (bar_h + gap);
  text(img, value_name, label_w, bottom + 22, 0.45);
  int lx = 10;
  for (std::size_t k = 0; k < legend.size(); ++k) {
    cv::rectangle(img, {lx, bottom + 36}, {lx + 14, bottom + 50}, colour(static_cast<int>(k)),
                  cv::FILLED);
    text(img, legend[k], lx + 20, bottom + 48, 0.45);
    lx += 30 + 9 * static_cast<int>(legend[k].size());
  }
  text(img, footer, 10, height - 10, 0.35, {90, 90, 90});
  save(path, img);
}

void line_chart(const std::filesystem::path& path, const std::string& title,
                const std::string& value_name, const std::vector<std::string>& labels,
                const std::vector<std::vector<double>>& series, double dt_s,
                const std::string& footer) {
  const int left = 70, plot_w = 760, plot_h = 320, top = 50;
  const int legend_h = 16 * static_cast<int>(series.size());
  const int height = top + plot_h + 50 + legend_h + 30;
  cv::Mat img(height, left + plot_w + 30, CV_8UC3, kWhite);
  text(img, title, 10, 25, 0.6);
  std::size_t longest = 1;
  double peak = 0;
  for (const auto& s : series) {
    longest = std::max(longest, s.size());
    for (const double v : s) {
      if (std::isfinite(v)) peak = std::max(peak, v);
    }
  }
  if (!(peak > 0)) peak = 1;
  const double t_max = static_cast<double>(longest - 1) * dt_s;
  cv::rectangle(img, {left, top}, {left + plot_w, top + plot_h}, kGrey, 1);
  for (int t = 0; t <= 4; ++t) {
    const int y = top + plot_h - plot_h * t / 4;
    text(img, fmt::format("{:.3g}", peak * t / 4), 5, y + 4, 0.4);
    const int x = left + plot_w * t / 4;
    text(img, fmt::format("{:.2g}", t_max * t / 4), x - 10, top + plot_h + 18, 0.4);
  }
  text(img, "t (s)", left + plot_w / 2, top + plot_h + 36, 0.45);
  text(img, value_name, left, top - 8, 0.45);
  for (std::size_t k = 0; k < series.size(); ++k) {
    std::vector<cv::Point> points;
    const auto& s = series[k];
    for (std::size_t i = 0; i < s.size(); ++i) {
      const double x = longest > 1 ? static_cast<double>(i) / static_cast<double>(longest - 1) : 0;
      points.emplace_back(left + static_cast<int>(std::lround(x * plot_w)),
                          top + plot_h - static_cast<int>(std::lround(s[i] / peak * plot_h)));
    }
    cv::polylines(img, points, false, colour(static_cast<int>(k)), 1, cv::LINE_AA);
    const int ly = top + plot_h + 50 + 16 * static_cast<int>(k);
    cv::line(img, {left, ly - 4}, {left + 20, ly - 4}, colour(static_cast<int>(k)), 2);
    text(img, labels[k], left + 26, ly, 0.4);
  }
  text(img, footer, 10, height - 10, 0.35, {90, 90, 90});
  save(path, img);
}

}  // namespace tactile::experiments::plots
