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
#include <stdexcept>

#include "camera/cv_image.hpp"
#include "tactile/common/atomic_write.hpp"

namespace tactile::capture {

namespace {

constexpr double kPi = std::numbers::pi;

struct Names {
  WarpPattern pattern;
  const char* name;
};
constexpr Names kNames[] = {{WarpPattern::rigid, "rigid"},
                            {WarpPattern::stretch, "stretch"},
                            {WarpPattern::compress, "compress"},
                            {WarpPattern::bump, "bump"},
                            {WarpPattern::wave, "wave"}};

PointMm centre_mm(const PrintWarpSpec& s) {
  return {(s.width_px - 1) / (2 * s.px_per_mm), (s.height_px - 1) / (2 * s.px_per_mm)};
}

// Fraction of the sequence elapsed at `frame`, 0..1.
double progress_of(const PrintWarpSpec& s, int frame) {
  return s.frame_count > 1 ? static_cast<double>(frame) / (s.frame_count - 1) : 0.0;
}

// The pattern's displacement u(X, f) in material millimetres; d = X - c.
PointMm pattern_displacement(const PrintWarpSpec& s, PointMm d, int frame) {
  const double tau = progress_of(s, frame);
  const double a = s.strain * std::sin(kPi * tau);
  if (s.pattern == WarpPattern::rigid || a == 0) return {0, 0};
  if (s.pattern == WarpPattern::wave) {
    // Strain a cos(k (x - v t)): the wave moves one wavelength over the sequence.
    const double k = 2 * kPi / s.width_mm;
    return {a / k * std::sin(k * (d.x_mm - s.width_mm * tau)), 0};
  }
  const double sigma = s.width_mm / (2 * std::sqrt(2 * std::log(2.0)));
  const double g = std::exp(-(d.x_mm * d.x_mm + d.y_mm * d.y_mm) / (2 * sigma * sigma));
  switch (s.pattern) {
    case WarpPattern::stretch:
      return {a * d.x_mm * g, 0};
    case WarpPattern::compress:
      return {0, -a * d.y_mm * g};
    default:  // bump
      return {a * d.x_mm * g, a * d.y_mm * g};
  }
}

// Lanczos (a = 4) weights for the 8 taps around a sample at fraction t of a pixel, normalised.
// The frames must move by exactly the warp. Cubic convolution (OpenCV's INTER_CUBIC) shifts a
// print's fine detail by a few hundredths of a pixel depending on the sample's fraction: on a
// pure slide of 0.4 px per frame an image tracker's step error was 0.06 px with it and 0.015 px
// (the tracker's own floor) with Lanczos-4 in double precision. The kernel, not remap's rounding
// of positions to 1/32 px, was the cause: an exact cubic gave the same error as remap.
std::array<double, 8> lanczos_weights(double t) {
  std::array<double, 8> w{};
  double sum = 0;
  for (int i = 0; i < 8; ++i) {
    const double d = (i - 3) - t;
    const double v = std::abs(d) < 1e-12
                         ? 1.0
                         : std::sin(kPi * d) * std::sin(kPi * d / 4) / (kPi * kPi * d * d / 4);
    w[static_cast<std::size_t>(i)] = v;
    sum += v;
  }
  for (auto& v : w) v /= sum;
  return w;
}

// `source` (CV_32F) at (x, y); `outside` beyond its border (skin out of contact).
float sample_lanczos(const cv::Mat& source, double x, double y, float outside) {
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
      row += wx[static_cast<std::size_t>(i)] * (inside ? source.at<float>(yy, xx) : outside);
    }
    sum += wy[static_cast<std::size_t>(j)] * row;
  }
  return static_cast<float>(sum);
}

double rotation_rad(const PrintWarpSpec& s, int frame) {
  return s.rotation_deg * kPi / 180 * progress_of(s, frame);
}

}  // namespace

WarpPattern parse_warp_pattern(std::string_view name) {
  for (const auto& n : kNames) {
    if (name == n.name) return n.pattern;
  }
  throw std::invalid_argument(fmt::format("warp pattern '{}' is not one of {}", name,
                                          fmt::join(warp_pattern_names(), ", ")));
}

std::string_view to_string(WarpPattern pattern) {
  for (const auto& n : kNames) {
    if (n.pattern == pattern) return n.name;
  }
  return "unknown";
}

const std::vector<std::string>& warp_pattern_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const auto& n : kNames) v.emplace_back(n.name);
    return v;
  }();
  return names;
}

void validate(const PrintWarpSpec& s) {
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
}

PointMm warp_to_image(const PrintWarpSpec& s, PointMm material, int frame) {
  const PointMm c = centre_mm(s);
  const PointMm d{material.x_mm - c.x_mm, material.y_mm - c.y_mm};
  const PointMm u = pattern_displacement(s, d, frame);
  const double th = rotation_rad(s, frame);
  const double ex = d.x_mm + u.x_mm, ey = d.y_mm + u.y_mm;
  const double tau = progress_of(s, frame);
  return {c.x_mm + std::cos(th) * ex - std::sin(th) * ey + s.slide_x_mm * tau,
          c.y_mm + std::sin(th) * ex + std::cos(th) * ey + s.slide_y_mm * tau};
}

