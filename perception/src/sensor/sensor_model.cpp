// The simulated BioTac-style fingertip (see sensor_model.hpp and docs/perception-models.md).

#include "tactile/perception/sensor_model.hpp"

#include "tactile/perception/sensor_contact.hpp"
#include "tactile/perception/skin_ringing.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <stdexcept>

namespace tactile::perception {
namespace {

using contact::Pose;

// The skin over the feature: an elastic sheet cannot curve more sharply than its minimum
// bending radius rho, so it tents over narrow bumps and sharp edges and bridges narrow pits
// instead of following the rigid profile (the Winkler foundation alone would follow steps
// exactly). It must still lie on or above the rigid surface, so its height is the smallest
// function >= the profile whose curvature stays within 1/rho: the dilation of the profile by a
// paraboloid, h_skin(r) = max over r' of h(r') - (r - r')^2 / (2 rho). The feature is round, so
// the 2D dilation reduces to this 1D one over radii. Tabulated with its radial derivatives.
class SkinProfile {
 public:
  SkinProfile(const SurfaceFeature& f, double rho_mm) {
    const double a = 0.5 * f.footprint_mm, h_abs = std::abs(f.height_mm);
    const double reach = std::sqrt(2 * rho_mm * h_abs);  // how far the tent spreads
    const auto n = static_cast<std::size_t>(std::ceil((a + reach) / kStepMm)) + 3;
    std::vector<double> rigid(n);
    for (std::size_t i = 0; i < n; ++i) rigid[i] = f.surface_mm(static_cast<double>(i) * kStepMm);
    const auto window = static_cast<std::ptrdiff_t>(std::ceil(reach / kStepMm));
    height_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      double best = rigid[i];
      const auto ii = static_cast<std::ptrdiff_t>(i);
      const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, ii - window);
      const std::ptrdiff_t hi =
          std::min<std::ptrdiff_t>(static_cast<std::ptrdiff_t>(n) - 1, ii + window);
      for (std::ptrdiff_t j = lo; j <= hi; ++j) {
        if (j == ii) continue;  // the profile itself (and no 0 / 0 when rho is 0)
        const double d = static_cast<double>(ii - j) * kStepMm;
        best = std::max(best, rigid[static_cast<std::size_t>(j)] - d * d / (2 * rho_mm));
      }
      height_[i] = best;
    }
  }

  // Height, radial slope and Laplacian (h'' + h'/r) of the skin at distance r from the centre.
  struct Sample {
    double height_mm = 0, slope = 0, laplacian_per_mm = 0;
  };
  Sample at(double r_mm) const {
    const double x = r_mm / kStepMm;
    if (x >= static_cast<double>(height_.size() - 2)) return {};
    const auto i = static_cast<std::size_t>(x);
    const double w = x - static_cast<double>(i);
    const auto value = [&](std::size_t k) { return height_[k]; };
    const auto d1 = [&](std::size_t k) {
      return k == 0 ? 0.0 : (value(k + 1) - value(k - 1)) / (2 * kStepMm);
    };
    const auto d2 = [&](std::size_t k) {
      const double left = k == 0 ? value(1) : value(k - 1);  // symmetric about the centre
      return (value(k + 1) - 2 * value(k) + left) / (kStepMm * kStepMm);
    };
    Sample s;
    s.height_mm = (1 - w) * value(i) + w * value(i + 1);
    s.slope = (1 - w) * d1(i) + w * d1(i + 1);
    const double curvature = (1 - w) * d2(i) + w * d2(i + 1);
    // Near the centre h'/r tends to h''.
    s.laplacian_per_mm = curvature + (r_mm > 2 * kStepMm ? s.slope / r_mm : curvature);
    return s;
  }

  // Radial slope of the height as interpolated between table points: constant over each
  // 0.02 mm cell, so a kink of the skin (the foot of a tent) stays within one cell.
  double cell_slope(double r_mm) const {
    const double x = r_mm / kStepMm;
    if (!(x >= 0) || x >= static_cast<double>(height_.size() - 1)) return 0.0;
    const auto i = static_cast<std::size_t>(x);
    return (height_[i + 1] - height_[i]) / kStepMm;
  }

