#include "landmarks/fingerprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

namespace tactile::capture {

namespace {

constexpr double kPi = std::numbers::pi;

// atan2 with ~1e-5 rad error; the texture evaluates tens of millions of them.
inline double fast_atan2(double y, double x) {
  const double ax = std::abs(x);
  const double ay = std::abs(y);
  const double mx = std::max(ax, ay);
  if (mx == 0.0) return 0.0;
  const double a = std::min(ax, ay) / mx;
  const double s = a * a;
  double r =
      a * (0.9998660 + s * (-0.3302995 + s * (0.1801410 + s * (-0.0851330 + s * 0.0208351))));
  if (ay > ax) r = kPi / 2 - r;
  if (x < 0) r = kPi - r;
  return y < 0 ? -r : r;
}

inline double wrap_pi(double a) {
  return a - 2 * kPi * std::floor((a + kPi) / (2 * kPi));
}

struct Spiral {
  double x_mm;
  double y_mm;
  double sign;
};

// Larkin & Fletcher style phase: a smooth whorl (elliptic rings, gently warped) plus spiral
// phase singularities, each of which inserts one ridge/valley pair and so creates one minutia.
// Ridge centres lie where the phase is a multiple of 2 pi.
class PhaseField {
 public:
  PhaseField(const SceneSpec& spec, PointMm centre, std::mt19937_64& rng) : centre_(centre) {
    std::uniform_real_distribution<double> angle(0, 2 * kPi);
    axis_ratio_ = 1.15;
    k_ = 2 * kPi / (spec.ridge_period_mm * 1.07);
    const double a1 = angle(rng);
    const double a2 = angle(rng);
    e1_ = {std::cos(a1), std::sin(a1)};
    e2_ = {std::cos(a2), std::sin(a2)};
    phase1_ = angle(rng);
    phase2_ = angle(rng);
  }

  double continuous(double x, double y) const {
    const double wx = x + 0.25 * std::sin(2 * kPi * (x * e1_[0] + y * e1_[1]) / 9.0 + phase1_);
    const double wy = y + 0.25 * std::sin(2 * kPi * (x * e2_[0] + y * e2_[1]) / 11.0 + phase2_);
    const double dx = wx - centre_.x_mm;
    const double dy = (wy - centre_.y_mm) * axis_ratio_;
    return k_ * std::sqrt(dx * dx + dy * dy);
  }

  double spiral_sum(double x, double y, std::size_t skip) const {
    double s = 0;
    for (std::size_t i = 0; i < spirals.size(); ++i) {
      if (i == skip) continue;
      s += spirals[i].sign * fast_atan2(y - spirals[i].y_mm, x - spirals[i].x_mm);
    }
    return s;
  }

  double operator()(double x, double y) const {
    return continuous(x, y) + spiral_sum(x, y, spirals.size());
  }

  // Gradient of everything except spiral `skip` (the smooth local fringe field there).
  std::array<double, 2> gradient(double x, double y, std::size_t skip) const {
    const double h = 1e-4;
    auto f = [&](double xx, double yy) { return continuous(xx, yy) + spiral_sum(xx, yy, skip); };
    return {(f(x + h, y) - f(x - h, y)) / (2 * h), (f(x, y + h) - f(x, y - h)) / (2 * h)};
  }

  std::vector<Spiral> spirals;

