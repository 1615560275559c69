#include "tactile/capture/print_warp.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <stdexcept>

#include "camera/cv_image.hpp"
#include "synthetic/carried_edge.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {

namespace {

constexpr double kPi = std::numbers::pi;

PointMm centre_mm(const PrintWarpSpec& s) {
  return {(s.width_px - 1) / (2 * s.px_per_mm), (s.height_px - 1) / (2 * s.px_per_mm)};
}

// Fraction of the sequence elapsed at `frame`, 0..1 (a little beyond within an exposure).
double progress_of(const PrintWarpSpec& s, double frame) {
  return s.frame_count > 1 ? frame / (s.frame_count - 1) : 0.0;
}

double smoothstep01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

double sigma_of(const PrintWarpSpec& s) {
  return s.width_mm / (2 * std::sqrt(2 * std::log(2.0)));
}

// A Gaussian displacement kernel of the random field: u = amplitude g(X - centre) direction,
// g of width sigma, with amplitude sin(2 pi t / period + phase).
struct Kernel {
  PointMm centre;  // relative to the field's centre
  double sigma_mm = 1, amplitude_mm = 0, direction_rad = 0, period_s = 1, phase_rad = 0;
};

// Everything about the warp that does not depend on the point, computed once per spec.
class Warp {
 public:
  explicit Warp(const PrintWarpSpec& s) : s_(s), c_(centre_mm(s)) {
    field_w_mm_ = s.width_px / s.px_per_mm;
    field_h_mm_ = s.height_px / s.px_per_mm;
    duration_s_ = sequence_duration_s(s);
    if (s.pattern == WarpPattern::kernels || s.pattern == WarpPattern::full_slip) make_kernels();
  }

  PointMm to_image(PointMm material, double frame) const {
    if (s_.pattern == WarpPattern::full_slip) {
      const PointMm p{material.x_mm - c_.x_mm + slid_mm(frame), material.y_mm - c_.y_mm};
      const PointMm w = glass_field(p);
      return {c_.x_mm + p.x_mm + w.x_mm, c_.y_mm + p.y_mm + w.y_mm};
    }
    const PointMm d{material.x_mm - c_.x_mm, material.y_mm - c_.y_mm};
    const PointMm u = displacement(d, frame);
    const double th = rotation_rad(frame);
    const double ex = d.x_mm + u.x_mm, ey = d.y_mm + u.y_mm;
    const double tau = progress_of(s_, frame);
    return {c_.x_mm + std::cos(th) * ex - std::sin(th) * ey + s_.slide_x_mm * tau,
            c_.y_mm + std::sin(th) * ex + std::cos(th) * ey + s_.slide_y_mm * tau};
  }

  PointMm to_material(PointMm image, double frame) const {
    if (s_.pattern == WarpPattern::full_slip) {
      // p + w(p) = q by fixed-point iteration, as below (w's gradient is at most the strain).
      const PointMm q{image.x_mm - c_.x_mm, image.y_mm - c_.y_mm};
      PointMm p = q;
      for (int i = 0; i < 60; ++i) {
        const PointMm w = glass_field(p);
        const PointMm next{q.x_mm - w.x_mm, q.y_mm - w.y_mm};
        const double step = std::hypot(next.x_mm - p.x_mm, next.y_mm - p.y_mm);
        p = next;
        if (step < 1e-12) break;
      }
      return {p.x_mm + c_.x_mm - slid_mm(frame), p.y_mm + c_.y_mm};
    }
    const double th = rotation_rad(frame);
    const double tau = progress_of(s_, frame);
    const double qx = image.x_mm - c_.x_mm - s_.slide_x_mm * tau;
    const double qy = image.y_mm - c_.y_mm - s_.slide_y_mm * tau;
    // d + u(d) = R^-1 q, solved by fixed-point iteration: u's gradient is at most the strain
    // (validate keeps it within 0.2; the random field's kernels add up to at most 2.5 times it),
    // so each step shrinks the error at least twofold.
    const PointMm y{std::cos(th) * qx + std::sin(th) * qy, -std::sin(th) * qx + std::cos(th) * qy};
    PointMm d = y;
    for (int i = 0; i < 60; ++i) {
      const PointMm u = displacement(d, frame);
      const PointMm next{y.x_mm - u.x_mm, y.y_mm - u.y_mm};
      const double step = std::hypot(next.x_mm - d.x_mm, next.y_mm - d.y_mm);
      d = next;
      if (step < 1e-12) break;
    }
    return {d.x_mm + c_.x_mm, d.y_mm + c_.y_mm};
  }