 private:
  static constexpr double kStepMm = 0.02;
  std::vector<double> height_;
};

// Gap closure, bending and stretch of the skin at pad point (x, y): the skin height over the
// feature on the pad's paraboloid, indented by depth, saturating at the fluid layer (L tanh(u/L),
// whose gradient and Laplacian follow by the chain rule). Zero where the skin is not touched.
struct SkinState {
  double indentation_mm = 0, bending_per_mm = 0, stretch = 0;
};
SkinState skin_state(const SkinProfile& skin, const Pose& p, const SensorModel& m, double x,
                     double y) {
  if (p.depth_mm <= 0) return {};
  const double cx = x - p.contact_x_mm, cy = y - p.contact_y_mm;
  const double pad = cx * cx / (2 * m.pad_radius_x_mm) + cy * cy / (2 * m.pad_radius_y_mm);
  const double fx = x - p.feature_x_mm, fy = y - p.feature_y_mm;
  const double r = std::hypot(fx, fy);
  const SkinProfile::Sample h = skin.at(r);
  const double u = p.depth_mm + h.height_mm - pad;
  if (u <= 0) return {};
  const double gx = (r > 0 ? h.slope * fx / r : 0.0) - cx / m.pad_radius_x_mm;
  const double gy = (r > 0 ? h.slope * fy / r : 0.0) - cy / m.pad_radius_y_mm;
  const double lap = h.laplacian_per_mm - 1 / m.pad_radius_x_mm - 1 / m.pad_radius_y_mm;
  const double L = m.fluid_layer_mm, t = std::tanh(u / L), sech2 = 1 - t * t;
  const double grad2 = (gx * gx + gy * gy) * sech2 * sech2;
  SkinState s;
  s.indentation_mm = L * t;
  s.bending_per_mm = -(sech2 * lap - 2 / L * t * sech2 * (gx * gx + gy * gy));
  s.stretch = std::sqrt(1 + grad2) - 1;
  return s;
}

// An electrode's receptive field: the current between the electrode and the fluid crosses the
// gap over its face and over a margin of about the gap's thickness around it, so the impedance
// weighs the skin with a Gaussian of sigma electrode_field_mm, sampled on a square grid out to
// 2 sigma (weights sum to 1).
struct FieldSample {
  double dx_mm, dy_mm, weight;
};
std::vector<FieldSample> field_weights(const SensorModel& m) {
  const int half = m.electrode_field_samples / 2;
  const double step = 2 * m.electrode_field_mm / std::max(1, half);
  std::vector<FieldSample> field;
  double total = 0;
  for (int i = -half; i <= half; ++i)
    for (int j = -half; j <= half; ++j) {
      const double dx = i * step, dy = j * step;
      const double w =
          std::exp(-(dx * dx + dy * dy) / (2 * m.electrode_field_mm * m.electrode_field_mm));
      field.push_back({dx, dy, w});
      total += w;
    }
  for (FieldSample& f : field) f.weight /= total;
  return field;
}

