// Contact mechanics of the simulated fingertip (see sensor_contact.hpp), shared by the sensor's
// channels (sensor_model.cpp) and the skin's strain (sensor_strain.cpp).

#include "tactile/perception/sensor_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tactile::perception::contact {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kReferenceAngleDeg = 25.0;  // contact centred on the pad at this angle

double smoothstep(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

// Displaced volume (mm^3) of the flat plate alone: the paraboloid cap pi sqrt(Rx Ry) depth^2.
double plate_volume_mm3(double depth_mm, const SensorModel& m) {
  if (depth_mm <= 0) return 0.0;
  return std::numbers::pi * std::sqrt(m.pad_radius_x_mm * m.pad_radius_y_mm) * depth_mm * depth_mm;
}

// Extra displaced volume (mm^3, negative for pits) due to the feature, sampled with 12 samples
// across its footprint, only where the pad can touch.
double feature_volume_mm3(const SurfaceFeature& f, const Pose& p, const SensorModel& m) {
  if (p.depth_mm <= 0) return 0.0;
  const double a = 0.5 * f.footprint_mm;
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

}  // namespace

std::vector<Pose> plan(Procedure procedure, const TrialVariation& v, const SensorModel& m,
                       double rate_hz) {
  const ProcedureKinematics k = paper_kinematics(procedure);
  const double speed = k.speed_mm_s * v.speed_scale;
  double motion_s = k.hold_s;
  if (procedure == Procedure::distal_proximal || procedure == Procedure::radial_ulnar)
    motion_s = k.stroke_mm / speed;
  else if (procedure == Procedure::roll)
    motion_s = k.roll_s / v.speed_scale;
  const double depth = -k.commanded_depth_mm * v.depth_scale;
  const double angle_shift_mm =
      m.pad_radius_x_mm * (k.contact_angle_deg + v.angle_deg - kReferenceAngleDeg) * kDegToRad;
  const double total_s = 2 * k.rest_s + 2 * k.approach_s + motion_s;
  const auto n = static_cast<std::size_t>(std::ceil(total_s * rate_hz));
  std::vector<Pose> poses(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / rate_hz;
    const double t_press = t - k.rest_s;
    const double t_move = t_press - k.approach_s;
    const double t_release = t_move - motion_s;
    Pose& p = poses[i];
    p.depth_mm =
        depth * (smoothstep(t_press / k.approach_s) - smoothstep(t_release / k.approach_s));
    const double s = std::clamp(t_move / motion_s, 0.0, 1.0);
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
        // Rolling without slip: the feature stays on the pad point where the contact was at the
        // start while the contact centre travels R * angle across the pad.
        const double half = 0.5 * k.roll_deg * kDegToRad * m.pad_radius_y_mm;
        p.feature_y_mm += -half;
        p.contact_y_mm = -half + 2 * half * s;
        break;
      }
    }
  }
  return poses;
}

double indentation_mm(const SurfaceFeature& f, const Pose& p, const SensorModel& m, double x,
                      double y) {
  if (p.depth_mm <= 0) return 0.0;
  const double cx = x - p.contact_x_mm, cy = y - p.contact_y_mm;
  const double pad = cx * cx / (2 * m.pad_radius_x_mm) + cy * cy / (2 * m.pad_radius_y_mm);
  const double h = f.surface_mm(std::hypot(x - p.feature_x_mm, y - p.feature_y_mm));
  const double u = p.depth_mm + h - pad;
  return u <= 0 ? 0.0 : m.fluid_layer_mm * std::tanh(u / m.fluid_layer_mm);
}

double arm_stiffness(Procedure procedure, const SensorModel& m) {
  const double commanded = -paper_kinematics(procedure).commanded_depth_mm;
  const double flat_depth = commanded * m.depth_transfer;
  return plate_volume_mm3(flat_depth, m) / (commanded - flat_depth);
}

double displaced_volume_mm3(const SurfaceFeature& f, const Pose& p, const SensorModel& m) {
  return std::max(0.0, plate_volume_mm3(p.depth_mm, m) + feature_volume_mm3(f, p, m));
}

double balance_depth(const SurfaceFeature& f, Pose p, double commanded_mm, double depth,
                     const SensorModel& m, double kappa) {
  if (commanded_mm <= 0) return 0.0;
  for (int it = 0; it < 2; ++it) {
    p.depth_mm = depth;
    const double v = displaced_volume_mm3(f, p, m);
    const double g = v - kappa * (commanded_mm - depth);
    const double slope =
        2 * std::numbers::pi * std::sqrt(m.pad_radius_x_mm * m.pad_radius_y_mm) * depth + kappa;
    depth = std::clamp(depth - g / slope, 0.0, commanded_mm);
  }
  return depth;
}

}  // namespace tactile::perception::contact
