#include "pores/pore_blobs.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "pores/flank_levels.hpp"
#include "pores/pore_model.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {

namespace {

// Rows 0..rows in bands for `workers` workers, a few each so that an uneven band does not hold
// the others up; in order from the top.
std::vector<cv::Range> row_bands(int rows, int workers) {
  const int bands = workers <= 1 ? 1 : std::min(rows, 4 * workers);
  std::vector<cv::Range> out;
  for (int b = 0; b < bands; ++b) out.emplace_back(b * rows / bands, (b + 1) * rows / bands);
  return out;
}

// Grey level of the ridge (or valley) each pixel lies on, measured along the local ridge
// direction (from the structure tensor) on both sides of the pixel. Each pixel is filtered
// with its own direction's kernel only: filtering the whole image with every direction's kernel
// and then picking one per pixel gave the same levels at twelve times the work. The direction
// field is smooth, so most runs of eight pixels share one kernel and are filtered together.
cv::Mat ridge_level(const cv::Mat& gray, double px_per_mm, const RidgeBlobParams& p) {
  cv::Mat gx, gy;
  cv::Sobel(gray, gx, CV_32F, 1, 0);
  cv::Sobel(gray, gy, CV_32F, 0, 1);
  const std::array<cv::Mat, 3> products = {gx.mul(gx), gy.mul(gy), gx.mul(gy)};
  const double ts = p.orientation_sigma_mm * px_per_mm;
  std::array<cv::Mat, 3> tensor;
  for (auto& t : tensor) t.create(gray.size(), CV_32F);
  // Each product smoothed in two halves of rows, six jobs for the workers instead of three: a
  // filter reads the rows beyond its half from the whole image, so the halves join seamlessly.
  const int split = gray.rows / 2;
  parallel_for(2 * tensor.size(), std::max(1, p.threads), [&](std::size_t job) {
    const std::size_t k = job / 2;
    const cv::Range rows = job % 2 == 0 ? cv::Range(0, split) : cv::Range(split, gray.rows);
    if (rows.empty()) return;
    cv::Mat part = tensor[k].rowRange(rows);
    cv::GaussianBlur(products[k].rowRange(rows), part, cv::Size(0, 0), ts);
  });
  const cv::Mat &jxx = tensor[0], &jyy = tensor[1], &jxy = tensor[2];
  const int n = std::max(2, p.orientations);
  const FlankKernels kernels = flank_kernels(
      n, p.along_sigma_mm * px_per_mm, p.across_sigma_mm * px_per_mm, p.pore_radius_mm * px_per_mm);
  const int rows = 2 * kernels.half + 1;
  // Borders reflected as filter2D's BORDER_REFLECT; the extra columns on the right meet only
  // zero taps.
  cv::Mat padded;
  cv::copyMakeBorder(gray, padded, kernels.half, kernels.half, kernels.half,
                     kernels.half + kernels.stride - rows, cv::BORDER_REFLECT);
  cv::Mat out(gray.size(), CV_32F);
  const bool eight_at_once = has_flank_levels_of_eight();
  const bool sixteen_at_once = eight_at_once && has_flank_levels_of_sixteen();
  const int workers = std::max(1, p.threads);
  const std::vector<cv::Range> bands = row_bands(gray.rows, workers);
  parallel_for(bands.size(), workers, [&](std::size_t band) {
    std::vector<int> direction(static_cast<std::size_t>(gray.cols));
    for (int y = bands[band].start; y < bands[band].end; ++y) {
      const float* a = jxx.ptr<float>(y);
      const float* b = jyy.ptr<float>(y);
      const float* d = jxy.ptr<float>(y);
      float* o = out.ptr<float>(y);
      ridge_directions(a, b, d, gray.cols, n, direction.data());
      // Eight pixels of at most three directions (the field turns slowly: mostly one or two)
      // are filtered eight at a time once per direction, each pixel keeping its own
      // direction's level: the same bits as one pixel at a time, for less work.
      const auto eight = [&](int x) {
        const auto first = direction.begin() + x;
        std::array<int, 3> seen{};
        int distinct = 0;  // 4: more than three
        for (auto d = first; d != first + 8 && distinct <= 3; ++d) {
          const auto known = seen.begin() + distinct;
          if (std::find(seen.begin(), known, *d) != known) continue;
          if (distinct < 3) seen[static_cast<std::size_t>(distinct)] = *d;
          ++distinct;
        }
        if (distinct == 1) {
          flank_levels_of_eight(kernels, *first, padded, y, x, o + x);
        } else if (distinct <= 3) {
          std::array<float, 8> level{};
          for (int q = 0; q < distinct; ++q) {
            const int k = seen[static_cast<std::size_t>(q)];
            flank_levels_of_eight(kernels, k, padded, y, x, level.data());
            for (int u = 0; u < 8; ++u) {
              if (first[u] == k) o[x + u] = level[static_cast<std::size_t>(u)];
            }
          }
        } else {
          for (int u = x; u < x + 8; ++u) {
            o[u] = flank_level(kernels, direction[static_cast<std::size_t>(u)], padded, y, u);
          }
        }
      };
      int x = 0;
      // Sixteen pixels of one direction at once where the machine has the registers for them.
      if (sixteen_at_once) {
        for (; x + 16 <= gray.cols; x += 16) {
          const auto first = direction.begin() + x;
          if (std::all_of(first + 1, first + 16, [&](int k) { return k == *first; })) {
            flank_levels_of_sixteen(kernels, *first, padded, y, x, o + x);
          } else {
            eight(x);
            eight(x + 8);
          }
        }
      }
      if (eight_at_once) {
        for (; x + 8 <= gray.cols; x += 8) eight(x);
      }
      for (; x < gray.cols; ++x) {
        o[x] = flank_level(kernels, direction[static_cast<std::size_t>(x)], padded, y, x);
      }
    }
  });
  return out;
}

// Where a level lies between the local valley level (0) and the local ridge bottom (1), and
// the valley-to-ridge contrast itself. Pores sit in the inner part of a ridge; bright spots at
// a ridge's edge are mostly its ragged outline, and spots where the level is wrong (ridge
// endings, wide valleys) are valley.
struct Envelope {
  cv::Mat depth;
  cv::Mat contrast;
};

Envelope ridge_envelope(const cv::Mat& level, double px_per_mm, const RidgeBlobParams& p) {
  const int window = std::max(3, static_cast<int>(std::lround(p.window_mm * px_per_mm)) | 1);
  const cv::Mat box = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(window, window));
  cv::Mat valley, ridge;
  parallel_for(2, std::max(1, p.threads), [&](std::size_t k) {
    if (k == 0) {
      cv::dilate(level, valley, box);
    } else {
      cv::erode(level, ridge, box);
    }
  });
  Envelope e;
  e.contrast.create(level.size(), CV_32F);
  e.depth.create(level.size(), CV_32F);
  for (int y = 0; y < level.rows; ++y) {
    const float* v = valley.ptr<float>(y);
    const float* r = ridge.ptr<float>(y);
    const float* l = level.ptr<float>(y);
    float* c = e.contrast.ptr<float>(y);
    float* d = e.depth.ptr<float>(y);
    for (int x = 0; x < level.cols; ++x) {
      c[x] = v[x] - r[x];
      d[x] = (v[x] - l[x]) / std::max(c[x], 1.0f);
    }
  }
  return e;
}

