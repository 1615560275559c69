// The simulated BioTac-style fingertip (see sensor_model.hpp and docs/perception-models.md).

#include "tactile/capture/sensor_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace tactile::capture {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kReferenceAngleDeg = 25.0;  // contact centred on the pad at this angle

// One 100 Hz step of a trial: indentation depth, where the pad's contact centre is and where
// the feature's centre is, both in pad coordinates (mm), and the sliding speed.
struct Pose {
  double depth_mm = 0;  // plan: commanded descent; simulation: pad indentation
  double contact_x_mm = 0, contact_y_mm = 0;
  double feature_x_mm = 0, feature_y_mm = 0;
  double slide_mm_s = 0;
};

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

std::vector<Pose> plan(Procedure procedure, const TrialVariation& v, const SensorModel& m,
                       double rate_hz) {
  const ProcedureKinematics k = paper_kinematics(procedure);
  const double speed = k.speed_mm_s * v.speed_scale;
  double motion_s = k.hold_s;
  if (procedure == Procedure::distal_proximal || procedure == Procedure::radial_ulnar)
    motion_s = k.stroke_mm / speed;
  else if (procedure == Procedure::roll)
    motion_s = k.roll_s / v.speed_scale;
  const double depth = -k.commanded_depth_mm * v.depth_scale;  // commanded descent
  const double angle_shift_mm =
      m.pad_radius_x_mm * (k.contact_angle_deg + v.angle_deg - kReferenceAngleDeg) * kDegToRad;
  const double total_s = 2 * k.rest_s + 2 * k.approach_s + motion_s;
  const auto n = static_cast<std::size_t>(std::ceil(total_s * rate_hz));
  std::vector<Pose> poses(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate_hz;
    const double t_press = t - k.rest_s;           // press ramp starts
    const double t_move = t_press - k.approach_s;  // motion starts
    const double t_release = t_move - motion_s;    // release ramp starts
    Pose& p = poses[i];
    p.depth_mm =
        depth * (smoothstep(t_press / k.approach_s) - smoothstep(t_release / k.approach_s));
    const double s = std::clamp(t_move / motion_s, 0.0, 1.0);  // motion progress
    const bool moving = t_move > 0 && t_move < motion_s;
    p.contact_x_mm = angle_shift_mm;
    p.feature_x_mm = angle_shift_mm + v.offset_x_mm;
    p.feature_y_mm = v.offset_y_mm;
    switch (procedure) {
      case Procedure::static_contact:
        break;
      case Procedure::distal_proximal:
        p.feature_x_mm += k.stroke_mm * (s - 0.5);
        p.slide_mm_s = moving ? speed : 0;
        break;
      case Procedure::radial_ulnar:
        p.feature_y_mm += k.stroke_mm * (s - 0.5);
        p.slide_mm_s = moving ? speed : 0;
        break;
      case Procedure::roll: {
        // Rolling without slip: the feature stays on the same pad point (where the contact was
        // at the start) while the contact centre travels R * angle across the pad.
        const double half = 0.5 * k.roll_deg * kDegToRad * m.pad_radius_y_mm;
        p.feature_y_mm += -half;
        p.contact_y_mm = -half + 2 * half * s;
        break;
      }
    }
  }
  return poses;
}

// Displaced volume (mm^3) of the flat plate alone: the paraboloid cap pi sqrt(Rx Ry) depth^2
// (the fluid layer's saturation is neglected for the plate; it matters only on tall bumps).
double plate_volume_mm3(double depth_mm, const SensorModel& m) {
  if (depth_mm <= 0) return 0.0;
  return std::numbers::pi * std::sqrt(m.pad_radius_x_mm * m.pad_radius_y_mm) * depth_mm * depth_mm;
}

// Extra displaced volume (mm^3, negative for pits) due to the feature: only its footprint,
// sampled with 12 samples across, and only where the pad can touch.
double feature_volume_mm3(const SurfaceFeature& f, const Pose& p, const SensorModel& m) {
  if (p.depth_mm <= 0) return 0.0;
  const double a = 0.5 * f.footprint_mm;
  // Beyond the reach of the pad (depth plus the tallest bump) nothing touches.
  const double reach = p.depth_mm + std::max(0.0, f.height_mm);
  const double reach_x = std::sqrt(2 * m.pad_radius_x_mm * reach);
  const double reach_y = std::sqrt(2 * m.pad_radius_y_mm * reach);
  if (std::abs(p.feature_x_mm - p.contact_x_mm) > reach_x + a ||
      std::abs(p.feature_y_mm - p.contact_y_mm) > reach_y + a)
    return 0.0;
  const double step = f.footprint_mm / 12;
  double volume = 0;
  for (double dx = -a + step / 2; dx < a; dx += step)
    for (double dy = -a + step / 2; dy < a; dy += step) {
      const double r = std::sqrt(dx * dx + dy * dy);
      if (r >= a) continue;
      const double cx = p.feature_x_mm + dx - p.contact_x_mm;
      const double cy = p.feature_y_mm + dy - p.contact_y_mm;
      const double free =
          p.depth_mm - cx * cx / (2 * m.pad_radius_x_mm) - cy * cy / (2 * m.pad_radius_y_mm);
      const double with = free + f.surface_mm(r);
      const double u_with = with <= 0 ? 0.0 : m.fluid_layer_mm * std::tanh(with / m.fluid_layer_mm);
      volume += u_with - std::max(0.0, free);
    }
  return volume * step * step;
}