// ElectrodeField::sheet. The current leaves the electrode's face and spreads radially through the
// thin fluid layer, so the resistance of the annulus at radius r goes as dr / (r x gap): a change
// of the gap there weighs as 1 / r^2 (1 / face^2 over the face), out to where the current leaves
// for the other electrodes (the reach, tapered over +-0.5 mm so that nothing jumps as the skin
// moves). A small feature is then seen by every electrode within a few millimetres, and smoothly
// in its position, where the Gaussian field sees it only on a steep flank.
class SheetField {
 public:
  explicit SheetField(const SensorModel& m)
      : face_mm_(m.sheet_face_mm), cut_mm_(m.sheet_reach_mm), taper_mm_(0.5) {
    if (!(face_mm_ > 0 && cut_mm_ > face_mm_ + taper_mm_ && cut_mm_ < 50))
      throw std::invalid_argument(fmt::format(
          "sheet electrode field: face {} mm and reach {} mm need 0 < face < reach - 0.5 < 50 mm",
          face_mm_, cut_mm_));
    // Normalised so that the weights integrate to 1, as the Gaussian's sum to 1.
    constexpr double h = 0.02;
    double total = 0;
    for (double x = -reach_mm(); x <= reach_mm(); x += h)
      for (double y = -reach_mm(); y <= reach_mm(); y += h)
        total += weight_per_mm2(std::hypot(x, y));
    norm_ = total * h * h;
    // The flat plate's part is smooth, so 0.5 mm cells, each with its integrated weight, suffice.
    constexpr double cell = 0.5;
    const int n = static_cast<int>(std::ceil(reach_mm() / cell));
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j) {
        double w = 0;
        for (int a = -2; a <= 2; ++a)
          for (int b = -2; b <= 2; ++b)
            w += weight_per_mm2(std::hypot((i + a / 5.0) * cell, (j + b / 5.0) * cell));
        if (w > 0) cells_.push_back({i * cell, j * cell, w * cell * cell / 25});
      }
  }
  double weight_per_mm2(double r_mm) const {
    const double s = (r_mm - (cut_mm_ - taper_mm_)) / (2 * taper_mm_);
    if (s >= 1) return 0.0;
    const double rr = std::max(r_mm, face_mm_);
    const double taper = s > 0 ? 1 - s * s * (3 - 2 * s) : 1.0;
    return taper / (rr * rr * norm_);
  }
  double reach_mm() const { return cut_mm_ + taper_mm_; }
  const std::vector<FieldSample>& cells() const { return cells_; }

 private:
  double face_mm_, cut_mm_, taper_mm_, norm_ = 1.0;
  std::vector<FieldSample> cells_;
};

// Counts of the skin at one point: the local indentation closes the gap (u / (L - u)), the skin's
// bending and its stretch redistribute the fluid.
double skin_counts(const SkinState& k, const SensorModel& m) {
  if (k.indentation_mm <= 0) return 0.0;
  const double u = std::min(k.indentation_mm, 0.8 * m.fluid_layer_mm);
  return m.electrode_per_mm * m.fluid_layer_mm * u / (m.fluid_layer_mm - u) +
         m.electrode_per_bending_mm * k.bending_per_mm + m.electrode_per_strain * k.stretch;
}

// The electrodes' impedance change at one pose. The sheet field reaches millimetres, so it is
// the flat plate's smooth part on coarse cells plus the feature's difference from it on samples
// fixed to the feature (the same shape sampling wherever the feature is).
class ElectrodeModel {
 public:
  ElectrodeModel(const SurfaceFeature& feature, const SensorModel& m)
      : m_(m),
        skin_(feature, m.skin_bend_radius_mm),
        plate_(SurfaceFeature{Curvature::planar, feature.footprint_mm, 0.0}, m.skin_bend_radius_mm),
        gaussian_(m.electrode_field == ElectrodeField::gaussian ? field_weights(m)
                                                                : std::vector<FieldSample>{}) {
    if (m.electrode_field != ElectrodeField::sheet) return;
    sheet_.emplace(m);
    feature_reach_mm_ = 0.5 * feature.footprint_mm +
                        std::sqrt(2 * m.skin_bend_radius_mm * std::abs(feature.height_mm)) + 0.04;
    const double step = std::clamp(feature_reach_mm_ / 12, 0.03, 0.6);
    feature_cell_mm2_ = step * step;
    const int n = static_cast<int>(std::ceil(feature_reach_mm_ / step));
    for (int i = -n; i <= n; ++i)
      for (int j = -n; j <= n; ++j)
        if (std::hypot(i * step, j * step) <= feature_reach_mm_)
          feature_samples_.push_back({i * step, j * step});
  }

