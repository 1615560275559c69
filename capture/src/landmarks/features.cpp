#include "tactile/capture/features.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <opencv2/imgproc.hpp>

#include "camera/cv_image.hpp"
#include "landmarks/run_components.hpp"
#include "landmarks/skeleton_repair.hpp"
#include "landmarks/thinning.hpp"
#include "pores/pore_blobs.hpp"
#include "tactile/common/csv.hpp"

namespace tactile::capture {

namespace {

int odd_at_least_3(double v) {
  return std::max(3, static_cast<int>(std::lround(v)) | 1);
}

struct Prepared {
  cv::Mat gray;             // CV_32F, unsmoothed
  cv::Mat smooth;           // CV_32F
  cv::Mat mean;             // CV_32F local mean
  cv::Mat bright;           // CV_8U 0/1: above local mean (valleys, pores, background)
  cv::Mat foreground;       // CV_8U 0/1: print in contact, away from borders
  cv::Mat near_background;  // CV_8U: background grown by half the border margin
};

// Box mean over window_px x window_px of an image binned by `factor` (area averaging), so that
// a large window costs a small one. The binned window covers window_px rounded to a multiple of
// the factor; for windows of dozens of pixels over a ridge texture that changes a mean by far
// less than a grey level.
int bin_factor(const cv::Mat& src, int window_px) {
  for (int f : {4, 2}) {
    if (window_px >= 8 * f && src.cols >= 16 * f && src.rows >= 16 * f) return f;
  }
  return 1;
}

cv::Mat binned(const cv::Mat& src, int factor) {
  if (factor == 1) return src;
  cv::Mat out;
  cv::resize(src, out, cv::Size(), 1.0 / factor, 1.0 / factor, cv::INTER_AREA);
  return out;
}

cv::Mat binned_box_mean(const cv::Mat& binned_src, int window_px, int factor) {
  const int window = odd_at_least_3(static_cast<double>(window_px) / factor);
  cv::Mat mean;
  cv::blur(binned_src, mean, cv::Size(window, window), cv::Point(-1, -1), cv::BORDER_REFLECT);
  return mean;
}

Prepared prepare(const cv::Mat& gray, double px_per_mm, const FeatureParams& p) {
  Prepared r;
  gray.convertTo(r.gray, CV_32F);
  const double sigma = p.smoothing_sigma_mm * px_per_mm;
  if (sigma > 0.1) {
    cv::GaussianBlur(r.gray, r.smooth, cv::Size(0, 0), sigma);
  } else {
    r.smooth = r.gray.clone();
  }
  // The 2 mm local mean is smooth at the scale of a few pixels: computed binned, interpolated.
  const int window = odd_at_least_3(p.local_window_mm * px_per_mm);
  const int bg_window = odd_at_least_3(p.background_window_mm * px_per_mm);
  const int factor = bin_factor(r.smooth, window);
  const int bg_factor = bin_factor(r.smooth, bg_window);
  const cv::Mat smooth_binned = binned(r.smooth, factor);
  const cv::Mat coarse_mean = binned_box_mean(smooth_binned, window, factor);
  if (factor > 1) {
    cv::resize(coarse_mean, r.mean, gray.size(), 0, 0, cv::INTER_LINEAR);
  } else {
    r.mean = coarse_mean;
  }
  // Background decided on the binned grid, then brought back pixel for pixel; the border
  // margin below is grown at full resolution.
  cv::Mat sq;
  cv::multiply(r.smooth, r.smooth, sq);
  const cv::Mat bg_mean = binned_box_mean(
      bg_factor == factor ? smooth_binned : binned(r.smooth, bg_factor), bg_window, bg_factor);
  const cv::Mat bg_mean_sq = binned_box_mean(binned(sq, bg_factor), bg_window, bg_factor);
  cv::Mat var = bg_mean_sq - bg_mean.mul(bg_mean);
  const double global_mean = cv::mean(r.smooth)[0];
  cv::Mat background = (var < p.background_max_std * p.background_max_std) &
                       (bg_mean > p.background_min_mean_ratio * global_mean);
  if (background.size() != gray.size()) {
    cv::resize(background, background, gray.size(), 0, 0, cv::INTER_NEAREST);
  }
  // Keep features away from the background and the image edge, where the local mean is biased.
  const int margin = std::max(0, static_cast<int>(std::lround(p.border_margin_mm * px_per_mm)));
  // Square dilations: separable for rectangles, so cheap whatever the margin.
  auto grow = [&](int radius) {
    cv::Mat grown_mask;
    cv::dilate(background, grown_mask,
               cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * radius + 1, 2 * radius + 1)),
               cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
    return grown_mask;
  };
  const cv::Mat grown = grow(margin);
  r.foreground = cv::Mat::zeros(gray.size(), CV_8U);
  const cv::Rect inner(margin, margin, std::max(0, gray.cols - 2 * margin),
                       std::max(0, gray.rows - 2 * margin));
  r.foreground(inner).setTo(1);
  r.foreground.setTo(0, grown);
  // Only the minutiae need it.
  if (p.find_minutiae) r.near_background = grow(std::max(1, margin / 2));
  r.bright = (r.smooth > r.mean) / 255;
  return r;
}

// pore_mask (when given) receives the pore pixels, for the minutiae stage.
void find_pores(const Prepared& r, double px_per_mm, const FeatureParams& p, cv::Mat* pore_mask,
                std::vector<Feature>& out) {
  const RunLabels blobs = label_runs_4(r.bright);
  const double px2_per_mm2 = px_per_mm * px_per_mm;
  const double max_extent = p.pore_max_extent_mm * px_per_mm;
  const std::size_t n = blobs.components.size();
  std::vector<char> is_pore(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const RunComponent& c = blobs.components[i];
    const double area = static_cast<double>(c.area);
    const double w = c.x_max - c.x_min + 1;
    const double h = c.y_max - c.y_min + 1;
    if (area < p.pore_min_area_mm2 * px2_per_mm2 || area > p.pore_max_area_mm2 * px2_per_mm2) {
      continue;
    }
    if (std::max(w, h) > max_extent || area < p.pore_min_fill * w * h) continue;
    is_pore[i] = 1;
  }
  // Grey-level centre of mass, weighted by brightness above the local mean.
  std::vector<cv::Vec3d> sums(n, cv::Vec3d(0, 0, 0));
  if (pore_mask) *pore_mask = cv::Mat::zeros(r.bright.size(), CV_8U);
  for (const PixelRun& run : blobs.runs) {
    const auto c = static_cast<std::size_t>(run.component);
    if (!is_pore[c]) continue;
    const float* srow = r.smooth.ptr<float>(run.y);
    const float* mrow = r.mean.ptr<float>(run.y);
    if (pore_mask) {
      std::fill_n(pore_mask->ptr<std::uint8_t>(run.y) + run.x_begin, run.x_end - run.x_begin, 1);
    }
    for (int x = run.x_begin; x < run.x_end; ++x) {
      const double w = srow[x] - mrow[x];
      sums[c] += cv::Vec3d(w * x, w * run.y, w);
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& s = sums[i];
    if (!is_pore[i] || s[2] <= 0) continue;
    const double x = s[0] / s[2];
    const double y = s[1] / s[2];
    if (!r.foreground.at<std::uint8_t>(static_cast<int>(std::lround(y)),
                                       static_cast<int>(std::lround(x)))) {
      continue;
    }
    out.push_back({FeatureType::pore, x, y, 0.0});
  }
}

// Valley skeleton pixels where one branch meets end a valley; three or more branches fork it.
void find_minutiae(const Prepared& r, const cv::Mat& pore_mask, double px_per_mm,
                   const FeatureParams& p, std::vector<Feature>& out) {
  cv::Mat valley = r.bright.clone();
  valley.setTo(0, pore_mask);
  // Cut valleys where the print meets the background, so that they end there (and those ends
  // fall inside the border margin) instead of forking into the background's own skeleton.
  valley.setTo(0, r.near_background);
  cv::Mat skeleton = zhang_suen_thinning(valley);
  repair_skeleton(skeleton, px_per_mm);
  std::vector<Feature> found;
  cv::Mat fork = cv::Mat::zeros(skeleton.size(), CV_8U);
  for (int y = 1; y < skeleton.rows - 1; ++y) {
    for (int x = 1; x < skeleton.cols - 1; ++x) {
      if (!skeleton.at<std::uint8_t>(y, x) || !r.foreground.at<std::uint8_t>(y, x)) continue;
      const int crossings = crossing_number(skeleton, x, y);
      if (crossings == 1) {
        // The ending points away from the valley it terminates.
        double dx = 0, dy = 0;
        for (int j = -1; j <= 1; ++j) {
          for (int i = -1; i <= 1; ++i) {
            if ((i || j) && skeleton.at<std::uint8_t>(y + j, x + i)) {
              dx += i;
              dy += j;
            }
          }
        }
        found.push_back({FeatureType::ending, double(x), double(y), std::atan2(-dy, -dx)});
      } else if (crossings >= 3) {
        fork.at<std::uint8_t>(y, x) = 1;
      }
    }
  }
  // Adjacent fork pixels describe one bifurcation.
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(fork, labels, stats, centroids, 8, CV_32S);
  for (int i = 1; i < n; ++i) {
    found.push_back(
        {FeatureType::bifurcation, centroids.at<double>(i, 0), centroids.at<double>(i, 1), 0.0});
  }
  // Over-dense minutiae left after the repair are still artefacts, not anatomy: drop them all.
  const double min_sep = p.minutia_min_separation_mm * px_per_mm;
  std::vector<char> drop(found.size(), 0);
  for (std::size_t i = 0; i < found.size(); ++i) {
    for (std::size_t j = i + 1; j < found.size(); ++j) {
      if (std::hypot(found[i].x_px - found[j].x_px, found[i].y_px - found[j].y_px) < min_sep) {
        drop[i] = drop[j] = 1;
      }
    }
  }
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (!drop[i]) out.push_back(found[i]);
  }
}

}  // namespace