  // How much of the skin seen at `image` touches at `frame`: the lesser of the lift-off's and
  // the contact patch's.
  double contact(PointMm image, double frame) const {
    return std::min(lift_contact(image, frame), patch_contact(image, frame));
  }

 private:
  // A region fixed on the glass, a little right of and above the centre, lifts off in the middle
  // of the sequence and comes back down.
  double lift_contact(PointMm image, double frame) const {
    if (s_.contact_loss <= 0) return 1.0;
    const double lift_s = std::sin(kPi * std::clamp(progress_of(s_, frame), 0.0, 1.0));
    const double dx = image.x_mm - c_.x_mm - 0.2 * field_w_mm_;
    const double dy = image.y_mm - c_.y_mm + 0.15 * field_h_mm_;
    const double sigma = sigma_of(s_);
    const double lifted =
        s_.contact_loss * lift_s * lift_s * std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
    return 1 - smoothstep01((lifted - 0.35) / 0.3);
  }

  // The moving, breathing patch: 1 inside, 0 outside, over a rim of a tenth of its radius.
  double patch_contact(PointMm image, double frame) const {
    if (!has_contact_patch(s_)) return 1.0;
    const double t_s = time_s(frame) - duration_s_ / 2;
    const double size = 1 + s_.patch_breathing * std::sin(2 * kPi * progress_of(s_, frame));
    const double dx = (image.x_mm - c_.x_mm - s_.patch_speed_mm_per_s * t_s) / (0.4 * field_w_mm_);
    const double dy = (image.y_mm - c_.y_mm) / (0.4 * field_h_mm_);
    const double r = std::hypot(dx, dy) / size;
    return 1 - smoothstep01((r - 0.95) / 0.1);
  }

  double time_s(double frame) const { return frame / s_.frame_rate_hz; }

  // How far the skin has slid along x since the first frame (full slip).
  double slid_mm(double frame) const { return s_.travel_speed_mm_per_s * time_s(frame); }

  // The static field of full slip, at p (millimetres from the centre, undeformed): the random
  // field's kernels frozen at their peak, each with its own sign, so that skin crossing the view
  // is stretched and compressed in turn.
  PointMm glass_field(PointMm p) const {
    if (s_.strain == 0) return {0, 0};
    PointMm w{0, 0};
    for (std::size_t i = 0; i < kernels_.size(); ++i) {
      const auto& k = kernels_[i];
      const double dx = p.x_mm - k.centre.x_mm, dy = p.y_mm - k.centre.y_mm;
      const double a = (i % 2 == 0 ? 1.0 : -1.0) * k.amplitude_mm *
                       std::exp(-(dx * dx + dy * dy) / (2 * k.sigma_mm * k.sigma_mm));
      w.x_mm += a * std::cos(k.direction_rad);
      w.y_mm += a * std::sin(k.direction_rad);
    }
    return w;
  }

  double rotation_rad(double frame) const {
    return s_.rotation_deg * kPi / 180 * progress_of(s_, frame);
  }

  // Where a travelling pattern is, along x from the centre: it crosses the centre in the middle
  // of the sequence, at the travel speed or, without one, from beyond one edge to beyond the
  // other over the sequence.
  double travelled_mm(double frame) const {
    if (s_.travel_speed_mm_per_s > 0) {
      return s_.travel_speed_mm_per_s * (time_s(frame) - duration_s_ / 2);
    }
    return (progress_of(s_, frame) - 0.5) * (field_w_mm_ + 2 * s_.width_mm);
  }