// Robust spread (1.4826 x median absolute deviation, the standard deviation for Gaussian
// noise) of the response over the mask within `roi`; 0 when fewer than `min_count` pixels.
double robust_spread(const cv::Mat& response, const cv::Mat& mask, cv::Rect roi,
                     std::size_t min_count) {
  std::vector<float> v;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const float* r = response.ptr<float>(y);
    const std::uint8_t* m = mask.ptr<std::uint8_t>(y);
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      if (m[x]) v.push_back(r[x]);
    }
  }
  if (v.size() < std::max<std::size_t>(min_count, 1)) return 0.0;
  return 1.4826 * mad(std::move(v));
}

// quantile() of the values; `fallback` when there are none.
double quantile_or(const std::vector<double>& v, double fraction, double fallback) {
  return v.empty() ? fallback : quantile(v, fraction);
}

}  // namespace

std::vector<PoreCandidate> find_pore_candidates(const cv::Mat& gray, const cv::Mat& allowed,
                                                double px_per_mm, const RidgeBlobParams& p) {
  std::vector<PoreCandidate> found;
  if (gray.empty()) return found;
  const cv::Mat level = ridge_level(gray, px_per_mm, p);
  const cv::Mat above = gray - level;
  // Brightness above the pixel's own ridge level, smoothed to about a pixel against noise.
  cv::Mat response;
  cv::GaussianBlur(above, response, cv::Size(0, 0), p.pore_sigma_mm * px_per_mm);
  const Envelope envelope = ridge_envelope(level, px_per_mm, p);

  // Ridge texture noise, over the print and per block: the pore scale of a dark noisy print
  // differs from that of a clean one. Floors keep flat (test) images finite.
  const cv::Mat deep = envelope.depth >= p.noise_ridge_depth;
  constexpr double kMinNoise = 0.5;  // grey levels: far below any real print's (6-22)
  const int block = std::max(8, static_cast<int>(std::lround(p.noise_block_mm * px_per_mm)));
  cv::Mat block_noise((gray.rows + block - 1) / block, (gray.cols + block - 1) / block, CV_64F);
  // Blob size: scale-normalised Laplacian of the brightness above the ridge level, from a
  // dot of one pixel to one of about a tenth of a millimetre.
  constexpr std::array<double, 8> kScalesMm{0.011, 0.015, 0.019, 0.023, 0.028, 0.034, 0.043, 0.053};
  std::vector<cv::Mat> blob(kScalesMm.size());
  // One set of jobs for the workers: the print's noise (the longest), each blob scale, and
  // each row of blocks; a block with too few deep pixels takes the print's noise afterwards.
  double print_spread = 0;
  const std::size_t blob_jobs = kScalesMm.size();
  parallel_for(1 + blob_jobs + static_cast<std::size_t>(block_noise.rows), std::max(1, p.threads),
               [&](std::size_t job) {
                 if (job == 0) {
                   print_spread =
                       robust_spread(response, deep, cv::Rect(0, 0, gray.cols, gray.rows), 1);
                 } else if (job <= blob_jobs) {
                   const std::size_t k = job - 1;
                   const double s = kScalesMm[k] * px_per_mm;
                   cv::Mat smoothed;
                   cv::GaussianBlur(above, smoothed, cv::Size(0, 0), s);
                   cv::Laplacian(smoothed, blob[k], CV_32F);
                   blob[k] *= -s * s;
                 } else {
                   const int by = static_cast<int>(job - 1 - blob_jobs);
                   for (int bx = 0; bx < block_noise.cols; ++bx) {
                     const cv::Rect roi = cv::Rect(bx * block, by * block, block, block) &
                                          cv::Rect(0, 0, gray.cols, gray.rows);
                     block_noise.at<double>(by, bx) = robust_spread(response, deep, roi, 20);
                   }
                 }
               });
  const double print_noise = std::max(kMinNoise, print_spread);
  for (int by = 0; by < block_noise.rows; ++by) {
    for (int bx = 0; bx < block_noise.cols; ++bx) {
      double& s = block_noise.at<double>(by, bx);
      s = s > 0 ? std::max(kMinNoise, s) : print_noise;
    }
  }

  // Candidates: 3 x 3 maxima of the response (a ramp rising towards a valley has none), deep
  // enough in a ridge.
  cv::Mat local_max;
  cv::dilate(response, local_max, cv::Mat());
  // Bands of rows in parallel, joined in order: the candidates come out row by row as from one
  // pass.
  const int workers = std::max(1, p.threads);
  const std::vector<cv::Range> bands = row_bands(gray.rows, workers);
  std::vector<std::vector<PoreCandidate>> in_band(bands.size());
  parallel_for(bands.size(), workers, [&](std::size_t band) {
    for (int y = bands[band].start; y < bands[band].end; ++y) {
      const float* resp = response.ptr<float>(y);
      const float* lmax = local_max.ptr<float>(y);
      const float* depth = envelope.depth.ptr<float>(y);
      const std::uint8_t* ok = allowed.ptr<std::uint8_t>(y);
      for (int x = 0; x < gray.cols; ++x) {
        const float v = resp[x];
        if (!ok[x] || v < lmax[x] || depth[x] < p.min_ridge_depth) continue;
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
        // Measures 4, 13-15 need every candidate's response first (below).
        PoreCandidate c{x + dx, y + dy, {}};
        auto& m = c.measures;
        m[0] = v / print_noise;
        m[1] = v / block_noise.at<double>(y / block, x / block);
        m[2] = depth[x];
        m[3] = envelope.contrast.at<float>(y, x) / print_noise;
        for (std::size_t k = 0; k < blob.size(); ++k) {
          m[5 + k] = blob[k].at<float>(y, x) / print_noise;
        }
        in_band[band].push_back(c);
      }
    }
  });
  for (auto& b : in_band) found.insert(found.end(), b.begin(), b.end());
  // Against this print's own spots: the median deep candidate (mostly ridge texture) and the
  // 90th percentile (its clear pores). The same brightness is a pore on a faint print and a
  // speck on one whose pores stand out.
  std::vector<double> deep_responses;
  for (const auto& c : found) {
    if (c.measures[2] >= p.noise_ridge_depth) deep_responses.push_back(c.measures[0] * print_noise);
  }
  const double typical = std::max(kMinNoise, quantile_or(deep_responses, 0.5, print_noise));
  const double clear = std::max(kMinNoise, quantile_or(deep_responses, 0.9, print_noise));
  for (auto& c : found) {
    auto& m = c.measures;
    const double v = m[0] * print_noise;
    m[4] = v / typical;
    m[13] = v / clear;
    m[14] = m[7] * print_noise / clear;
    m[15] = m[9] * print_noise / clear;
  }
  return found;
}