std::vector<Feature> extract_features(const GrayImage& image, double px_per_mm,
                                      const FeatureParams& params) {
  if (!(px_per_mm > 0)) {
    throw std::invalid_argument(fmt::format("px_per_mm must be > 0, got {}", px_per_mm));
  }
  if (image.width_px < 3 || image.height_px < 3) return {};
  const Prepared r = prepare(as_mat(image), px_per_mm, params);
  std::vector<Feature> features;
  cv::Mat pore_mask;
  if (params.pore_detector == PoreDetector::ridge_blob) {
    features = find_ridge_blob_pores(r.gray, r.foreground, px_per_mm, params.ridge_blob);
    // Blob pores sit inside ridges, never in the bright valleys the minutiae are traced in.
    pore_mask = cv::Mat::zeros(r.bright.size(), CV_8U);
  } else {
    find_pores(r, px_per_mm, params, params.find_minutiae ? &pore_mask : nullptr, features);
  }
  if (params.find_minutiae) find_minutiae(r, pore_mask, px_per_mm, params, features);
  return features;
}

void write_features_csv(const std::filesystem::path& path, const std::vector<Feature>& features,
                        const Calibration& calibration) {
  auto out = csv::open_with_header(path, "type,x_px,y_px,x_mm,y_mm,orientation_rad");
  for (const auto& f : features) {
    const PointMm mm = to_mm(calibration, f.x_px, f.y_px);
    out << fmt::format("{},{:.4f},{:.4f},{:.5f},{:.5f},{:.5f}\n", feature_type_name(f.type), f.x_px,
                       f.y_px, mm.x_mm, mm.y_mm, f.orientation_rad);
  }
  csv::finish(out, path);
}

}  // namespace tactile::capture