// Pad indentation where the arm's spring balances the pad: the commanded descent d is shared
// between the arm (kappa (d - depth)) and the pad (its displaced volume V). kappa is set so that
// a flat plate takes depth_transfer of the commanded depth. Two Newton steps per 10 ms from the
// previous depth (slope of the flat plate's volume), so the finger follows a moving balance.
double balance_depth(const SurfaceFeature& f, Pose p, double commanded_mm, double depth,
                     const SensorModel& m, double kappa) {
  if (commanded_mm <= 0) return 0.0;
  for (int it = 0; it < 2; ++it) {
    p.depth_mm = depth;
    const double v = std::max(0.0, plate_volume_mm3(depth, m) + feature_volume_mm3(f, p, m));
    const double g = v - kappa * (commanded_mm - depth);
    const double slope =
        2 * std::numbers::pi * std::sqrt(m.pad_radius_x_mm * m.pad_radius_y_mm) * depth + kappa;
    depth = std::clamp(depth - g / slope, 0.0, commanded_mm);
  }
  return depth;
}

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

TrialVariation draw_variation(std::uint64_t seed, double scale) {
  // Repeatability of a robot arm replaying a trajectory, as measured on the real recordings'
  // arm poses (../shared/data/biotac-slide/*_cp.csv, trials 2-4 of each material): across
  // trials the cross-track position differs by <= 0.02 mm (std), the lowest height by <= 0.03 mm,
  // the speed by 0.03 % and the orientation by ~0.01 degree. We allow five to twenty times that
  // for a different arm. The depth is the exception: the same trials' pressure differs by
  // 3.5-8.4 % (coefficient of variation) at a repeatable height (skin and fluid state, the
  // arm's compliance), which the commanded depth's 3 % spread reproduces (pressure ~ depth^2).
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 1);
  std::uniform_real_distribution<double> offset(-0.1, 0.1), angle(-0.1, 0.1);
  std::normal_distribution<double> depth(1.0, 0.03), speed(1.0, 0.005);
  TrialVariation v;
  v.offset_x_mm = scale * offset(rng);
  v.offset_y_mm = scale * offset(rng);
  v.depth_scale = 1 + scale * (depth(rng) - 1);
  v.speed_scale = 1 + scale * (speed(rng) - 1);
  v.angle_deg = scale * angle(rng);
  return v;
}