  // Seconds a stick-slip cycle or a kernel's time course takes: the time the skin needs to
  // travel the pattern's width, or a third of the sequence without a speed.
  double cycle_s() const {
    return s_.travel_speed_mm_per_s > 0 ? s_.width_mm / s_.travel_speed_mm_per_s
                                        : std::max(duration_s_, 1e-9) / 3;
  }

  void make_kernels() {
    std::mt19937_64 rng(s_.seed * 0x2545F4914F6CDD1DULL + 7);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    constexpr int kKernels = 5;
    for (int k = 0; k < kKernels; ++k) {
      Kernel q;
      q.centre = {(unit(rng) - 0.5) * 0.7 * field_w_mm_, (unit(rng) - 0.5) * 0.7 * field_h_mm_};
      q.sigma_mm = sigma_of(s_) * (0.6 + 0.8 * unit(rng));
      // A kernel's largest strain is amplitude / (sigma sqrt(e)): each reaches half the peak,
      // so overlapping ones can come near it.
      q.amplitude_mm = 0.5 * s_.strain * q.sigma_mm * std::sqrt(std::exp(1.0));
      q.direction_rad = 2 * kPi * unit(rng);
      q.period_s = cycle_s() * (2 + 3 * unit(rng));
      q.phase_rad = 2 * kPi * unit(rng);
      kernels_.push_back(q);
    }
  }

  // The pattern's displacement u(X, f) in material millimetres; d = X - c.
  PointMm displacement(PointMm d, double frame) const {
    if (s_.pattern == WarpPattern::rigid || s_.strain == 0) return {0, 0};
    const double tau = progress_of(s_, frame);
    const double sigma = sigma_of(s_);
    switch (s_.pattern) {
      case WarpPattern::wave: {
        // Strain a cos(k (x - v t)): without a speed the wave moves one wavelength over the
        // sequence.
        const double a = s_.strain * std::sin(kPi * tau);
        const double k = 2 * kPi / s_.width_mm;
        const double shift = s_.travel_speed_mm_per_s > 0 ? s_.travel_speed_mm_per_s * time_s(frame)
                                                          : s_.width_mm * tau;
        return {a / k * std::sin(k * (d.x_mm - shift)), 0};
      }
      case WarpPattern::pulse: {
        const double x = d.x_mm - travelled_mm(frame);
        const double g = std::exp(-(x * x + d.y_mm * d.y_mm) / (2 * sigma * sigma));
        return {s_.strain * x * g, s_.strain * d.y_mm * g};
      }
      case WarpPattern::ridge: {
        // Strain -a g(x - x0): the skin behind the ridge has been pushed forward.
        const double z = (d.x_mm - travelled_mm(frame)) / (std::sqrt(2.0) * sigma);
        return {s_.strain * sigma * std::sqrt(kPi / 2) * std::erfc(z), 0};
      }
      case WarpPattern::stick_slip: {
        // The centre sticks while the rim is loaded, then the rim slips back within a sixth of
        // the cycle; the peak strain of the loaded annulus is the spec's strain.
        constexpr double q = 0.4;
        const double semi_x = 0.42 * field_w_mm_, semi_y = 0.42 * field_h_mm_;
        const double rho = std::hypot(d.x_mm / semi_x, d.y_mm / semi_y);
        const double phase = time_s(frame) / cycle_s() - std::floor(time_s(frame) / cycle_s());
        constexpr double stick = 5.0 / 6;
        const double load =
            phase < stick ? phase / stick : 1 - smoothstep01((phase - stick) / (1 - stick));
        const double rim_mm = s_.strain * semi_x * (1 - q) / 1.5;
        return {rim_mm * load * smoothstep01((rho - q) / (1 - q)), 0};
      }
      case WarpPattern::kernels: {
        PointMm u{0, 0};
        const double t = time_s(frame);
        for (const auto& k : kernels_) {
          const double dx = d.x_mm - k.centre.x_mm, dy = d.y_mm - k.centre.y_mm;
          const double a = k.amplitude_mm * std::sin(2 * kPi * t / k.period_s + k.phase_rad) *
                           std::exp(-(dx * dx + dy * dy) / (2 * k.sigma_mm * k.sigma_mm));
          u.x_mm += a * std::cos(k.direction_rad);
          u.y_mm += a * std::sin(k.direction_rad);
        }
        return u;
      }
      case WarpPattern::full_slip:
        return {0, 0};  // its field is the glass's (glass_field), not the skin's
      default:
        break;
    }
    const double a = s_.strain * std::sin(kPi * tau);
    const double g = std::exp(-(d.x_mm * d.x_mm + d.y_mm * d.y_mm) / (2 * sigma * sigma));
    switch (s_.pattern) {
      case WarpPattern::stretch:
        return {a * d.x_mm * g, 0};
      case WarpPattern::compress:
        return {0, -a * d.y_mm * g};
      default:  // bump
        return {a * d.x_mm * g, a * d.y_mm * g};
    }
  }