 private:
  PointMm centre_;
  double axis_ratio_ = 1;
  double k_ = 1;
  std::array<double, 2> e1_{1, 0};
  std::array<double, 2> e2_{0, 1};
  double phase1_ = 0;
  double phase2_ = 0;
};

// Moves spiral i along the local fringe normal until its fork has the wanted topology. On the
// side of the singularity with one fringe fewer (direction sign * t, t = gradient turned +90
// degrees), the fork's stem is a ridge when phase = 0 there (a ridge splits, the valley between
// its branches ends: a valley ending) and a valley when phase = pi (a valley bifurcation).
void set_minutia_type(PhaseField& field, std::size_t i, FeatureType type) {
  const double target = type == FeatureType::ending ? 0.0 : kPi;
  for (int iteration = 0; iteration < 6; ++iteration) {
    Spiral& sp = field.spirals[i];
    const auto g = field.gradient(sp.x_mm, sp.y_mm, i);
    const double gn = std::hypot(g[0], g[1]);
    if (gn <= 0) return;
    const double tx = -g[1] / gn * sp.sign;
    const double ty = g[0] / gn * sp.sign;
    const double phi = field.continuous(sp.x_mm, sp.y_mm) + field.spiral_sum(sp.x_mm, sp.y_mm, i);
    const double err = wrap_pi(target - phi - sp.sign * std::atan2(ty, tx));
    sp.x_mm += err / gn * g[0] / gn;
    sp.y_mm += err / gn * g[1] / gn;
    if (std::abs(err) < 1e-6) return;
  }
}

double smoothstep(double lo, double hi, double v) {
  const double t = std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

}  // namespace

FingerprintTexture render_fingerprint(const SceneSpec& spec, double min_x_mm, double max_x_mm,
                                      double min_y_mm, double max_y_mm, double texels_per_mm,
                                      std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ux(min_x_mm, max_x_mm);
  std::uniform_real_distribution<double> uy(min_y_mm, max_y_mm);
  std::uniform_real_distribution<double> unit(0, 1);

  const PointMm whorl{(min_x_mm + max_x_mm) / 2 + (unit(rng) - 0.5) * 3,
                      (min_y_mm + max_y_mm) / 2 + (unit(rng) - 0.5) * 3};
  PhaseField field(spec, whorl, rng);

  // Minutiae: spread out, away from the whorl core, alternating sign so the far field stays
  // untwisted.
  const double area = (max_x_mm - min_x_mm) * (max_y_mm - min_y_mm);
  const int minutia_count = static_cast<int>(std::lround(spec.minutiae_per_mm2 * area));
  std::vector<FeatureType> minutia_types;
  for (int attempt = 0;
       attempt < 200 * minutia_count && static_cast<int>(field.spirals.size()) < minutia_count;
       ++attempt) {
    const double x = ux(rng);
    const double y = uy(rng);
    if (std::hypot(x - whorl.x_mm, y - whorl.y_mm) < 1.5) continue;
    bool crowded = false;
    for (const auto& s : field.spirals) crowded |= std::hypot(x - s.x_mm, y - s.y_mm) < 1.0;
    if (crowded) continue;
    field.spirals.push_back({x, y, field.spirals.size() % 2 == 0 ? 1.0 : -1.0});
    minutia_types.push_back(unit(rng) < 0.5 ? FeatureType::ending : FeatureType::bifurcation);
  }
  for (int pass = 0; pass < 3; ++pass) {
    for (std::size_t i = 0; i < field.spirals.size(); ++i) {
      set_minutia_type(field, i, minutia_types[i]);
    }
  }

  FingerprintTexture tex;
  tex.origin_x_mm = min_x_mm;
  tex.origin_y_mm = min_y_mm;
  tex.texels_per_mm = texels_per_mm;
  const int cols = static_cast<int>(std::ceil((max_x_mm - min_x_mm) * texels_per_mm)) + 1;
  const int rows = static_cast<int>(std::ceil((max_y_mm - min_y_mm) * texels_per_mm)) + 1;
  tex.reflectance.create(rows, cols, CV_32F);

  // FTIR contrast: ridges in contact are dark and a little wider than the bright valleys.
  constexpr double kRidge = 0.22;
  constexpr double kValley = 0.85;
  constexpr double kPore = 0.78;
  cv::parallel_for_(cv::Range(0, rows), [&](const cv::Range& range) {
    for (int r = range.start; r < range.end; ++r) {
      float* row = tex.reflectance.ptr<float>(r);
      const double y = min_y_mm + r / texels_per_mm;
      for (int c = 0; c < cols; ++c) {
        const double x = min_x_mm + c / texels_per_mm;
        const double ridge = smoothstep(-0.6, -0.1, std::cos(field(x, y)));
        row[c] = static_cast<float>(kValley + (kRidge - kValley) * ridge);
      }
    }
  });

  // Pores sit on ridge centres: project random points onto the nearest phase = 2 pi n line.
  std::int32_t next_id = 0;
  const double density = 1.0 / (spec.ridge_period_mm * spec.pore_spacing_mm);
  const int candidates = static_cast<int>(density * area * 1.6);
  const double min_gap = 0.6 * spec.pore_spacing_mm;
  std::vector<SkinLandmark> pores;
  const double cell = min_gap;
  const int grid_cols = static_cast<int>((max_x_mm - min_x_mm) / cell) + 1;
  const int grid_rows = static_cast<int>((max_y_mm - min_y_mm) / cell) + 1;
  std::vector<std::vector<int>> grid(static_cast<std::size_t>(grid_cols * grid_rows));
  for (int n = 0; n < candidates; ++n) {
    double x = ux(rng);
    double y = uy(rng);
    bool on_ridge = false;
    for (int it = 0; it < 3; ++it) {
      const auto g = field.gradient(x, y, field.spirals.size());
      const double g2 = g[0] * g[0] + g[1] * g[1];
      if (g2 <= 0) break;
      const double e = wrap_pi(field(x, y));
      x -= e * g[0] / g2;
      y -= e * g[1] / g2;
      on_ridge = std::abs(e) < 1e-3;
    }
    if (!on_ridge || x < min_x_mm || x > max_x_mm || y < min_y_mm || y > max_y_mm) continue;
    bool near_minutia = false;
    for (const auto& s : field.spirals) near_minutia |= std::hypot(x - s.x_mm, y - s.y_mm) < 0.45;
    if (near_minutia) continue;
    const int gc = static_cast<int>((x - min_x_mm) / cell);
    const int gr = static_cast<int>((y - min_y_mm) / cell);
    bool crowded = false;
    for (int rr = std::max(0, gr - 1); rr <= std::min(grid_rows - 1, gr + 1) && !crowded; ++rr) {
      for (int cc = std::max(0, gc - 1); cc <= std::min(grid_cols - 1, gc + 1); ++cc) {
        for (int idx : grid[static_cast<std::size_t>(rr * grid_cols + cc)]) {
          const auto& p = pores[static_cast<std::size_t>(idx)];
          if (std::hypot(p.skin.x_mm - x, p.skin.y_mm - y) < min_gap) crowded = true;
        }
      }
    }
    if (crowded) continue;
    const double d = spec.pore_min_diameter_mm +
                     unit(rng) * (spec.pore_max_diameter_mm - spec.pore_min_diameter_mm);
    grid[static_cast<std::size_t>(gr * grid_cols + gc)].push_back(static_cast<int>(pores.size()));
    pores.push_back({next_id++, FeatureType::pore, {x, y}, d});
  }

  for (const auto& p : pores) {
    const double cx = (p.skin.x_mm - min_x_mm) * texels_per_mm;
    const double cy = (p.skin.y_mm - min_y_mm) * texels_per_mm;
    const double radius = p.diameter_mm / 2 * texels_per_mm;
    const int x0 = std::max(0, static_cast<int>(cx - radius - 2));
    const int x1 = std::min(cols - 1, static_cast<int>(cx + radius + 2));
    const int y0 = std::max(0, static_cast<int>(cy - radius - 2));
    const int y1 = std::min(rows - 1, static_cast<int>(cy + radius + 2));
    for (int r = y0; r <= y1; ++r) {
      float* row = tex.reflectance.ptr<float>(r);
      for (int c = x0; c <= x1; ++c) {
        const double cover = std::clamp(radius + 0.5 - std::hypot(c - cx, r - cy), 0.0, 1.0);
        row[c] = static_cast<float>(row[c] + (kPore - row[c]) * cover);
      }
    }
  }
  tex.landmarks = std::move(pores);
  for (std::size_t i = 0; i < field.spirals.size(); ++i) {
    tex.landmarks.push_back(
        {next_id++, minutia_types[i], {field.spirals[i].x_mm, field.spirals[i].y_mm}, 0.0});
  }
  // Approximates each camera pixel's area integration before point sampling.
  cv::GaussianBlur(tex.reflectance, tex.reflectance, cv::Size(0, 0),
                   0.5 * texels_per_mm / (spec.width_px / spec.field_width_mm));
  return tex;
}

}  // namespace tactile::capture