  double counts(const Pose& p, const PadPoint& e) const {
    double c = 0;
    if (m_.electrode_field == ElectrodeField::gaussian) {
      for (const FieldSample& w : gaussian_)
        c += w.weight *
             skin_counts(skin_state(skin_, p, m_, e.x_mm + w.dx_mm, e.y_mm + w.dy_mm), m_);
      return c;
    }
    for (const FieldSample& w : sheet_->cells())
      c +=
          w.weight * skin_counts(skin_state(plate_, p, m_, e.x_mm + w.dx_mm, e.y_mm + w.dy_mm), m_);
    if (std::hypot(p.feature_x_mm - e.x_mm, p.feature_y_mm - e.y_mm) >=
        sheet_->reach_mm() + feature_reach_mm_)
      return c;
    for (const auto& [dx, dy] : feature_samples_) {
      const double x = p.feature_x_mm + dx, y = p.feature_y_mm + dy;
      const double w = sheet_->weight_per_mm2(std::hypot(x - e.x_mm, y - e.y_mm));
      if (w <= 0) continue;
      c += w * feature_cell_mm2_ *
           (skin_counts(skin_state(skin_, p, m_, x, y), m_) -
            skin_counts(skin_state(plate_, p, m_, x, y), m_));
    }
    return c;
  }
  const SkinProfile& skin() const { return skin_; }

 private:
  const SensorModel& m_;
  SkinProfile skin_, plate_;
  std::vector<FieldSample> gaussian_;
  std::optional<SheetField> sheet_;  // only for ElectrodeField::sheet
  double feature_reach_mm_ = 0, feature_cell_mm2_ = 0;
  std::vector<std::array<double, 2>> feature_samples_;
};

}  // namespace

std::array<PadPoint, kElectrodeCount> sensor_electrode_positions() {
  return {{{-7.5, -4.0},
           {-4.5, -4.0},
           {-1.5, -4.0},
           {1.5, -4.0},
           {4.5, -4.0},
           {7.5, -4.0},
           {9.0, 0.0},
           {7.5, -1.5},
           {7.5, 1.5},
           {4.5, 0.0},
           {-7.5, 4.0},
           {-4.5, 4.0},
           {-1.5, 4.0},
           {1.5, 4.0},
           {4.5, 4.0},
           {7.5, 4.0},
           {-4.5, 0.0},
           {-1.5, 0.0},
           {1.5, 0.0}}};
}

TrialVariation draw_variation(std::uint64_t seed, const VariationScale& scale) {
  // Repeatability of a robot arm replaying a trajectory, as measured on the real recordings'
  // arm poses (tests/data/biotac-slide/*_cp.csv, trials 2-4 of each material): across
  // trials the cross-track position differs by <= 0.02 mm (std), the lowest height by <= 0.03 mm,
  // the speed by 0.03 % and the orientation by ~0.01 degree. We allow five to twenty times that
  // for a different arm. The depth is the exception: the same trials' pressure differs by
  // 3.5-8.4 % (coefficient of variation) at a repeatable height (skin and fluid state, the
  // arm's compliance), which the commanded depth's 3 % spread reproduces (pressure ~ depth^2).
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 1);
  std::uniform_real_distribution<double> offset(-0.1, 0.1), angle(-0.1, 0.1);
  std::normal_distribution<double> depth(1.0, 0.03), speed(1.0, 0.005);
  TrialVariation v;
  v.offset_x_mm = scale.position * offset(rng);
  v.offset_y_mm = scale.position * offset(rng);
  v.depth_scale = 1 + scale.depth * (depth(rng) - 1);
  v.speed_scale = 1 + scale.speed * (speed(rng) - 1);
  v.angle_deg = scale.position * angle(rng);
  return v;
}