  const PrintWarpSpec& s_;
  PointMm c_;
  double field_w_mm_ = 0, field_h_mm_ = 0, duration_s_ = 0;
  std::vector<Kernel> kernels_;
};

// Lanczos (a = 4) weights for the 8 taps around a sample at fraction t of a pixel, normalised.
// The frames must move by exactly the warp. Cubic convolution (OpenCV's INTER_CUBIC) shifts a
// print's fine detail by a few hundredths of a pixel depending on the sample's fraction: on a
// pure slide of 0.4 px per frame an image tracker's step error was 0.06 px with it and 0.015 px
// (the tracker's own floor) with Lanczos-4 in double precision. The kernel, not remap's rounding
// of positions to 1/32 px, was the cause: an exact cubic gave the same error as remap.
std::array<double, 8> lanczos_weights(double t) {
  // sin(pi (k - t)) = -(-1)^k sin(pi t), and sin(pi (k - t) / 4) by the angle sum: four
  // trigonometric calls per axis instead of sixteen (a sample is taken many times per pixel).
  const double s1 = std::sin(kPi * t), s4 = std::sin(kPi * t / 4), c4 = std::cos(kPi * t / 4);
  constexpr double h = 0.70710678118654752440;  // sqrt(2) / 2
  // sin and cos of pi k / 4 for k = -3 .. 4.
  constexpr std::array<double, 8> sin_k{-h, -1, -h, 0, h, 1, h, 0};
  constexpr std::array<double, 8> cos_k{-h, 0, h, 1, h, 0, -h, -1};
  std::array<double, 8> w{};
  double sum = 0;
  for (int i = 0; i < 8; ++i) {
    const int k = i - 3;
    const auto u = static_cast<std::size_t>(i);
    const double d = k - t;
    double v = 1.0;
    if (std::abs(d) >= 1e-12) {
      const double sin_pd = (k % 2 == 0 ? -1.0 : 1.0) * s1;
      const double sin_pd4 = sin_k[u] * c4 - cos_k[u] * s4;
      v = sin_pd * sin_pd4 / (kPi * kPi * d * d / 4);
    }
    w[u] = v;
    sum += v;
  }
  for (auto& v : w) v /= sum;
  return w;
}

// An index into 0..n-1 of the source mirrored at its border pixels without end (period
// 2 (n - 1)), so that neighbouring copies meet without a step.
int mirrored(int i, int n) {
  if (n < 2) return 0;
  const int period = 2 * (n - 1);
  int r = i % period;
  if (r < 0) r += period;
  return r < n ? r : period - r;
}

// The span [begin, end) of `contrast` left once the runs at both ends that fall below 0.7 of its
// median are cut, each at most a third of the whole: a print's border where the finger did not
// touch the glass, flat grey, and the band before it where the ridges fade out over part of the
// height (PolyU print 12's right edge: 18-24 grey levels across the print, 13-15 in the fading
// band, 2-10 in the flat border). Mirrored into a sliding view, either shows as skin out of
// contact where the scene's truth says it touches.
std::pair<int, int> touched_span(const std::vector<double>& contrast) {
  const int n = static_cast<int>(contrast.size());
  std::vector<double> sorted = contrast;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double low = 0.7 * sorted[static_cast<std::size_t>(n / 2)];
  const auto flat = [&](int i) { return contrast[static_cast<std::size_t>(i)] < low; };
  int begin = 0, end = n;
  while (begin < n / 3 && flat(begin)) ++begin;
  while (end > n - n / 3 && flat(end - 1)) --end;
  return {begin, end};
}

// The part of a print (CV_32F) between the untouched borders of touched_span.
cv::Rect touched_area(const cv::Mat& print) {
  // Contrast of the ridges: the standard deviation of each column and each row of the print
  // less its shading (a blur wider than a ridge period), so that a lamp's gradient across a
  // flat border does not count as texture.
  cv::Mat shading;
  cv::GaussianBlur(print, shading, {0, 0}, 8);
  const cv::Mat texture = print - shading;
  cv::Mat squared = texture.mul(texture);
  cv::Mat col_power, row_power;
  cv::reduce(squared, col_power, 0, cv::REDUCE_AVG, CV_64F);
  cv::reduce(squared, row_power, 1, cv::REDUCE_AVG, CV_64F);
  std::vector<double> cols(col_power.begin<double>(), col_power.end<double>());
  std::vector<double> rows(row_power.begin<double>(), row_power.end<double>());
  for (auto* v : {&cols, &rows}) {
    for (double& p : *v) p = std::sqrt(p);
  }
  const auto [x0, x1] = touched_span(cols);
  const auto [y0, y1] = touched_span(rows);
  return {x0, y0, x1 - x0, y1 - y0};
}

// `source` (CV_32F) at (x, y); `outside` beyond its border (skin out of contact), or with
// `mirror` the source's `area` mirrored without end.
float sample_lanczos(const cv::Mat& source, double x, double y, float outside, bool mirror,
                     const cv::Rect& area) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto wx = lanczos_weights(x - fx), wy = lanczos_weights(y - fy);
  const int x0 = static_cast<int>(fx) - 3, y0 = static_cast<int>(fy) - 3;
  double sum = 0;
  for (int j = 0; j < 8; ++j) {
    const int yy = y0 + j;
    double row = 0;
    for (int i = 0; i < 8; ++i) {
      const int xx = x0 + i;
      const bool inside = xx >= 0 && yy >= 0 && xx < source.cols && yy < source.rows;
      const float grey = mirror   ? source.at<float>(area.y + mirrored(yy - area.y, area.height),
                                                   area.x + mirrored(xx - area.x, area.width))
                         : inside ? source.at<float>(yy, xx)
                                  : outside;
      row += wx[static_cast<std::size_t>(i)] * grey;
    }
    sum += wy[static_cast<std::size_t>(j)] * row;
  }
  return static_cast<float>(sum);
}

}  // namespace