PointMm warp_to_material(const PrintWarpSpec& s, PointMm image, int frame) {
  const PointMm c = centre_mm(s);
  const double th = rotation_rad(s, frame);
  const double tau = progress_of(s, frame);
  const double qx = image.x_mm - c.x_mm - s.slide_x_mm * tau;
  const double qy = image.y_mm - c.y_mm - s.slide_y_mm * tau;
  // d + u(d) = R^-1 q, solved by fixed-point iteration: u's gradient is at most the strain
  // (validate keeps it within 0.2), so each step shrinks the error at least fivefold.
  const PointMm y{std::cos(th) * qx + std::sin(th) * qy, -std::sin(th) * qx + std::cos(th) * qy};
  PointMm d = y;
  for (int i = 0; i < 30; ++i) {
    const PointMm u = pattern_displacement(s, d, frame);
    const PointMm next{y.x_mm - u.x_mm, y.y_mm - u.y_mm};
    const double step = std::hypot(next.x_mm - d.x_mm, next.y_mm - d.y_mm);
    d = next;
    if (step < 1e-12) break;
  }
  return {d.x_mm + c.x_mm, d.y_mm + c.y_mm};
}

double warp_rel_change(const PrintWarpSpec& s, PointMm a_from, PointMm b_from, int frame_from,
                       int frame_to) {
  const PointMm a = warp_to_image(s, warp_to_material(s, a_from, frame_from), frame_to);
  const PointMm b = warp_to_image(s, warp_to_material(s, b_from, frame_from), frame_to);
  const double before = std::hypot(b_from.x_mm - a_from.x_mm, b_from.y_mm - a_from.y_mm);
  const double after = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
  return before > 0 ? (after - before) / before : 0.0;
}

PrintSequence render_print_sequence(const PrintWarpSpec& spec, const GrayImage& print,
                                    const std::vector<std::array<double, 2>>& marks_px) {
  validate(spec);
  if (print.width_px != spec.width_px || print.height_px != spec.height_px) {
    throw std::invalid_argument(fmt::format("the print is {} x {} px but the spec says {} x {} px",
                                            print.width_px, print.height_px, spec.width_px,
                                            spec.height_px));
  }
  PrintSequence seq;
  seq.spec = spec;
  seq.calibration = uniform_calibration(spec.px_per_mm, spec.width_px, spec.height_px);
  seq.calibration.method = fmt::format("px-per-mm {}", spec.px_per_mm);
  seq.marks_px = marks_px;

  cv::Mat source;
  as_mat(print).convertTo(source, CV_32F);
  // Skin that slides in from outside the print is shown as the print's valleys: bright, no
  // ridges, as skin out of contact is in a prism.
  std::vector<float> values(source.begin<float>(), source.end<float>());
  std::nth_element(values.begin(), values.begin() + static_cast<long>(values.size() * 9 / 10),
                   values.end());
  const float background = values[values.size() * 9 / 10];

  const int w = spec.width_px, h = spec.height_px;
  seq.frames.resize(static_cast<std::size_t>(spec.frame_count));
  cv::parallel_for_(cv::Range(0, spec.frame_count), [&](const cv::Range& range) {
    for (int f = range.start; f < range.end; ++f) {
      cv::Mat frame(h, w, CV_32F);
      for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
          const PointMm m = warp_to_material(spec, {x / spec.px_per_mm, y / spec.px_per_mm}, f);
          frame.at<float>(y, x) =
              sample_lanczos(source, m.x_mm * spec.px_per_mm, m.y_mm * spec.px_per_mm, background);
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
    for (std::size_t i = 0; i < marks_px.size(); ++i) {
      const PointMm x = warp_to_image(
          spec, {marks_px[i][0] / spec.px_per_mm, marks_px[i][1] / spec.px_per_mm}, f);
      const double x_px = x.x_mm * spec.px_per_mm, y_px = x.y_mm * spec.px_per_mm;
      if (x_px < 0 || y_px < 0 || x_px > w - 1 || y_px > h - 1) continue;
      seq.landmarks.push_back(
          {static_cast<std::int32_t>(i), FeatureType::pore, f, x_px, y_px, x.x_mm, x.y_mm, 0.0});
    }
  }
  return seq;
}

void write_print_sequence(const std::filesystem::path& dir, const PrintSequence& seq) {
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
               {"seed", s.seed}};
  j["marks"] = seq.marks_px.size();
  j["frames"] = fmt::format("frame_000.png .. frame_{:03d}.png",
                            seq.frames.empty() ? 0 : seq.frames.size() - 1);
  write_text_atomically(dir / "scene.json", j.dump(2) + "\n");
}

}  // namespace tactile::capture
