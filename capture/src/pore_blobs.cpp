#include "pore_blobs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

namespace tactile::capture {

namespace {

// Anisotropic Gaussian, long axis at `angle_rad` (image x to the right, y down), unit sum,
// with the middle band |along| < gap_px left out: the level it measures at a pixel comes from
// either side of it along the ridge, so a pore does not lift its own ridge level.
cv::Mat flank_kernel(double angle_rad, double along_px, double across_px, double gap_px) {
  const int half = std::max(1, static_cast<int>(std::ceil(3.0 * along_px)));
  cv::Mat k(2 * half + 1, 2 * half + 1, CV_32F);
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  double sum = 0;
  for (int y = -half; y <= half; ++y) {
    for (int x = -half; x <= half; ++x) {
      const double u = x * c + y * s;
      const double v = -x * s + y * c;
      const double w =
          std::abs(u) < gap_px
              ? 0.0
              : std::exp(-u * u / (2 * along_px * along_px) - v * v / (2 * across_px * across_px));
      k.at<float>(y + half, x + half) = static_cast<float>(w);
      sum += w;
    }
  }
  return k / sum;
}

// Grey level of the ridge (or valley) each pixel lies on, measured along the local ridge
// direction (from the structure tensor) on both sides of the pixel.
cv::Mat ridge_level(const cv::Mat& gray, double px_per_mm, const RidgeBlobParams& p) {
  cv::Mat gx, gy;
  cv::Sobel(gray, gx, CV_32F, 1, 0);
  cv::Sobel(gray, gy, CV_32F, 0, 1);
  cv::Mat jxx = gx.mul(gx), jyy = gy.mul(gy), jxy = gx.mul(gy);
  const double ts = p.orientation_sigma_mm * px_per_mm;
  for (cv::Mat* m : {&jxx, &jyy, &jxy}) cv::GaussianBlur(*m, *m, cv::Size(0, 0), ts);
  const int n = std::max(2, p.orientations);
  const double step = std::numbers::pi / n;
  std::vector<cv::Mat> smoothed(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const cv::Mat kernel =
        flank_kernel(k * step, p.along_sigma_mm * px_per_mm, p.across_sigma_mm * px_per_mm,
                     p.pore_radius_mm * px_per_mm);
    cv::filter2D(gray, smoothed[static_cast<std::size_t>(k)], CV_32F, kernel, cv::Point(-1, -1), 0,
                 cv::BORDER_REFLECT);
  }
  cv::Mat out(gray.size(), CV_32F);
  for (int y = 0; y < gray.rows; ++y) {
    const float* a = jxx.ptr<float>(y);
    const float* b = jyy.ptr<float>(y);
    const float* d = jxy.ptr<float>(y);
    float* o = out.ptr<float>(y);
    for (int x = 0; x < gray.cols; ++x) {
      // The dominant gradient is across the ridges; the ridge runs at right angles to it.
      const double ridge = 0.5 * std::atan2(2.0 * d[x], a[x] - b[x]) + std::numbers::pi / 2;
      const int k = ((static_cast<int>(std::lround(ridge / step)) % n) + n) % n;
      o[x] = smoothed[static_cast<std::size_t>(k)].at<float>(y, x);
    }
  }
  return out;
}

// Where a level lies between the local valley level (0) and the local ridge bottom (1). Pores
// sit in the inner part of a ridge; bright spots at a ridge's edge are mostly its ragged
// outline, and spots where the level is wrong (ridge endings, wide valleys) are valley.
cv::Mat ridge_depth(const cv::Mat& level, double px_per_mm, const RidgeBlobParams& p) {
  const int window = std::max(3, static_cast<int>(std::lround(p.window_mm * px_per_mm)) | 1);
  const cv::Mat box = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(window, window));
  cv::Mat valley, ridge;
  cv::dilate(level, valley, box);
  cv::erode(level, ridge, box);
  return (valley - level) / cv::max(valley - ridge, 1.0);
}

}  // namespace

std::vector<Feature> find_ridge_blob_pores(const cv::Mat& gray, const cv::Mat& allowed,
                                           double px_per_mm, const RidgeBlobParams& p) {
  const cv::Mat level = ridge_level(gray, px_per_mm, p);
  // Brightness above the pixel's own ridge level, smoothed to about a pixel against noise.
  cv::Mat response;
  cv::GaussianBlur(gray - level, response, cv::Size(0, 0), p.pore_sigma_mm * px_per_mm);
  const cv::Mat inner = ridge_depth(level, px_per_mm, p) >= p.min_ridge_depth;

  // A pore is a local maximum of the response in its 3 x 3 neighbourhood (a ramp rising
  // towards a valley has none) and the strongest inner-ridge pixel within the suppression
  // radius (valley pixels do not compete: a valley edge would suppress a pore beside it).
  cv::Mat local_max;
  cv::dilate(response, local_max, cv::Mat());
  cv::Mat inner_response = response.clone();
  inner_response.setTo(-1e9, ~inner);
  const int r = std::max(1, static_cast<int>(std::lround(p.suppression_radius_mm * px_per_mm)));
  cv::Mat inner_max;
  cv::dilate(inner_response, inner_max,
             cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));

  struct Candidate {
    Feature feature;
    float response;
  };
  std::vector<Candidate> found;
  for (int y = 0; y < gray.rows; ++y) {
    const float* resp = response.ptr<float>(y);
    const float* lmax = local_max.ptr<float>(y);
    const float* imax = inner_max.ptr<float>(y);
    const std::uint8_t* in = inner.ptr<std::uint8_t>(y);
    const std::uint8_t* ok = allowed.ptr<std::uint8_t>(y);
    for (int x = 0; x < gray.cols; ++x) {
      const float v = resp[x];
      if (!in[x] || !ok[x] || v < lmax[x] || v < imax[x]) continue;
      // Sub-pixel peak: a parabola through the neighbours along each axis, kept within half a
      // pixel (a nearly flat top would otherwise throw the peak far away).
      auto offset = [v](float before, float after) {
        const double curvature = before - 2.0 * v + after;
        return curvature < 0 ? std::clamp(0.5 * (before - after) / curvature, -0.5, 0.5) : 0.0;
      };
      const double dx = (x > 0 && x + 1 < gray.cols) ? offset(resp[x - 1], resp[x + 1]) : 0.0;
      const double dy = (y > 0 && y + 1 < gray.rows)
                            ? offset(response.at<float>(y - 1, x), response.at<float>(y + 1, x))
                            : 0.0;
      found.push_back({{FeatureType::pore, x + dx, y + dy, 0.0}, v});
    }
  }
  // Scale of this image's pores: faint maxima far below the typical one are texture noise.
  std::vector<Feature> pores;
  if (found.empty()) return pores;
  std::vector<float> responses;
  for (const auto& c : found) responses.push_back(c.response);
  const auto mid = responses.begin() + static_cast<std::ptrdiff_t>(responses.size() / 2);
  std::nth_element(responses.begin(), mid, responses.end());
  const double floor = p.min_relative_response * *mid;
  for (const auto& c : found) {
    if (c.response >= floor) pores.push_back(c.feature);
  }
  return pores;
}

}  // namespace tactile::capture