WarpPattern parse_warp_pattern(std::string_view name) {
  return parse_name("warp pattern", name, kWarpPatternNames);
}

std::string to_string(WarpPattern pattern) {
  return name_in(kWarpPatternNames, pattern);
}

void validate_print_warp(const PrintWarpSpec& s) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("invalid print warp: " + what);
  };
  if (!(s.px_per_mm >= 5 && s.px_per_mm <= 500)) {
    fail(fmt::format("px_per_mm {} is out of range: must be 5 to 500", s.px_per_mm));
  }
  if (s.width_px < 16 || s.height_px < 16 || s.width_px > 8192 || s.height_px > 8192) {
    fail(fmt::format("the print is {} x {} px: must be 16 to 8192 px on each side", s.width_px,
                     s.height_px));
  }
  if (!(std::abs(s.strain) <= 0.2)) {
    fail(fmt::format("strain {} is out of range: must be -0.2 to 0.2 (20 %)", s.strain));
  }
  if (!(s.width_mm >= 0.5 && s.width_mm <= 50)) {
    fail(fmt::format("width_mm {} is out of range: must be 0.5 to 50", s.width_mm));
  }
  if (!(std::abs(s.slide_x_mm) <= 5 && std::abs(s.slide_y_mm) <= 5)) {
    fail("slide must be within 5 mm on each axis");
  }
  if (!(std::abs(s.rotation_deg) <= 30)) fail("rotation_deg must be within +-30");
  if (s.frame_count < 2 || s.frame_count > 10000) fail("frame_count must be 2 to 10000");
  if (!(s.frame_rate_hz > 0 && s.frame_rate_hz <= 100000)) fail("frame_rate_hz must be > 0");
  if (!(s.blur_sigma_px >= 0 && s.blur_sigma_px <= 10)) fail("blur_sigma_px must be 0 to 10");
  if (!(s.noise_sigma >= 0 && s.noise_sigma <= 100)) fail("noise_sigma must be 0 to 100");
  if (!(std::abs(s.brightness_drift) <= 0.5)) fail("brightness_drift must be within +-0.5");
  if (!(s.travel_speed_mm_per_s >= 0 && s.travel_speed_mm_per_s <= 1000)) {
    fail(fmt::format("travel_speed_mm_per_s {} is out of range: must be 0 to 1000",
                     s.travel_speed_mm_per_s));
  }
  if (!(s.exposure_s >= 0 && s.exposure_s * s.frame_rate_hz <= 1)) {
    fail(fmt::format("exposure_s {} is out of range: must be 0 to one frame ({:.4g} s)",
                     s.exposure_s, 1 / s.frame_rate_hz));
  }
  if (s.supersample < 1 || s.supersample > 8) {
    fail(fmt::format("supersample {} is out of range: must be 1 to 8", s.supersample));
  }
  if (s.pattern == WarpPattern::full_slip && !(s.travel_speed_mm_per_s > 0)) {
    fail("full slip needs travel_speed_mm_per_s > 0 (the skin's speed through the view)");
  }
  if (!(s.contact_loss >= 0 && s.contact_loss <= 1)) {
    fail(fmt::format("contact_loss {} is out of range: must be 0 to 1", s.contact_loss));
  }
  // The patch's centre stays within the view's middle: at most a view's width of travel.
  if (!(std::abs(s.patch_speed_mm_per_s * sequence_duration_s(s)) <= s.width_px / s.px_per_mm)) {
    fail(
        fmt::format("patch_speed_mm_per_s {} is out of range: the patch would travel more than "
                    "the view's width ({:.3g} mm) in the sequence's {:.3g} s",
                    s.patch_speed_mm_per_s, s.width_px / s.px_per_mm, sequence_duration_s(s)));
  }
  if (!(s.patch_breathing >= 0 && s.patch_breathing <= 0.5)) {
    fail(fmt::format("patch_breathing {} is out of range: must be 0 to 0.5", s.patch_breathing));
  }
}

