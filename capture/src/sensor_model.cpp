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

// Indentation of the pad at pad point (x, y), saturating at the fluid layer's thickness.
double indentation_mm(const SurfaceFeature& f, const Pose& p, const SensorModel& m, double x,
                      double y) {
  if (p.depth_mm <= 0) return 0.0;
  const double cx = x - p.contact_x_mm, cy = y - p.contact_y_mm;
  const double pad = cx * cx / (2 * m.pad_radius_x_mm) + cy * cy / (2 * m.pad_radius_y_mm);
  const double h = f.surface_mm(std::hypot(x - p.feature_x_mm, y - p.feature_y_mm));
  const double u = p.depth_mm + h - pad;
  return u <= 0 ? 0.0 : m.fluid_layer_mm * std::tanh(u / m.fluid_layer_mm);
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
  std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ull + 1);
  std::uniform_real_distribution<double> offset(-0.5, 0.5), angle(-1.0, 1.0);
  std::normal_distribution<double> depth(1.0, 0.03), speed(1.0, 0.02);
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
    r.pressure.push_back(p0 + load[i] + m.pressure_noise * unit(rng));
    for (int e = 0; e < kElectrodeCount; ++e) {
      // Impedance follows the skin over the electrode's face (7 x 7 points 0.2 mm apart): the
      // local indentation closes the fluid gap (u / (L - u)), the skin's bending (Laplacian)
      // and its stretch (membrane strain sqrt(1 + |grad u|^2) - 1) redistribute the fluid.
      const auto [x, y] = electrodes[e];
      constexpr double s = 0.2;
      std::array<std::array<double, 9>, 9> g{};
      for (int i = 0; i < 9; ++i)
        for (int j = 0; j < 9; ++j)
          g[i][j] = indentation_mm(feature, p, m, x + (i - 4) * s, y + (j - 4) * s);
      double gap = 0;
      for (int i = 1; i < 8; ++i)
        for (int j = 1; j < 8; ++j) {
          const double uc = g[i][j];
          const double bending =
              -(g[i + 1][j] + g[i - 1][j] + g[i][j + 1] + g[i][j - 1] - 4 * uc) / (s * s);
          const double slope =
              std::hypot(g[i + 1][j] - g[i - 1][j], g[i][j + 1] - g[i][j - 1]) / (2 * s);
          const double stretch = std::sqrt(1 + slope * slope) - 1;
          const double u = std::min(uc, 0.8 * m.fluid_layer_mm);
          gap += m.electrode_per_mm * m.fluid_layer_mm * u / (m.fluid_layer_mm - u) +
                 m.electrode_per_bending_mm * bending + m.electrode_per_strain * stretch;
        }
      gap /= 49;
      r.electrodes[e].push_back(e0[e] + gap + 0.05 * load[i] + m.electrode_noise * unit(rng));
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
    const double h = l > 0 ? feature.surface_mm(std::hypot(fx - sx, fy - sy)) : 0.0;
    const double kink = k >= 2 ? h - 2 * h1 + h2 : 0.0;
    const double ring = a1 * y1 + a2 * y2 + m.edge_gain * kink;
    h2 = h1;
    h1 = h;
    y2 = y1;
    y1 = ring;
    r.vibration.push_back(m.vibration_offset + m.vibration_gain * fs / 100 * (l - previous) + ring +
                          friction + m.vibration_noise * unit(rng));
    previous = l;
  }
  return r;
}

}  // namespace tactile::capture
