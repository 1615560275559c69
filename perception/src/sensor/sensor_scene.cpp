// The feature plates and exploratory procedures of paper 2 (see sensor_scene.hpp).

#include "tactile/perception/sensor_scene.hpp"

#include <cmath>
#include <stdexcept>

namespace tactile::perception {

double SurfaceFeature::surface_mm(double r_mm) const {
  const double a = 0.5 * footprint_mm;
  if (r_mm >= a) return 0.0;
  switch (curvature) {
    case Curvature::planar:
      return height_mm;
    case Curvature::conical:
      return height_mm * (1.0 - r_mm / a);
    case Curvature::spherical: {
      // Spherical cap of base radius a and height |h|: sphere radius R = (a^2 + h^2) / 2|h|.
      const double h = std::abs(height_mm);
      const double radius = (a * a + h * h) / (2 * h);
      const double z = std::sqrt(radius * radius - r_mm * r_mm) - (radius - h);
      return height_mm > 0 ? z : -z;
    }
  }
  return 0.0;
}

std::vector<SurfaceFeature> paper_features() {
  const double footprints_mm[] = {1.25, 2.5, 3.75, 5, 7.5, 10, 15, 20};
  std::vector<SurfaceFeature> features;
  for (Curvature c : {Curvature::planar, Curvature::conical, Curvature::spherical})
    for (double sign : {1.0, -1.0})
      for (double d : footprints_mm) {
        const double h = d <= 3.75 ? 0.5 * d : 2.5;
        features.push_back({c, d, sign * h});
      }
  return features;
}

namespace {
struct ProcedureNames {
  const char* full;
  const char* short_name;
};
ProcedureNames names_of(Procedure p) {
  switch (p) {
    case Procedure::static_contact:
      return {"static", "static"};
    case Procedure::distal_proximal:
      return {"distal-proximal", "dp"};
    case Procedure::radial_ulnar:
      return {"radial-ulnar", "ru"};
    case Procedure::roll:
      return {"roll", "roll"};
  }
  throw std::invalid_argument("unknown exploratory procedure");
}
}  // namespace

std::string procedure_name(Procedure p) {
  return names_of(p).full;
}
std::string procedure_short_name(Procedure p) {
  return names_of(p).short_name;
}

ProcedureKinematics paper_kinematics(Procedure p) {
  ProcedureKinematics k;
  if (p == Procedure::roll) k.contact_angle_deg = 30.0;
  return k;
}

}  // namespace tactile::perception