double sequence_duration_s(const PrintWarpSpec& s) {
  return (s.frame_count - 1) / s.frame_rate_hz;
}

PointMm warp_to_image(const PrintWarpSpec& s, PointMm material, double frame) {
  return Warp(s).to_image(material, frame);
}

PointMm warp_to_material(const PrintWarpSpec& s, PointMm image, double frame) {
  return Warp(s).to_material(image, frame);
}

bool has_contact_patch(const PrintWarpSpec& s) {
  return s.patch_speed_mm_per_s != 0 || s.patch_breathing > 0;
}

double warp_contact(const PrintWarpSpec& s, PointMm image, double frame) {
  return Warp(s).contact(image, frame);
}

double warp_least_contact(const PrintWarpSpec& s, double frame, int step_px) {
  if (step_px < 1) throw std::invalid_argument("warp_least_contact: a step of at least 1 px");
  const Warp warp(s);
  double least = 1.0;
  for (int y = 0; y < s.height_px; y += step_px) {
    for (int x = 0; x < s.width_px; x += step_px) {
      least = std::min(least, warp.contact({x / s.px_per_mm, y / s.px_per_mm}, frame));
    }
  }
  return least;
}

double warp_rel_change(const PrintWarpSpec& s, PointMm a_from, PointMm b_from, int frame_from,
                       int frame_to) {
  const Warp warp(s);
  const auto [before, after] = carried_edge(a_from, b_from, [&](PointMm p) {
    return warp.to_image(warp.to_material(p, frame_from), frame_to);
  });
  return before > 0 ? (after - before) / before : 0.0;
}