std::vector<Feature> find_ridge_blob_pores(const cv::Mat& gray, const cv::Mat& allowed,
                                           double px_per_mm, const RidgeBlobParams& p) {
  struct Scored {
    Feature feature;
    double log_odds;
  };
  std::vector<Scored> kept;
  const std::span<const double> model = p.model.empty() ? shipped_pore_model() : p.model;
  check_pore_model(model);
  for (const auto& c : find_pore_candidates(gray, allowed, px_per_mm, p)) {
    const double log_odds = pore_log_odds(c.measures, model);
    if (log_odds > p.min_log_odds)
      kept.push_back({{FeatureType::pore, c.x_px, c.y_px, 0.0}, log_odds});
  }
  // Likeliest first; a candidate within the suppression radius of a kept pore is the same pore.
  std::sort(kept.begin(), kept.end(),
            [](const Scored& a, const Scored& b) { return a.log_odds > b.log_odds; });
  // Kept pores are binned in cells of side r: any within r of a candidate lies in its cell or
  // one of the eight around it.
  const double r = p.suppression_radius_mm * px_per_mm;
  const double cell = std::max(r, 1.0);
  const int cols = static_cast<int>(gray.cols / cell) + 1,
            rows = static_cast<int>(gray.rows / cell) + 1;
  std::vector<std::vector<std::size_t>> bins(static_cast<std::size_t>(cols) *
                                             static_cast<std::size_t>(rows));
  auto bin_of = [&](double v, int n) { return std::clamp(static_cast<int>(v / cell), 0, n - 1); };
  std::vector<Feature> pores;
  for (const auto& s : kept) {
    const int bx = bin_of(s.feature.x_px, cols), by = bin_of(s.feature.y_px, rows);
    bool taken = false;
    for (int y = std::max(0, by - 1); y <= std::min(rows - 1, by + 1) && !taken; ++y) {
      for (int x = std::max(0, bx - 1); x <= std::min(cols - 1, bx + 1) && !taken; ++x) {
        for (const std::size_t k : bins[static_cast<std::size_t>(y * cols + x)]) {
          if (std::hypot(pores[k].x_px - s.feature.x_px, pores[k].y_px - s.feature.y_px) < r) {
            taken = true;
            break;
          }
        }
      }
    }
    if (taken) continue;
    bins[static_cast<std::size_t>(by * cols + bx)].push_back(pores.size());
    pores.push_back(s.feature);
  }
  return pores;
}

}  // namespace tactile::capture