SensorRecording simulate_trial(const SurfaceFeature& feature, Procedure procedure,
                               std::uint64_t seed, const SensorModel& m) {
  const TrialVariation variation = draw_variation(seed, m.variation);
  std::mt19937_64 rng(seed ^ 0xD1B54A32D192ED03ull);
  std::normal_distribution<double> unit(0.0, 1.0);

  SensorRecording r;
  r.source = fmt::format("simulated {} trial {} of feature {:+g} mm", procedure_name(procedure),
                         seed, feature.signed_footprint_mm());
  const std::vector<Pose> poses = contact::plan(procedure, variation, m, r.rate_hz);
  const auto electrodes = sensor_electrode_positions();
  const double p0 = m.pressure_baseline + m.baseline_spread * unit(rng);
  std::array<double, kElectrodeCount> e0{};
  for (double& e : e0) e = m.electrode_baseline + m.baseline_spread * unit(rng);

  const double kappa = contact::arm_stiffness(procedure, m);
  const ElectrodeModel electrode_model(feature, m);
  const SkinProfile& skin = electrode_model.skin();
  double depth = 0;
  std::vector<double> load(poses.size());  // pressure above baseline, noiseless
  std::vector<double> depth_at(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Pose p = poses[i];
    depth = contact::balance_depth(feature, p, p.depth_mm, depth, m, kappa);
    p.depth_mm = depth;
    depth_at[i] = depth;
    load[i] = m.pressure_per_mm3 * contact::displaced_volume_mm3(feature, p, m);
    r.t_s.push_back(static_cast<double>(i) / r.rate_hz);
    r.temperature_dc.push_back(2.0);
    r.temperature_ac.push_back(0.0);
    r.pressure.push_back(std::round(p0 + load[i] + m.pressure_noise * unit(rng)));
    for (int e = 0; e < kElectrodeCount; ++e) {
      const double gap = electrode_model.counts(p, electrodes[e]);
      r.electrodes[e].push_back(
          std::round(e0[e] + gap + 0.05 * load[i] + m.electrode_noise * unit(rng)));
    }
  }

  // Vibration: the AC-coupled change of the load between 2200 Hz samples (load interpolated
  // linearly between rows); the skin ringing where the skin meets a change of the surface's
  // slope (SkinRinging); friction noise while sliding (proportional to load and speed, smoothed
  // by the skin: one-pole low-pass at 400 Hz); and sensor noise.
  const double fs = r.vibration_rate_hz;
  const double alpha = 1.0 - std::exp(-2 * std::numbers::pi * 400.0 / fs);
  SkinRinging ringing(fs, m.edge_gain);
  double previous = 0, friction = 0;
  const std::size_t n = poses.size() * kVibrationPerRow;
  r.vibration.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double row = static_cast<double>(k) / kVibrationPerRow;
    const auto i0 = static_cast<std::size_t>(row);
    const std::size_t i1 = std::min(i0 + 1, poses.size() - 1);
    const double w = row - static_cast<double>(i0);
    const auto lerp = [w](double a, double b) { return (1 - w) * a + w * b; };
    const double l = lerp(load[i0], load[i1]);
    const double slide = poses[i0].slide_mm_s;
    friction += alpha * (m.friction_noise_per_unit * l * slide * unit(rng) * 10 - friction);
    // The skin meets the surface first at the leading edge of the contact patch (half-length
    // from the depth), on the side the surface comes from; the slope there is the skin's, along
    // the direction of sliding (x for the distal-proximal stroke, y for the others).
    const Pose& p0 = poses[i0];
    const Pose& p1 = poses[i1];
    const double pad_depth_mm = std::max(0.0, lerp(depth_at[i0], depth_at[i1]));
    double sx = lerp(p0.contact_x_mm, p1.contact_x_mm);
    double sy = lerp(p0.contact_y_mm, p1.contact_y_mm);
    if (procedure == Procedure::distal_proximal)
      sx -= std::sqrt(2 * m.pad_radius_x_mm * pad_depth_mm);
    if (procedure == Procedure::radial_ulnar) sy -= std::sqrt(2 * m.pad_radius_y_mm * pad_depth_mm);
    if (procedure == Procedure::roll) sy += std::sqrt(2 * m.pad_radius_y_mm * pad_depth_mm);
    const double mx = lerp(p0.feature_x_mm, p1.feature_x_mm) - sx;
    const double my = lerp(p0.feature_y_mm, p1.feature_y_mm) - sy;
    const double mr = std::hypot(mx, my);
    const double along = procedure == Procedure::distal_proximal ? mx : my;
    const double slope = mr > 0 ? skin.cell_slope(mr) * along / mr : 0.0;
    const double ring = ringing.step(l > 0, slope);
    r.vibration.push_back(std::round(m.vibration_offset +
                                     m.vibration_gain * fs / 100 * (l - previous) + ring +
                                     friction + m.vibration_noise * unit(rng)));
    previous = l;
  }
  return r;
}

}  // namespace tactile::perception