PrintSequence render_print_sequence(const PrintWarpSpec& spec, const GrayImage& print,
                                    const std::vector<std::array<double, 2>>& marks_px) {
  validate_print_warp(spec);
  if (print.width_px != spec.width_px || print.height_px != spec.height_px) {
    throw std::invalid_argument(fmt::format("the print is {} x {} px but the spec says {} x {} px",
                                            print.width_px, print.height_px, spec.width_px,
                                            spec.height_px));
  }
  PrintSequence seq;
  seq.spec = spec;
  seq.calibration = uniform_calibration(spec.px_per_mm, spec.width_px, spec.height_px);
  seq.calibration.method = fmt::format("px-per-mm {}", spec.px_per_mm);
  cv::Mat source;
  as_mat(print).convertTo(source, CV_32F);
  // Full slip brings skin from far beyond the print into view: mirrored from the print's
  // touched area only, so a border the finger did not touch is not shown as skin in contact.
  const bool mirror = spec.pattern == WarpPattern::full_slip;
  const cv::Rect area = mirror ? touched_area(source) : cv::Rect(0, 0, source.cols, source.rows);
  // A mark in a border left out is not where the frames show its pore (they show the mirror
  // image of the touched area there).
  for (const auto& m : marks_px) {
    if (!mirror || (m[0] >= area.x && m[0] < area.x + area.width && m[1] >= area.y &&
                    m[1] < area.y + area.height)) {
      seq.marks_px.push_back(m);
    }
  }
  // Skin that slides in from outside the print is shown as the print's valleys: bright, no
  // ridges, as skin out of contact is in a prism.
  const auto background = static_cast<float>(
      quantile(std::vector<float>(source.begin<float>(), source.end<float>()), 0.9));

  const int w = spec.width_px, h = spec.height_px;
  const Warp warp(spec);
  // Each pixel averages the moving image over its area and the shutter time: n x n points on
  // the pixel, each at its own instant of the exposure (stratified, so that n^2 samples cover
  // both), which is what a sensor integrates.
  struct Offset {
    double dx_px, dy_px, dframe;
  };
  std::vector<Offset> offsets;
  const int n = spec.supersample;
  const double exposure_frames = spec.exposure_s * spec.frame_rate_hz;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      // A Latin-square order of instants: neighbouring points of the pixel get distant ones.
      const int slot = (i * n + (j + i) % n) % (n * n);
      offsets.push_back({(i + 0.5) / n - 0.5, (j + 0.5) / n - 0.5,
                         exposure_frames * ((slot + 0.5) / (n * n) - 0.5)});
    }
  }
  seq.frames.resize(static_cast<std::size_t>(spec.frame_count));
  cv::parallel_for_(cv::Range(0, spec.frame_count), [&](const cv::Range& range) {
    for (int f = range.start; f < range.end; ++f) {
      cv::Mat frame(h, w, CV_32F);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          double sum = 0;
          for (const auto& o : offsets) {
            const PointMm at{(x + o.dx_px) / spec.px_per_mm, (y + o.dy_px) / spec.px_per_mm};
            const double instant = f + o.dframe;
            const PointMm m = warp.to_material(at, instant);
            const double grey = sample_lanczos(source, m.x_mm * spec.px_per_mm,
                                               m.y_mm * spec.px_per_mm, background, mirror, area);
            const double touch = warp.contact(at, instant);
            sum += touch * grey + (1 - touch) * background;
          }
          frame.at<float>(y, x) = static_cast<float>(sum / static_cast<double>(offsets.size()));
        }
      }
      const double tau = progress_of(spec, f);
      // Exposure drifts over the sequence, a little more on the right (a lamp warming up).
      cv::Mat gain(h, w, CV_32F);
      for (int x = 0; x < w; ++x) {
        gain.col(x).setTo(1 + spec.brightness_drift * tau * (0.7 + 0.6 * x / std::max(1, w - 1)));
      }
      frame = frame.mul(gain);
      if (spec.blur_sigma_px > 0) cv::GaussianBlur(frame, frame, {0, 0}, spec.blur_sigma_px);
      if (spec.noise_sigma > 0) {
        cv::RNG rng(spec.seed * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(f) + 1);
        cv::Mat noise(frame.size(), CV_32F);
        rng.fill(noise, cv::RNG::NORMAL, 0.0, spec.noise_sigma);
        frame += noise;
      }
      cv::Mat out;
      frame.convertTo(out, CV_8U);
      seq.frames[static_cast<std::size_t>(f)] = from_mat(out);
    }
  });

  for (int f = 0; f < spec.frame_count; ++f) {
    for (std::size_t i = 0; i < seq.marks_px.size(); ++i) {
      const auto& m = seq.marks_px[i];
      const PointMm x = warp.to_image({m[0] / spec.px_per_mm, m[1] / spec.px_per_mm}, f);
      const double x_px = x.x_mm * spec.px_per_mm, y_px = x.y_mm * spec.px_per_mm;
      if (x_px < 0 || y_px < 0 || x_px > w - 1 || y_px > h - 1) continue;
      if (warp.contact(x, f) < 0.5) continue;
      seq.landmarks.push_back(
          {static_cast<std::int32_t>(i), FeatureType::pore, f, x_px, y_px, x.x_mm, x.y_mm, 0.0});
    }
  }
  return seq;
}