SensorRecording simulate_trial(const SurfaceFeature& feature, Procedure procedure,
                               std::uint64_t seed, const SensorModel& m) {
  const TrialVariation variation = draw_variation(seed, m.variation_scale);
  std::mt19937_64 rng(seed ^ 0xD1B54A32D192ED03ull);
  std::normal_distribution<double> unit(0.0, 1.0);

  SensorRecording r;
  r.source = fmt::format("simulated {} trial {} of feature {:+g} mm", procedure_name(procedure),
                         seed, feature.signed_footprint_mm());
  const std::vector<Pose> poses = plan(procedure, variation, m, r.rate_hz);
  const auto electrodes = sensor_electrode_positions();
  const double p0 = m.pressure_baseline + m.baseline_spread * unit(rng);
  std::array<double, kElectrodeCount> e0{};
  for (double& e : e0) e = m.electrode_baseline + m.baseline_spread * unit(rng);

  const double commanded = -paper_kinematics(procedure).commanded_depth_mm;
  const double flat_depth = commanded * m.depth_transfer;
  const double kappa = plate_volume_mm3(flat_depth, m) / (commanded - flat_depth);
  const SkinProfile skin(feature, m.skin_bend_radius_mm);
  const std::vector<FieldSample> field = field_weights(m);
  double depth = 0;
  std::vector<double> load(poses.size());  // pressure above baseline, noiseless
  std::vector<double> depth_at(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    Pose p = poses[i];
    depth = balance_depth(feature, p, p.depth_mm, depth, m, kappa);
    p.depth_mm = depth;
    depth_at[i] = depth;
    load[i] = m.pressure_per_mm3 *
              std::max(0.0, plate_volume_mm3(depth, m) + feature_volume_mm3(feature, p, m));
    r.t_s.push_back(static_cast<double>(i) / r.rate_hz);
    r.temperature_dc.push_back(2.0);
    r.temperature_ac.push_back(0.0);
    r.pressure.push_back(std::round(p0 + load[i] + m.pressure_noise * unit(rng)));
    for (int e = 0; e < kElectrodeCount; ++e) {
      // Impedance follows the fluid gap over the electrode's receptive field (weights from
      // field_weights): the local indentation closes the gap (u / (L - u)), the skin's bending
      // and its stretch redistribute the fluid.
      const auto [x, y] = electrodes[e];
      double gap = 0;
      for (const FieldSample& w : field) {
        const SkinState k = skin_state(skin, p, m, x + w.dx_mm, y + w.dy_mm);
        if (k.indentation_mm <= 0) continue;
        const double u = std::min(k.indentation_mm, 0.8 * m.fluid_layer_mm);
        gap += w.weight *
               (m.electrode_per_mm * m.fluid_layer_mm * u / (m.fluid_layer_mm - u) +
                m.electrode_per_bending_mm * k.bending_per_mm + m.electrode_per_strain * k.stretch);
      }
      r.electrodes[e].push_back(
          std::round(e0[e] + gap + 0.05 * load[i] + m.electrode_noise * unit(rng)));
    }
  }

  // Vibration: the AC-coupled change of the load between 2200 Hz samples (load interpolated
  // linearly between rows); the skin ringing (a 150 Hz resonator, Q = 3) when the pad centre
  // passes a change of the surface's slope (edges, rims, apexes: the profile's second
  // difference along the path); friction noise while sliding (proportional to load and speed,
  // smoothed by the skin: one-pole low-pass at 400 Hz); and sensor noise.
  const double fs = r.vibration_rate_hz;
  const double alpha = 1.0 - std::exp(-2 * std::numbers::pi * 400.0 / fs);
  const double w0 = 2 * std::numbers::pi * 150.0 / fs, damping = std::exp(-w0 / (2 * 3.0));
  const double a1 = 2 * damping * std::cos(w0), a2 = -damping * damping;
  double previous = 0, friction = 0, h1 = 0, h2 = 0, y1 = 0, y2 = 0;
  const std::size_t n = poses.size() * kVibrationPerRow;
  r.vibration.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double row = static_cast<double>(k) / kVibrationPerRow;
    const auto i0 = static_cast<std::size_t>(row);
    const std::size_t i1 = std::min(i0 + 1, poses.size() - 1);
    const double w = row - static_cast<double>(i0);
    const double l = (1 - w) * load[i0] + w * load[i1];
    const double slide = poses[i0].slide_mm_s;
    friction += alpha * (m.friction_noise_per_unit * l * slide * unit(rng) * 10 - friction);
    // Slope changes ring the skin where it first meets them: the leading edge of the contact
    // patch (half-lengths from the depth), on the side the surface comes from.
    const Pose& p0 = poses[i0];
    const double lead_x = std::sqrt(2 * m.pad_radius_x_mm * std::max(0.0, depth_at[i0]));
    const double lead_y = std::sqrt(2 * m.pad_radius_y_mm * std::max(0.0, depth_at[i0]));
    double sx = p0.contact_x_mm, sy = p0.contact_y_mm;
    if (procedure == Procedure::distal_proximal) sx -= lead_x;
    if (procedure == Procedure::radial_ulnar) sy -= lead_y;
    if (procedure == Procedure::roll) sy += lead_y;
    const Pose& p1 = poses[i1];
    const double fx = (1 - w) * p0.feature_x_mm + w * p1.feature_x_mm;
    const double fy = (1 - w) * p0.feature_y_mm + w * p1.feature_y_mm;
    const double h = l > 0 ? skin.at(std::hypot(fx - sx, fy - sy)).height_mm : 0.0;
    const double kink = k >= 2 ? h - 2 * h1 + h2 : 0.0;
    const double ring = a1 * y1 + a2 * y2 + m.edge_gain * kink;
    h2 = h1;
    h1 = h;
    y2 = y1;
    y1 = ring;
    r.vibration.push_back(std::round(m.vibration_offset +
                                     m.vibration_gain * fs / 100 * (l - previous) + ring +
                                     friction + m.vibration_noise * unit(rng)));
    previous = l;
  }
  return r;
}

}  // namespace tactile::capture
