#include "tactile/capture/chart.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace tactile::capture {

namespace {

const cv::Scalar kColours[] = {{200, 60, 30},  {40, 140, 40}, {30, 30, 200}, {160, 60, 160},
                               {20, 140, 200}, {90, 90, 90},  {200, 160, 0}, {0, 90, 160}};

struct Axis {
  bool log = true;
  double lo = 0, hi = 1;
  double map(double v) const { return log ? std::log10(v) : v; }
  double frac(double v) const { return (map(v) - lo) / (hi - lo); }
};

Axis fit_axis(const std::vector<double>& values, bool log, double target) {
  Axis a;
  a.log = log;
  std::vector<double> m;
  for (double v : values) m.push_back(a.map(v));
  if (target > 0) m.push_back(a.map(target));
  const auto [mn, mx] = std::minmax_element(m.begin(), m.end());
  a.lo = *mn;
  a.hi = *mx;
  const double pad = std::max(0.08 * (a.hi - a.lo), log ? 0.1 : 1e-9 + 0.05 * std::abs(a.hi));
  a.lo -= pad;
  a.hi += pad;
  return a;
}

std::string tick_text(double v) {
  return std::abs(v) >= 100 ? fmt::format("{:.0f}", v) : fmt::format("{:.3g}", v);
}

}  // namespace

void write_scatter_chart_png(const std::filesystem::path& path,
                             const std::vector<ChartPoint>& points, const ChartSpec& spec) {
  std::vector<ChartPoint> ok;
  for (const auto& p : points) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) continue;
    if ((spec.log_x && p.x <= 0) || (spec.log_y && p.y <= 0)) continue;
    ok.push_back(p);
  }
  const int w = 960, h = 600, left = 90, right = 260, top = 50, bottom = 70;
  cv::Mat img(h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  const cv::Rect plot(left, top, w - left - right, h - top - bottom);
  cv::rectangle(img, plot, cv::Scalar(0, 0, 0), 1);
  const auto font = cv::FONT_HERSHEY_SIMPLEX;
  cv::putText(img, spec.title, {left, 30}, font, 0.6, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, spec.x_label, {left + plot.width / 2 - 80, h - 20}, font, 0.5,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, spec.y_label, {5, top - 10}, font, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  if (!ok.empty()) {
    std::vector<double> xs, ys;
    for (const auto& p : ok) {
      xs.push_back(p.x);
      ys.push_back(p.y);
    }
    const Axis ax = fit_axis(xs, spec.log_x, spec.x_target);
    const Axis ay = fit_axis(ys, spec.log_y, spec.y_target);
    auto px = [&](double x, double y) {
      return cv::Point(left + static_cast<int>(std::lround(ax.frac(x) * plot.width)),
                       top + plot.height - static_cast<int>(std::lround(ay.frac(y) * plot.height)));
    };
    // Ticks: five evenly spaced values along each (possibly logarithmic) axis.
    for (int k = 0; k <= 4; ++k) {
      const double fx = ax.lo + (ax.hi - ax.lo) * k / 4.0;
      const double vx = ax.log ? std::pow(10.0, fx) : fx;
      const int x = left + plot.width * k / 4;
      cv::line(img, {x, top + plot.height}, {x, top + plot.height + 5}, cv::Scalar(0, 0, 0));
      cv::putText(img, tick_text(vx), {x - 20, top + plot.height + 22}, font, 0.4,
                  cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
      const double fy = ay.lo + (ay.hi - ay.lo) * k / 4.0;
      const double vy = ay.log ? std::pow(10.0, fy) : fy;
      const int y = top + plot.height - plot.height * k / 4;
      cv::line(img, {left - 5, y}, {left, y}, cv::Scalar(0, 0, 0));
      cv::putText(img, tick_text(vy), {10, y + 4}, font, 0.4, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    }
    auto dashed = [&](cv::Point a, cv::Point b) {
      const double len = cv::norm(b - a);
      for (double s = 0; s < len; s += 12) {
        const double e = std::min(len, s + 6);
        cv::line(img, a + (b - a) * (s / len), a + (b - a) * (e / len), cv::Scalar(120, 120, 120));
      }
    };
    if (spec.y_target > 0) {
      dashed(px(std::pow(10.0, ax.lo), spec.y_target), px(std::pow(10.0, ax.hi), spec.y_target));
    }
    if (spec.x_target > 0) {
      dashed(px(spec.x_target, ay.log ? std::pow(10.0, ay.lo) : ay.lo),
             px(spec.x_target, ay.log ? std::pow(10.0, ay.hi) : ay.hi));
    }
    std::vector<std::string> labels;
    for (const auto& p : ok) {
      auto it = std::find(labels.begin(), labels.end(), p.label);
      if (it == labels.end()) {
        labels.push_back(p.label);
        it = labels.end() - 1;
      }
      const auto colour = kColours[static_cast<std::size_t>(it - labels.begin()) % 8];
      cv::circle(img, px(p.x, p.y), 6, colour, -1, cv::LINE_AA);
    }
    for (std::size_t i = 0; i < labels.size(); ++i) {
      const int y = top + 20 + 24 * static_cast<int>(i);
      cv::circle(img, {w - right + 20, y - 4}, 6, kColours[i % 8], -1, cv::LINE_AA);
      cv::putText(img, labels[i], {w - right + 32, y}, font, 0.45, cv::Scalar(0, 0, 0), 1,
                  cv::LINE_AA);
    }
  }
  bool written = false;
  try {
    written = cv::imwrite(path.string(), img);
  } catch (const cv::Exception&) {
    written = false;
  }
  if (!written) {
    throw std::runtime_error(fmt::format("{}: cannot write chart", path.string()));
  }
}

}  // namespace tactile::capture