void write_print_sequence(const std::filesystem::path& dir, const PrintSequence& seq,
                          const std::filesystem::path& print, const std::string& command_line) {
  write_frames(dir, seq.frames);
  write_landmarks_csv(dir / "landmarks.csv", seq.landmarks);
  const PrintWarpSpec& s = seq.spec;
  nlohmann::json j;
  j["format"] = "tactile-print-warp";
  j["format_version"] = 1;
  j["warp"] = {{"source", s.source},
               {"px_per_mm", s.px_per_mm},
               {"width_px", s.width_px},
               {"height_px", s.height_px},
               {"pattern", std::string(to_string(s.pattern))},
               {"strain", s.strain},
               {"width_mm", s.width_mm},
               {"slide_x_mm", s.slide_x_mm},
               {"slide_y_mm", s.slide_y_mm},
               {"rotation_deg", s.rotation_deg},
               {"frame_count", s.frame_count},
               {"frame_rate_hz", s.frame_rate_hz},
               {"blur_sigma_px", s.blur_sigma_px},
               {"noise_sigma", s.noise_sigma},
               {"brightness_drift", s.brightness_drift},
               {"travel_speed_mm_per_s", s.travel_speed_mm_per_s},
               {"exposure_s", s.exposure_s},
               {"supersample", s.supersample},
               {"contact_loss", s.contact_loss},
               {"patch_speed_mm_per_s", s.patch_speed_mm_per_s},
               {"patch_breathing", s.patch_breathing},
               {"seed", s.seed}};
  Provenance provenance = make_provenance(print.string(), "print warp", j["warp"].dump());
  provenance.command_line = command_line;
  j["provenance"] = provenance_json(provenance);
  j["marks"] = seq.marks_px.size();
  j["frames"] = frame_files_text(seq.frames.size());
  write_text_atomically(dir / "scene.json", j.dump(2) + "\n");
}

}  // namespace tactile::capture
